#include "pbms/io/h5md_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pbms/error.hpp"
#include "pbms/io/hdf5.hpp"

namespace pbms {
namespace {

std::string shape_of(const std::vector<hsize_t>& dims) {
  std::string s = "(";
  for (size_t i = 0; i < dims.size(); ++i) s += fmt::format("{}{}", i ? ", " : "", dims[i]);
  return s + ")";
}

std::vector<hsize_t> dims_of(hid_t ds) {
  h5::Handle space(H5Dget_space(ds), H5Sclose);
  const int nd = H5Sget_simple_extent_ndims(space.id());
  std::vector<hsize_t> dims(static_cast<size_t>(std::max(nd, 0)));
  if (nd > 0) H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
  return dims;
}

// A time series (group with step, time and value) or a fixed dataset;
// both are H5MD elements.
struct Element {
  std::string where;  // path in the file, for messages
  h5::Handle value;
  bool timed = false;
  std::vector<std::int64_t> steps;  // one per stored frame, when timed
  h5::Handle time;                  // absent (id -1) when the file has none
};

class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {
    if (!std::filesystem::exists(path_)) fail("no such file");
    hid_t f = -1;
    H5E_BEGIN_TRY {
      f = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    }
    H5E_END_TRY;
    if (f < 0) fail("cannot open as an HDF5 file");
    file_ = h5::Handle(f, H5Fclose);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(fmt::format("{}: {}", path_, what));
  }

  [[nodiscard]] hid_t file() const { return file_.id(); }

  // Checks each component in turn: H5Lexists fails, rather than answering
  // no, when an intermediate group is missing.
  bool exists(const std::string& where) const {
    size_t pos = 0;
    bool ok = true;
    H5E_BEGIN_TRY {
      while (ok) {
        pos = where.find('/', pos + 1);
        const std::string prefix = where.substr(0, pos);
        ok = H5Lexists(file_.id(), prefix.c_str(), H5P_DEFAULT) > 0;
        if (pos == std::string::npos) break;
      }
    }
    H5E_END_TRY;
    return ok;
  }

  h5::Handle open(const std::string& where) const {
    if (!exists(where)) fail(fmt::format("missing '{}'", where));
    return h5::Handle(H5Oopen(file_.id(), where.c_str(), H5P_DEFAULT), H5Oclose);
  }

  h5::Handle open_dataset(const std::string& where) const {
    if (!exists(where)) fail(fmt::format("missing dataset '{}'", where));
    if (!is_dataset(where)) fail(fmt::format("'{}' is not a dataset", where));
    return h5::Handle(H5Dopen2(file_.id(), where.c_str(), H5P_DEFAULT), H5Dclose);
  }

  bool is_dataset(const std::string& where) const {
    h5::Handle obj = open(where);
    return H5Iget_type(obj.id()) == H5I_DATASET;
  }

  std::optional<Element> element(const std::string& where) const {
    if (!exists(where)) return std::nullopt;
    Element e;
    e.where = where;
    if (is_dataset(where)) {
      e.value = open_dataset(where);
      return e;
    }
    e.timed = true;
    e.value = open_dataset(where + "/value");
    const auto vdims = dims_of(e.value.id());
    if (vdims.empty()) fail(fmt::format("'{}/value' has no frame axis", where));
    e.steps = counters<std::int64_t>(where + "/step", H5T_NATIVE_INT64, vdims[0]);
    // A writer that stopped mid-frame may have extended step before value.
    hsize_t frames = std::min<hsize_t>(vdims[0], e.steps.size());
    if (exists(where + "/time")) {
      e.time = open_dataset(where + "/time");
      const auto tdims = dims_of(e.time.id());
      if (!tdims.empty()) frames = std::min(frames, tdims[0]);
    }
    e.steps.resize(frames);
    return e;
  }

  // H5MD 1.1 lets step and time be a scalar increment (plus an optional
  // `offset` attribute) instead of one entry per frame.
  template <class T>
  std::vector<T> counters(const std::string& where, hid_t mem_type, hsize_t frames) const {
    h5::Handle ds = open_dataset(where);
    const auto dims = dims_of(ds.id());
    if (dims.size() > 1) fail(fmt::format("'{}' has shape {}", where, shape_of(dims)));
    if (dims.size() == 1) {
      std::vector<T> v(dims[0]);
      if (!v.empty()) H5Dread(ds.id(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
      return v;
    }
    T increment{}, offset{};
    H5Dread(ds.id(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &increment);
    if (H5Aexists(ds.id(), "offset") > 0) {
      h5::Handle attr(H5Aopen(ds.id(), "offset", H5P_DEFAULT), H5Aclose);
      H5Aread(attr.id(), mem_type, &offset);
    }
    std::vector<T> v(frames);
    for (hsize_t i = 0; i < frames; ++i) v[i] = offset + static_cast<T>(i) * increment;
    return v;
  }

  double time_of(const Element& e, hsize_t frame) const {
    if (e.time.id() < 0) return std::numeric_limits<double>::quiet_NaN();
    return counters<double>(e.where + "/time", H5T_NATIVE_DOUBLE, frame + 1).at(frame);
  }

  // The stored frame of `e` at `step`, or nullopt.
  static std::optional<hsize_t> frame_at(const Element& e, std::int64_t step) {
    for (size_t j = e.steps.size(); j-- > 0;) {
      if (e.steps[j] == step) return j;
    }
    return std::nullopt;
  }

  // One frame (or the whole of a fixed dataset) of per-frame shape `shape`.
  template <class T>
  std::vector<T> read(const Element& e, hid_t mem_type, std::optional<hsize_t> frame,
                      const std::vector<hsize_t>& shape) const {
    const auto dims = dims_of(e.value.id());
    const size_t lead = e.timed ? 1 : 0;
    std::vector<hsize_t> want;
    if (e.timed) want.push_back(dims.empty() ? 0 : dims[0]);
    want.insert(want.end(), shape.begin(), shape.end());
    if (dims != want) {
      const std::string name = e.timed ? e.where + "/value" : e.where;
      std::string expected = e.timed ? "(frames" : "(";
      for (size_t i = 0; i < shape.size(); ++i) {
        expected += fmt::format("{}{}", (i || e.timed) ? ", " : "", shape[i]);
      }
      fail(fmt::format("'{}' has shape {}, expected {})", name, shape_of(dims), expected));
    }
    hsize_t count = 1;
    for (hsize_t d : shape) count *= d;
    std::vector<T> out(count);
    if (count == 0) return out;
    h5::Handle fspace(H5Dget_space(e.value.id()), H5Sclose);
    if (lead == 1) {
      std::vector<hsize_t> start(dims.size(), 0), cnt = dims;
      start[0] = *frame;
      cnt[0] = 1;
      H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, start.data(), nullptr, cnt.data(), nullptr);
    }
    h5::Handle mspace(H5Screate_simple(1, &count, nullptr), H5Sclose);
    if (H5Dread(e.value.id(), mem_type, mspace.id(), fspace.id(), H5P_DEFAULT, out.data()) < 0) {
      fail(fmt::format("cannot read '{}'", e.where));
    }
    return out;
  }

  std::vector<std::string> string_attribute(const std::string& where,
                                            const std::string& name) const {
    h5::Handle obj = open(where);
    if (H5Aexists(obj.id(), name.c_str()) <= 0) {
      fail(fmt::format("'{}' has no '{}' attribute", where, name));
    }
    h5::Handle attr(H5Aopen(obj.id(), name.c_str(), H5P_DEFAULT), H5Aclose);
    h5::Handle ftype(H5Aget_type(attr.id()), H5Tclose);
    if (H5Tget_class(ftype.id()) != H5T_STRING) {
      fail(fmt::format("attribute '{}' of '{}' is not a string", name, where));
    }
    h5::Handle space(H5Aget_space(attr.id()), H5Sclose);
    const auto n = static_cast<size_t>(H5Sget_simple_extent_npoints(space.id()));
    std::vector<std::string> out;
    if (H5Tis_variable_str(ftype.id()) > 0) {
      h5::Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
      H5Tset_size(mtype.id(), H5T_VARIABLE);
      std::vector<char*> buf(n, nullptr);
      H5Aread(attr.id(), mtype.id(), buf.data());
      for (char* s : buf) out.emplace_back(s ? s : "");
      H5Dvlen_reclaim(mtype.id(), space.id(), H5P_DEFAULT, buf.data());
    } else {
      // Read with the file's own type, so that no padding conversion cuts
      // a string written without room for its terminator (ch5md does so).
      const size_t size = H5Tget_size(ftype.id());
      std::vector<char> buf(n * size);
      H5Aread(attr.id(), ftype.id(), buf.data());
      for (size_t i = 0; i < n; ++i) {
        std::string s(&buf[i * size], size);
        s = s.substr(0, s.find('\0'));
        s.erase(s.find_last_not_of(' ') + 1);
        out.push_back(s);
      }
    }
    return out;
  }

 private:
  std::string path_;
  h5::Handle file_;
};

herr_t collect_group(hid_t parent, const char* name, const H5L_info_t*, void* data) {
  const hid_t obj = H5Oopen(parent, name, H5P_DEFAULT);
  if (obj < 0) return 0;
  if (H5Iget_type(obj) == H5I_GROUP)
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  H5Oclose(obj);
  return 0;
}

std::string pick_group(const Reader& r, const std::string& requested) {
  if (!r.exists("particles")) r.fail("missing group 'particles' (not an H5MD particles file)");
  h5::Handle particles(H5Gopen2(r.file(), "particles", H5P_DEFAULT), H5Gclose);
  std::vector<std::string> names;
  hsize_t idx = 0;
  H5Literate(particles.id(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect_group, &names);
  if (names.empty()) r.fail("group 'particles' holds no particles group");
  if (requested.empty()) return names.front();
  if (std::find(names.begin(), names.end(), requested) == names.end()) {
    r.fail(fmt::format("missing group 'particles/{}' (the file has: {})", requested,
                       fmt::join(names, ", ")));
  }
  return requested;
}

bool written_by_lammps(const Reader& r) {
  if (!r.exists("h5md/creator")) return false;
  h5::Handle creator = r.open("h5md/creator");
  if (H5Aexists(creator.id(), "name") <= 0) return false;
  auto name = r.string_attribute("h5md/creator", "name").at(0);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name == "lammps";
}

std::vector<std::array<double, 3>> as_triples(const std::vector<double>& flat) {
  std::vector<std::array<double, 3>> out(flat.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  return out;
}

// The frame of `e` at `step`; nullopt for a fixed dataset.
std::optional<hsize_t> frame_of(const Reader& r, const Element& e, std::int64_t step) {
  if (!e.timed) return std::nullopt;
  const auto j = Reader::frame_at(e, step);
  if (!j) r.fail(fmt::format("'{}' has no entry at step {}", e.where, step));
  return j;
}

// Reads the positions of `frame` into `snap`, with its step and time when
// the positions are a time series; returns the particle count.
hsize_t read_positions(const Reader& r, const std::string& base, std::int64_t frame,
                       ParticleSnapshot& snap) {
  const auto position = r.element(base + "/position");
  if (!position) r.fail(fmt::format("missing '{}/position'", base));
  const auto pdims = dims_of(position->value.id());
  const size_t lead = position->timed ? 1 : 0;
  if (pdims.size() != lead + 2 || pdims[lead + 1] != 3) {
    r.fail(fmt::format("'{}' has shape {}; only 3-D positions are supported",
                       position->timed ? base + "/position/value" : base + "/position",
                       shape_of(pdims)));
  }
  const hsize_t n = pdims[lead];
  const auto frames = position->timed ? static_cast<std::int64_t>(position->steps.size()) : 1;
  const std::int64_t k = frame < 0 ? frames + frame : frame;
  if (k < 0 || k >= frames) {
    r.fail(
        fmt::format("frame {} out of range: '{}/position' has {} frame(s)", frame, base, frames));
  }
  std::optional<hsize_t> at;
  if (position->timed) {
    at = static_cast<hsize_t>(k);
    snap.step = position->steps[*at];
    snap.time = r.time_of(*position, *at);
  }
  snap.x = as_triples(r.read<double>(*position, H5T_NATIVE_DOUBLE, at, {n, 3}));
  return n;
}

// Velocities, images, ids and species at the snapshot's step, or their
// defaults where the file has none.
void read_per_particle(const Reader& r, const std::string& base, hsize_t n,
                       ParticleSnapshot& snap) {
  snap.v.assign(n, {0.0, 0.0, 0.0});
  if (const auto velocity = r.element(base + "/velocity")) {
    const auto j = velocity->timed ? Reader::frame_at(*velocity, snap.step) : std::nullopt;
    if (!velocity->timed || j) {
      snap.v = as_triples(r.read<double>(*velocity, H5T_NATIVE_DOUBLE, j, {n, 3}));
      snap.has_velocities = true;
    }
  }

  if (const auto image = r.element(base + "/image")) {
    const auto flat = r.read<int>(*image, H5T_NATIVE_INT, frame_of(r, *image, snap.step), {n, 3});
    snap.image.resize(n);
    for (size_t i = 0; i < n; ++i) snap.image[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
  }

  if (const auto id = r.element(base + "/id")) {
    snap.id = r.read<std::int64_t>(*id, H5T_NATIVE_INT64, frame_of(r, *id, snap.step), {n});
  } else {
    snap.id.resize(n);
    for (hsize_t i = 0; i < n; ++i) snap.id[i] = static_cast<std::int64_t>(i);
  }

  if (const auto species = r.element(base + "/species")) {
    snap.species = r.read<int>(*species, H5T_NATIVE_INT, frame_of(r, *species, snap.step), {n});
    if (written_by_lammps(r)) {
      for (int& s : snap.species) s -= 1;
    }
  } else {
    snap.species.assign(n, 0);
  }
}

void require_3d_box(const Reader& r, const std::string& box) {
  if (!r.exists(box)) r.fail(fmt::format("missing group '{}'", box));
  h5::Handle box_group = r.open(box);
  if (H5Aexists(box_group.id(), "dimension") > 0) {
    h5::Handle attr(H5Aopen(box_group.id(), "dimension", H5P_DEFAULT), H5Aclose);
    int dim = 0;
    H5Aread(attr.id(), H5T_NATIVE_INT, &dim);
    if (dim != 3)
      r.fail(fmt::format("'{}' has dimension {}; only 3-D boxes are supported", box, dim));
  }
}

void read_boundary(const Reader& r, const std::string& box, ParticleSnapshot& snap) {
  const auto boundary = r.string_attribute(box, "boundary");
  if (boundary.size() != 3) {
    r.fail(fmt::format("attribute 'boundary' of '{}' has {} entries, expected 3", box,
                       boundary.size()));
  }
  for (int a = 0; a < 3; ++a) {
    if (boundary[a] != "periodic" && boundary[a] != "none") {
      r.fail(fmt::format("attribute 'boundary' of '{}' holds '{}', expected 'periodic' or 'none'",
                         box, boundary[a]));
    }
    snap.periodic[a] = boundary[a] == "periodic";
  }
}

void read_edges(const Reader& r, const std::string& box, ParticleSnapshot& snap) {
  const auto edges = r.element(box + "/edges");
  if (!edges) r.fail(fmt::format("missing '{}/edges'", box));
  const auto edims = dims_of(edges->value.id());
  const bool matrix = edims.size() == (edges->timed ? 3u : 2u);
  const auto e = r.read<double>(*edges, H5T_NATIVE_DOUBLE, frame_of(r, *edges, snap.step),
                                matrix ? std::vector<hsize_t>{3, 3} : std::vector<hsize_t>{3});
  for (int a = 0; a < 3; ++a) {
    if (matrix) {
      for (int b = 0; b < 3; ++b) {
        if (a != b && e[3 * a + b] != 0.0) {
          r.fail(fmt::format("'{}/edges' is not diagonal: triclinic boxes are not supported", box));
        }
      }
    }
    snap.box_hi[a] = matrix ? e[4 * a] : e[a];
  }
}

}  // namespace

ParticleSnapshot read_h5md_particles(const std::string& path, const std::string& group,
                                     std::int64_t frame) {
  Reader r(path);
  const std::string base = "particles/" + pick_group(r, group);
  ParticleSnapshot snap;
  const hsize_t n = read_positions(r, base, frame, snap);
  read_per_particle(r, base, n, snap);
  const std::string box = base + "/box";
  require_3d_box(r, box);
  read_boundary(r, box, snap);
  read_edges(r, box, snap);
  return snap;
}

}  // namespace pbms
