#include "pbms/io/h5md_writer.hpp"

#include <algorithm>

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <tuple>

#include "pbms/error.hpp"

namespace pbms {
namespace {

int rank_of(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

// The dataset's rows [offset, offset + n_local) at `frame` (a leading frame
// dimension when dims > 1), `width` values per row, and the memory space of
// as many values.
h5::Handle select_block(hid_t fspace, int dims, hsize_t frame, hsize_t offset, hsize_t n_local,
                        hsize_t width) {
  const hsize_t n = n_local * width;
  h5::Handle mspace(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (n == 0) {
    H5Sselect_none(fspace);
    H5Sselect_none(mspace.id());
    return mspace;
  }
  const hsize_t start[3] = {frame, offset, 0}, count[3] = {1, n_local, width};
  const int skip = dims > 1 ? 0 : 1;
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start + skip, nullptr, count + skip, nullptr);
  return mspace;
}

void write_fixed(hid_t parent, const std::string& name, hid_t mem_type, hid_t file_type,
                 const void* local, hsize_t n_local, hsize_t offset, hsize_t n_total, hid_t dxpl) {
  h5::Handle fspace(H5Screate_simple(1, &n_total, nullptr), H5Sclose);
  h5::Handle ds(H5Dcreate2(parent, name.c_str(), file_type, fspace.id(), H5P_DEFAULT, H5P_DEFAULT,
                           H5P_DEFAULT),
                H5Dclose);
  const h5::Handle mspace = select_block(fspace.id(), 1, 0, offset, n_local, 1);
  H5Dwrite(ds.id(), mem_type, mspace.id(), fspace.id(), dxpl, local);
}

void write_string_array(hid_t obj, const std::string& name, const std::vector<std::string>& v) {
  h5::Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id(), 9);
  std::vector<char> buf(v.size() * 9, 0);
  for (size_t i = 0; i < v.size(); ++i) v[i].copy(&buf[i * 9], 8);
  const hsize_t n = v.size();
  h5::Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  h5::Handle attr(H5Acreate2(obj, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
                  H5Aclose);
  H5Awrite(attr.id(), type.id(), buf.data());
}

}  // namespace

H5mdWriter::H5mdWriter(MPI_Comm comm, const Options& opt, const std::vector<int64_t>& ids,
                       const std::vector<int>& species)
    : comm_(comm),
      rank_(rank_of(comm)),
      opt_(opt),
      rows_(comm, ids),
      blocks_(comm, rows_.total()),
      n_total_(rows_.total()) {
  if (ids.size() != species.size()) throw Error("H5MD: ids and species differ in length");
  blocks_.route(rows_.rows(ids));
  int size = 1;
  MPI_Comm_size(comm, &size);

  file_ = h5::create_truncate(opt.path, comm);
  dxpl_ = h5::Handle(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  if (size > 1) H5Pset_dxpl_mpio(dxpl_.id(), H5FD_MPIO_COLLECTIVE);

  auto h5md = h5::require_group(file_.id(), "h5md");
  h5::write_attribute(h5md.id(), "version", std::vector<int>{1, 1});
  auto author = h5::require_group(h5md.id(), "author");
  h5::write_attribute(author.id(), "name", std::string("PBMS user"));
  auto creator = h5::require_group(h5md.id(), "creator");
  h5::write_attribute(creator.id(), "name", opt.creator);
  h5::write_attribute(creator.id(), "version", opt.creator_version);

  auto all = h5::require_group(file_.id(), "particles/all");
  auto box = h5::require_group(all.id(), "box");
  const int dim = 3;
  {
    const hsize_t one = 1;
    h5::Handle space(H5Screate_simple(1, &one, nullptr), H5Sclose);
    h5::Handle attr(
        H5Acreate2(box.id(), "dimension", H5T_NATIVE_INT, space.id(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose);
    H5Awrite(attr.id(), H5T_NATIVE_INT, &dim);
  }
  std::vector<std::string> boundary;
  for (bool p : opt.periodic) boundary.push_back(p ? "periodic" : "none");
  write_string_array(box.id(), "boundary", boundary);
  const bool metal = opt.metal_units;
  edges_ = make_series(box.id(), "edges", 2, 3, metal ? "Angstrom" : nullptr);
  position_ = make_series(all.id(), "position", 2, n_total_, metal ? "Angstrom" : nullptr);
  if (opt.velocities) {
    velocity_ = make_series(all.id(), "velocity", 2, n_total_, metal ? "Angstrom ps-1" : nullptr);
  }
  if (opt.forces) {
    // Forces stay in metal units, eV/Å, like every PBMS file. MDAnalysis
    // knows no eV-based force unit and refuses a file with one it does not
    // know, so the unit goes into `pbms_unit`, not `unit`; MDAnalysis then
    // reads the file with convert_units=False, which leaves its Å and ps
    // (its own base units) as they are.
    force_ =
        make_series(all.id(), "force", 2, n_total_, metal ? "eV Angstrom-1" : nullptr, "pbms_unit");
  }
  if (opt.internal_energy) {
    internal_energy_ =
        make_series(all.id(), "internal_energy", 1, n_total_, metal ? "eV" : nullptr);
  }

  const auto block_ids = blocks_.to_block(ids.data());
  write_fixed(all.id(), "id", H5T_NATIVE_INT64, H5T_STD_I64LE, block_ids.data(), blocks_.count(),
              blocks_.begin(), n_total_, dxpl_.id());
  const auto block_species = blocks_.to_block(species.data());
  write_fixed(all.id(), "species", H5T_NATIVE_INT, H5T_STD_I32LE, block_species.data(),
              blocks_.count(), blocks_.begin(), n_total_, dxpl_.id());
}

namespace {

// A dataset read whole into doubles (or int64 ids).
template <typename T>
std::vector<T> read_all(hid_t parent, const std::string& name, hid_t type) {
  h5::Handle ds(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose);
  h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
  std::vector<T> out(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id())));
  if (!out.empty() && H5Dread(ds.id(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw Error(fmt::format("cannot read '{}'", name));
  }
  return out;
}

}  // namespace

std::unique_ptr<H5mdWriter> H5mdWriter::reopen(MPI_Comm comm, const Options& opt,
                                               const std::vector<int64_t>& ids, int64_t last_step) {
  // The kept frames are copied into a new file, written as any file is: a
  // file written on another rank count cannot always be appended to in
  // parallel. Rank 0 reads them and passes every particle of each frame.
  const int rank = rank_of(comm);
  const std::string old = opt.path + ".resumed_from";
  std::vector<int64_t> all_ids, steps;
  std::vector<int> species;
  std::vector<double> times, edges;
  std::map<std::string, std::vector<double>> values;  // series -> frames x rows x width
  std::string problem;
  if (rank == 0) {
    try {
      std::filesystem::rename(opt.path, old);
      h5::Handle f(H5Fopen(old.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
      h5::Handle all(H5Gopen2(f.id(), "particles/all", H5P_DEFAULT), H5Gclose);
      all_ids = read_all<int64_t>(all.id(), "id", H5T_NATIVE_INT64);
      species = read_all<int>(all.id(), "species", H5T_NATIVE_INT);
      steps = read_all<int64_t>(all.id(), "position/step", H5T_NATIVE_INT64);
      times = read_all<double>(all.id(), "position/time", H5T_NATIVE_DOUBLE);
      edges = read_all<double>(all.id(), "box/edges/value", H5T_NATIVE_DOUBLE);
      for (const char* name : {"position", "velocity", "force", "internal_energy"}) {
        if (H5Lexists(all.id(), name, H5P_DEFAULT) > 0) {
          values[name] =
              read_all<double>(all.id(), std::string(name) + "/value", H5T_NATIVE_DOUBLE);
        }
      }
    } catch (const std::exception& e) {
      problem = e.what();
    }
  }
  int length = static_cast<int>(problem.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  problem.resize(static_cast<std::size_t>(length));
  MPI_Bcast(problem.data(), length, MPI_CHAR, 0, comm);
  if (!problem.empty()) throw Error(fmt::format("H5MD file '{}': {}", opt.path, problem));
  long long total = static_cast<long long>(all_ids.size()), keep = 0;
  while (keep < static_cast<long long>(steps.size()) &&
         steps[static_cast<std::size_t>(keep)] <= last_step) {
    ++keep;
  }
  MPI_Bcast(&total, 1, MPI_LONG_LONG, 0, comm);
  MPI_Bcast(&keep, 1, MPI_LONG_LONG, 0, comm);
  long long mine = static_cast<long long>(ids.size()), everyone = 0;
  MPI_Allreduce(&mine, &everyone, 1, MPI_LONG_LONG, MPI_SUM, comm);
  if (everyone != total) {
    throw Error(
        fmt::format("H5MD file '{}' holds {} particles, this run {}", opt.path, total, everyone));
  }
  auto w = std::make_unique<H5mdWriter>(comm, opt, all_ids, species);
  const auto n = static_cast<std::size_t>(total);
  const auto frame = [&](const char* name, std::size_t width, long long k) {
    if (rank != 0 || values.count(name) == 0) return std::vector<double>{};
    const auto& v = values[name];
    const auto begin =
        v.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(k) * n * width);
    return std::vector<double>(begin, begin + static_cast<std::ptrdiff_t>(n * width));
  };
  for (long long k = 0; k < keep; ++k) {
    std::array<double, 3> box{};
    if (rank == 0) {
      for (std::size_t a = 0; a < 3; ++a) box[a] = edges[static_cast<std::size_t>(k) * 9 + 4 * a];
    }
    w->write_frame(rank == 0 ? steps[static_cast<std::size_t>(k)] : 0,
                   rank == 0 ? times[static_cast<std::size_t>(k)] : 0.0, box,
                   rank == 0 ? all_ids : std::vector<int64_t>{}, frame("position", 3, k),
                   frame("velocity", 3, k), frame("force", 3, k), frame("internal_energy", 1, k));
  }
  if (rank == 0) std::filesystem::remove(old);
  return w;
}

H5mdWriter::TimeSeries H5mdWriter::make_series(hid_t parent, const std::string& name, int rank_dims,
                                               hsize_t n, const char* unit,
                                               const char* unit_attribute) {
  TimeSeries ts;
  ts.group = h5::require_group(parent, name);
  auto make = [&](const char* dname, int nd, const hsize_t* dims, const hsize_t* chunk,
                  hid_t type) {
    std::vector<hsize_t> maxdims(dims, dims + nd);
    maxdims[0] = H5S_UNLIMITED;
    h5::Handle space(H5Screate_simple(nd, dims, maxdims.data()), H5Sclose);
    h5::Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
    H5Pset_chunk(dcpl.id(), nd, chunk);
    return h5::Handle(
        H5Dcreate2(ts.group.id(), dname, type, space.id(), H5P_DEFAULT, dcpl.id(), H5P_DEFAULT),
        H5Dclose);
  };
  const hsize_t zero1[1] = {0}, chunk1[1] = {64};
  ts.step = make("step", 1, zero1, chunk1, H5T_STD_I64LE);
  ts.time = make("time", 1, zero1, chunk1, H5T_IEEE_F64LE);
  if (unit != nullptr) h5::write_vlen_attribute(ts.time.id(), "unit", "ps");
  if (rank_dims == 1) {
    // Small rows (few particles, or the 3 x 3 box edges below) batch frames
    // per chunk; larger ones take one frame per chunk, capped. HDF5 refuses
    // zero-sized chunk dimensions, hence the floor of 1.
    const hsize_t width = std::max<hsize_t>(1, std::min<hsize_t>(n, 65536));
    const hsize_t dims[2] = {0, n}, chunk[2] = {n <= 64 ? hsize_t{16} : hsize_t{1}, width};
    ts.value = make("value", 2, dims, chunk, H5T_IEEE_F64LE);
  } else {
    const hsize_t dims[3] = {0, n, 3};
    const hsize_t chunk[3] = {n <= 64 ? hsize_t{16} : hsize_t{1},
                              std::max<hsize_t>(1, std::min<hsize_t>(n, 65536)), 3};
    ts.value = make("value", 3, dims, chunk, H5T_IEEE_F64LE);
  }
  if (unit != nullptr) h5::write_vlen_attribute(ts.value.id(), unit_attribute, unit);
  return ts;
}

void H5mdWriter::append(TimeSeries& ts, int64_t step, double time, const std::vector<double>& data,
                        hsize_t n_local, hsize_t offset, hsize_t n_total, hsize_t width) {
  const hsize_t t = static_cast<hsize_t>(frames_);
  const hsize_t new1[1] = {t + 1};
  H5Dset_extent(ts.step.id(), new1);
  H5Dset_extent(ts.time.id(), new1);
  for (auto [ds, type, ptr] : {std::tuple{ts.step.id(), H5T_NATIVE_INT64, (const void*)&step},
                               std::tuple{ts.time.id(), H5T_NATIVE_DOUBLE, (const void*)&time}}) {
    h5::Handle fspace(H5Dget_space(ds), H5Sclose);
    const hsize_t one = 1;
    h5::Handle mspace(H5Screate_simple(1, &one, nullptr), H5Sclose);
    H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, &t, nullptr, &one, nullptr);
    if (rank_ != 0) {
      H5Sselect_none(fspace.id());
      H5Sselect_none(mspace.id());
    }
    H5Dwrite(ds, type, mspace.id(), fspace.id(), dxpl_.id(), ptr);
  }
  const bool vec3 = width == 3;
  if (vec3) {
    const hsize_t dims[3] = {t + 1, n_total, 3};
    H5Dset_extent(ts.value.id(), dims);
  } else {
    const hsize_t dims[2] = {t + 1, n_total};
    H5Dset_extent(ts.value.id(), dims);
  }
  h5::Handle fspace(H5Dget_space(ts.value.id()), H5Sclose);
  const h5::Handle mspace = select_block(fspace.id(), vec3 ? 3 : 2, t, offset, n_local, width);
  H5Dwrite(ts.value.id(), H5T_NATIVE_DOUBLE, mspace.id(), fspace.id(), dxpl_.id(), data.data());
}

void H5mdWriter::write_frame(int64_t step, double time_ps, const std::array<double, 3>& box_edges,
                             const std::vector<int64_t>& ids, const std::vector<double>& positions,
                             const std::vector<double>& velocities,
                             const std::vector<double>& forces,
                             const std::vector<double>& internal_energy) {
  // All sizes are checked, on every rank together, before the first append,
  // so that a refused frame leaves no series one frame longer than the
  // others and no rank waiting in a collective write.
  const std::size_t n = ids.size();
  const char* wrong = positions.size() != 3 * n                             ? "position"
                      : opt_.velocities && velocities.size() != 3 * n       ? "velocity"
                      : opt_.forces && forces.size() != 3 * n               ? "force"
                      : opt_.internal_energy && internal_energy.size() != n ? "internal energy"
                                                                            : nullptr;
  int any_wrong = wrong != nullptr ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &any_wrong, 1, MPI_INT, MPI_MAX, comm_);
  if (any_wrong != 0) {
    throw Error(fmt::format("H5MD: {} array has the wrong size", wrong ? wrong : "another rank's"));
  }
  blocks_.route(rows_.rows(ids));
  const std::array<double, 9> matrix = {box_edges[0], 0.0, 0.0, 0.0,         box_edges[1],
                                        0.0,          0.0, 0.0, box_edges[2]};
  append(edges_, step, time_ps, {matrix.begin(), matrix.end()}, rank_ == 0 ? 3 : 0, 0, 3, 3);
  const hsize_t n_local = blocks_.count(), offset = blocks_.begin();
  append(position_, step, time_ps, blocks_.to_block(positions.data(), 3), n_local, offset, n_total_,
         3);
  if (opt_.velocities) {
    append(velocity_, step, time_ps, blocks_.to_block(velocities.data(), 3), n_local, offset,
           n_total_, 3);
  }
  if (opt_.forces) {
    append(force_, step, time_ps, blocks_.to_block(forces.data(), 3), n_local, offset, n_total_, 3);
  }
  if (opt_.internal_energy) {
    append(internal_energy_, step, time_ps, blocks_.to_block(internal_energy.data(), 1), n_local,
           offset, n_total_, 1);
  }
  ++frames_;
  H5Fflush(file_.id(), H5F_SCOPE_GLOBAL);
}

}  // namespace pbms
