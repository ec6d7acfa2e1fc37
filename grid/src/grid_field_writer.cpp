#include "pbms/grid/grid_field_writer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms {
namespace {

// Throws on every rank when any rank has an error, with the message of the
// lowest such rank: a rank that threw alone would leave the others waiting
// in the next collective call.
void throw_if_any(MPI_Comm comm, const std::string& error) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = error.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  std::string message = error;
  int n = static_cast<int>(message.size());
  MPI_Bcast(&n, 1, MPI_INT, first, comm);
  message.resize(static_cast<size_t>(n));
  MPI_Bcast(message.data(), n, MPI_CHAR, first, comm);
  if (size > 1) message += fmt::format(" (rank {})", first);
  throw Error(message);
}

// HDF5 requires the same metadata calls with the same arguments on every
// rank, and silently corrupts the file otherwise; comparing a hash of them
// costs one small reduction.
void require_same_everywhere(MPI_Comm comm, std::uint64_t hash, const std::string& what) {
  // max(~h) == ~min(h), so one MAX reduction yields both extremes.
  const std::uint64_t mine[2] = {hash, ~hash};
  std::uint64_t all[2] = {0, 0};
  MPI_Allreduce(mine, all, 2, MPI_UINT64_T, MPI_MAX, comm);
  if (all[0] != ~all[1]) throw Error(what);
}

class Fnv1a {
 public:
  Fnv1a& add(std::string_view s) {
    for (const char c : s) step(static_cast<unsigned char>(c));
    step(0);  // so that ("ab", "c") and ("a", "bc") differ
    return *this;
  }
  Fnv1a& add(std::uint64_t v) {
    for (int b = 0; b < 8; ++b) step(static_cast<unsigned char>(v >> (8 * b)));
    return *this;
  }
  Fnv1a& add(double v) { return add(std::bit_cast<std::uint64_t>(v)); }
  [[nodiscard]] std::uint64_t value() const { return h_; }

 private:
  void step(unsigned char c) { h_ = (h_ ^ c) * 0x100000001b3ULL; }
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

std::string describe(const grid::NodeBox& b) {
  return fmt::format("[{},{})x[{},{})x[{},{})", b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2],
                     b.hi[2]);
}

// Every rank computes the same verdict from the same gathered boxes, so all
// of them throw together without a further reduction.
void require_tiling(MPI_Comm comm, const grid::RegularGrid& grid, const grid::NodeBox& owned,
                    const std::string& context) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int mine[6] = {owned.lo[0], owned.lo[1], owned.lo[2],
                       owned.hi[0], owned.hi[1], owned.hi[2]};
  std::vector<int> all(6 * static_cast<size_t>(size));
  MPI_Allgather(mine, 6, MPI_INT, all.data(), 6, MPI_INT, comm);
  std::vector<std::pair<int, grid::NodeBox>> boxes;
  std::int64_t covered = 0;
  for (int r = 0; r < size; ++r) {
    const int* v = &all[6 * static_cast<size_t>(r)];
    const grid::NodeBox b{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (b.empty()) continue;
    covered += b.count();
    boxes.emplace_back(r, b);
  }
  // Quadratic in the ranks, but run once; thousands of ranks take well
  // under a second.
  for (size_t a = 0; a < boxes.size(); ++a) {
    for (size_t b = a + 1; b < boxes.size(); ++b) {
      if (!boxes[a].second.intersected(boxes[b].second).empty()) {
        throw Error(fmt::format("{}: ranks {} and {} both own nodes of {}", context, boxes[a].first,
                                boxes[b].first,
                                describe(boxes[a].second.intersected(boxes[b].second))));
      }
    }
  }
  if (covered != grid.node_count()) {
    throw Error(fmt::format("{}: the ranks' node boxes cover {} of the grid's {} nodes", context,
                            covered, grid.node_count()));
  }
}

bool valid_field_name(std::string_view name) {
  if (name.empty()) return false;
  const auto is_alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (!is_alpha(name[0]) && name[0] != '_') return false;
  for (const char c : name) {
    const bool ok = is_alpha(c) || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string step_group(std::int64_t step) {
  return fmt::format("step_{}", step);
}

void write_doubles_attribute(hid_t obj, const std::string& name, const std::vector<double>& v) {
  const hsize_t n = v.size();
  h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  h5::Handle attr(
      H5Acreate2(obj, name.c_str(), H5T_IEEE_F64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, v.data());
}

void write_int64_attribute(hid_t obj, const std::string& name, std::int64_t value) {
  h5::Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  h5::Handle attr(
      H5Acreate2(obj, name.c_str(), H5T_STD_I64LE, space.id(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  H5Awrite(attr.id(), H5T_NATIVE_INT64, &value);
}

}  // namespace

GridFieldWriter::GridFieldWriter(MPI_Comm comm, const std::string& base,
                                 const grid::RegularGrid& grid, const grid::NodeBox& owned)
    : GridFieldWriter(comm, base, grid, owned, NoFileYet{}) {
  file_ = h5::create_truncate(h5_path_, comm);
  make_transfer_list();

  // For readers without XDMF (h5py, MATLAB): the geometry, in x, y, z order.
  const auto& o = grid.origin();
  const auto n = grid.nodes_per_axis();
  write_doubles_attribute(file_.id(), "origin", {o[0], o[1], o[2]});
  h5::write_attribute(file_.id(), "cell_size", grid.cell_size());
  h5::write_attribute(file_.id(), "nodes_per_axis", std::vector<int>{n[0], n[1], n[2]});
  h5::write_attribute(file_.id(), "layout",
                      std::string("/step_<n>/<field>, shape (nz, ny, nx) or (nz, ny, nx, 3); "
                                  "node (i, j, k) at [k, j, i]"));

  // A description left from an earlier run would point into the file just
  // truncated.
  std::string error;
  if (rank_ == 0) {
    std::error_code ec;
    std::filesystem::remove(xdmf_path_, ec);
    if (ec) error = fmt::format("cannot remove stale '{}': {}", xdmf_path_, ec.message());
  }
  throw_if_any(comm, error);
}

// Checked, with no file open yet: the public constructor creates one,
// reopen() opens the existing one.
GridFieldWriter::GridFieldWriter(MPI_Comm comm, const std::string& base,
                                 const grid::RegularGrid& grid, const grid::NodeBox& owned,
                                 NoFileYet /*unused*/)
    : comm_(comm),
      grid_(grid),
      owned_(owned),
      h5_path_(base + ".h5"),
      xdmf_path_(base + ".xdmf"),
      h5_name_(std::filesystem::path(h5_path_).filename().string()) {
  MPI_Comm_rank(comm, &rank_);
  check_arguments(base);
}

void GridFieldWriter::check_arguments(const std::string& base) const {
  std::string error;
  if (std::filesystem::path(base).filename().empty()) {
    error = fmt::format("grid output: base path '{}' names a directory, not a file", base);
  } else if (h5_name_.find_first_of(": \t\n") != std::string::npos) {
    // The XDMF reference "file.h5:/path" is split at the colon and taken
    // apart at white space.
    error =
        fmt::format("grid output: file name '{}' must not contain ':' or white space", h5_name_);
  } else if (!owned_.empty() && owned_.intersected(grid_.node_box()) != owned_) {
    error = fmt::format("{}: owned node box {} reaches outside the grid's nodes {}", h5_path_,
                        describe(owned_), describe(grid_.node_box()));
  }
  throw_if_any(comm_, error);

  Fnv1a same;
  same.add(base).add(grid_.cell_size());
  for (int d = 0; d < 3; ++d) {
    same.add(grid_.origin()[d]).add(static_cast<std::uint64_t>(grid_.cells()[d]));
  }
  require_same_everywhere(
      comm_, same.value(),
      fmt::format("{}: ranks disagree on the output path or the grid", h5_path_));
  require_tiling(comm_, grid_, owned_, h5_path_);
}

void GridFieldWriter::make_transfer_list() {
  dxpl_ = h5::Handle(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  int size = 1;
  MPI_Comm_size(comm_, &size);
  if (size > 1) H5Pset_dxpl_mpio(dxpl_.id(), H5FD_MPIO_COLLECTIVE);
}

std::unique_ptr<GridFieldWriter> GridFieldWriter::reopen(MPI_Comm comm, const std::string& base,
                                                         const grid::RegularGrid& grid,
                                                         const grid::NodeBox& owned,
                                                         std::int64_t last_step) {
  std::unique_ptr<GridFieldWriter> w(new GridFieldWriter(comm, base, grid, owned, NoFileYet{}));
  FramesOnFile frames;
  std::string error;
  if (w->rank_ == 0) {
    try {
      frames = w->frames_on_file(last_step);
    } catch (const std::exception& e) {
      error = fmt::format("{}: cannot go on with it: {}", w->h5_path_, e.what());
    }
  }
  throw_if_any(comm, error);
  // Every rank makes the same metadata calls: the steps travel from rank 0.
  for (auto* steps : {&frames.kept, &frames.dropped}) {
    long long n = static_cast<long long>(steps->size());
    MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, comm);
    steps->resize(static_cast<std::size_t>(n));
    MPI_Bcast(steps->data(), static_cast<int>(n), MPI_INT64_T, 0, comm);
  }
  w->file_ = h5::open_read_write(w->h5_path_, comm);
  w->make_transfer_list();
  for (const std::int64_t step : frames.dropped) {
    h5::delete_link_if_exists(w->file_.id(), step_group(step));
  }
  w->steps_.insert(frames.kept.begin(), frames.kept.end());
  w->frames_ = static_cast<std::int64_t>(frames.kept.size());
  w->frame_xml_ = std::move(frames.xml);
  error.clear();
  if (w->rank_ == 0) {
    try {
      w->write_xdmf();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  throw_if_any(comm, error);
  return w;
}

GridFieldWriter::FramesOnFile GridFieldWriter::frames_on_file(std::int64_t last_step) const {
  h5::Handle f(H5Fopen(h5_path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (f.id() < 0) throw Error("cannot open it to read");
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  H5Literate(f.id(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect, &names);
  std::vector<std::pair<std::int64_t, std::string>> frames;  // step, group
  for (const auto& name : names) {
    if (name.rfind("step_", 0) == 0) frames.emplace_back(std::stoll(name.substr(5)), name);
  }
  std::sort(frames.begin(), frames.end());
  FramesOnFile out;
  for (const auto& [step, name] : frames) {
    if (step > last_step) {
      out.dropped.push_back(step);
      continue;
    }
    h5::Handle g(H5Gopen2(f.id(), name.c_str(), H5P_DEFAULT), H5Gclose);
    double time = 0.0;
    h5::Handle t(H5Aopen(g.id(), "time", H5P_DEFAULT), H5Aclose);
    H5Aread(t.id(), H5T_NATIVE_DOUBLE, &time);
    std::vector<std::string> datasets;
    H5Literate(g.id(), H5_INDEX_NAME, H5_ITER_NATIVE, nullptr, collect, &datasets);
    std::vector<Field> fields;
    for (const auto& d : datasets) {
      h5::Handle ds(H5Dopen2(g.id(), d.c_str(), H5P_DEFAULT), H5Dclose);
      h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
      Field field{d, h5::read_string_attribute(ds.id(), "unit"),
                  H5Sget_simple_extent_ndims(space.id()) == 4 ? 3 : 1, nullptr};
      fields.push_back(std::move(field));
    }
    out.kept.push_back(step);
    out.xml.push_back(frame_xml(step, time, fields));
  }
  return out;
}

void GridFieldWriter::write_frame(std::int64_t step, double time,
                                  const std::vector<Field>& fields) {
  check_frame(step, time, fields);
  auto group = h5::require_group(file_.id(), step_group(step));
  // Taken even if a write below fails: the group exists now, and a retry of
  // the step should be refused with a message, not fail in HDF5.
  steps_.insert(step);
  write_int64_attribute(group.id(), "step", step);
  h5::write_attribute(group.id(), "time", time);
  std::string failed = write_datasets(group.id(), step, fields);
  // Flushing before the XDMF names the frame: a crash afterwards leaves a
  // readable file holding every frame the XDMF lists.
  if (H5Fflush(file_.id(), H5F_SCOPE_GLOBAL) < 0 && failed.empty()) {
    failed = fmt::format("{}: flushing step {} failed", h5_path_, step);
  }
  throw_if_any(comm_, failed);
  publish_frame(step, time, fields);
}

void GridFieldWriter::check_frame(std::int64_t step, double time,
                                  const std::vector<Field>& fields) const {
  std::string error = frame_error(step, time, fields);
  if (!error.empty()) error = fmt::format("{}: step {}: {}", h5_path_, step, error);
  throw_if_any(comm_, error);

  Fnv1a same;
  same.add(static_cast<std::uint64_t>(step)).add(time);
  for (const auto& f : fields) {
    same.add(f.name).add(f.unit).add(static_cast<std::uint64_t>(f.components));
  }
  require_same_everywhere(
      comm_, same.value(),
      fmt::format("{}: ranks disagree on the step, time or fields (names, units, components) of "
                  "step {}",
                  h5_path_, step));
}

std::string GridFieldWriter::frame_error(std::int64_t step, double time,
                                         const std::vector<Field>& fields) const {
  std::string error;
  std::set<std::string> names;
  if (!std::isfinite(time)) {
    error = fmt::format("time {} is not a finite number", time);
  } else if (steps_.count(step) > 0) {
    error = "the step was already written";
  }
  for (const auto& f : fields) {
    if (!error.empty()) break;
    if (!valid_field_name(f.name)) {
      error = fmt::format(
          "field name '{}' is not one of letters, digits, '_', '-', '.' starting with a letter "
          "or '_'",
          f.name);
    } else if (!names.insert(f.name).second) {
      error = fmt::format("field '{}' is given twice", f.name);
    } else if (f.components != 1 && f.components != 3) {
      error =
          fmt::format("field '{}' has {} components; 1 or 3 are supported", f.name, f.components);
    } else if (f.data == nullptr && !owned_.empty()) {
      error = fmt::format("field '{}' has no data", f.name);
    }
  }
  return error;
}

std::string GridFieldWriter::write_datasets(hid_t group, std::int64_t step,
                                            const std::vector<Field>& fields) const {
  const auto n = grid_.nodes_per_axis();
  const auto e = owned_.extent();
  const auto& lo = owned_.lo;
  h5::Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  // The boxes tile the grid, so every value is written once; a fill pass
  // would only double the I/O (parallel HDF5 allocates, and fills, early).
  H5Pset_fill_time(dcpl.id(), H5D_FILL_TIME_NEVER);

  const auto u = [](int v) { return static_cast<hsize_t>(v); };
  std::string failed;
  for (const auto& f : fields) {
    const int rank_dims = f.components == 3 ? 4 : 3;
    const hsize_t dims[4] = {u(n[2]), u(n[1]), u(n[0]), 3};
    const hsize_t start[4] = {u(lo[2]), u(lo[1]), u(lo[0]), 0};
    const hsize_t count[4] = {u(e[2]), u(e[1]), u(e[0]), 3};
    h5::Handle fspace(H5Screate_simple(rank_dims, dims, nullptr), H5Sclose);
    h5::Handle ds(H5Dcreate2(group, f.name.c_str(), H5T_IEEE_F64LE, fspace.id(), H5P_DEFAULT,
                             dcpl.id(), H5P_DEFAULT),
                  H5Dclose);
    // The owned block in memory, i fastest then components, is exactly a
    // C-order (ez, ey, ex[, 3]) array, so no repacking is needed.
    h5::Handle mspace(H5Screate_simple(rank_dims, count, nullptr), H5Sclose);
    if (owned_.empty()) {
      H5Sselect_none(fspace.id());
      H5Sselect_none(mspace.id());
    } else {
      H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start, nullptr, count, nullptr);
    }
    // An empty rank still joins the collective write; HDF5 wants a buffer.
    static const double nothing = 0.0;
    const double* data = f.data != nullptr ? f.data : &nothing;
    if (H5Dwrite(ds.id(), H5T_NATIVE_DOUBLE, mspace.id(), fspace.id(), dxpl_.id(), data) < 0 &&
        failed.empty()) {
      failed = fmt::format("{}: writing field '{}' of step {} failed", h5_path_, f.name, step);
    }
    h5::write_attribute(ds.id(), "unit", f.unit);
  }
  return failed;
}

void GridFieldWriter::publish_frame(std::int64_t step, double time,
                                    const std::vector<Field>& fields) {
  ++frames_;
  if (rank_ == 0) frame_xml_.push_back(frame_xml(step, time, fields));
  std::string xdmf_error;
  if (rank_ == 0) {
    try {
      write_xdmf();
    } catch (const std::exception& ex) {
      xdmf_error = ex.what();
    }
  }
  // The frame is in the HDF5 file either way; the next frame's XDMF lists it.
  throw_if_any(comm_, xdmf_error);
}

std::string GridFieldWriter::frame_xml(std::int64_t step, double time,
                                       const std::vector<Field>& fields) const {
  const auto n = grid_.nodes_per_axis();
  const auto& o = grid_.origin();
  const double h = grid_.cell_size();
  // XDMF orders every triple slowest axis first: z, y, x.
  const std::string dims = fmt::format("{} {} {}", n[2], n[1], n[0]);
  std::string s;
  s += fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n", step_group(step));
  s += fmt::format("        <Time Value=\"{}\"/>\n", time);
  s += fmt::format("        <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"{}\"/>\n", dims);
  s += "        <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n";
  s += fmt::format(
      "          <DataItem Name=\"Origin\" Dimensions=\"3\" NumberType=\"Float\" "
      "Precision=\"8\" Format=\"XML\">{} {} {}</DataItem>\n",
      o[2], o[1], o[0]);
  s += fmt::format(
      "          <DataItem Name=\"Spacing\" Dimensions=\"3\" NumberType=\"Float\" "
      "Precision=\"8\" Format=\"XML\">{} {} {}</DataItem>\n",
      h, h, h);
  s += "        </Geometry>\n";
  for (const auto& f : fields) {
    const bool vector = f.components == 3;
    s += fmt::format("        <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">\n",
                     f.name, vector ? "Vector" : "Scalar");
    s += fmt::format("          <Information Name=\"unit\" Value=\"{}\"/>\n", xml_escape(f.unit));
    s += fmt::format(
        "          <DataItem Dimensions=\"{}{}\" NumberType=\"Float\" Precision=\"8\" "
        "Format=\"HDF\">{}:/{}/{}</DataItem>\n",
        dims, vector ? " 3" : "", xml_escape(h5_name_), step_group(step), f.name);
    s += "        </Attribute>\n";
  }
  s += "      </Grid>\n";
  return s;
}

void GridFieldWriter::write_xdmf() const {
  // Rename within one directory is atomic, so a reader sees the old file or
  // the new one, never a mixture.
  const std::string tmp = xdmf_path_ + ".tmp";
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<Xdmf Version=\"3.0\">\n"
        << "  <Domain>\n"
        << fmt::format(
               "    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Temporal\">\n",
               xml_escape(std::filesystem::path(h5_name_).stem().string()));
    for (const auto& frame : frame_xml_) out << frame;
    out << "    </Grid>\n"
        << "  </Domain>\n"
        << "</Xdmf>\n";
    out.close();
    if (!out) throw Error(fmt::format("cannot write '{}'", tmp));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, xdmf_path_, ec);
  if (ec) throw Error(fmt::format("cannot rename '{}' to '{}': {}", tmp, xdmf_path_, ec.message()));
}

}  // namespace pbms
