#include "pbms/io/h5md_writer.hpp"

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms {
namespace {

void write_fixed(hid_t parent, const std::string& name, hid_t mem_type, hid_t file_type,
                 const void* local, hsize_t n_local, hsize_t offset, hsize_t n_total, hid_t dxpl) {
  h5::Handle fspace(H5Screate_simple(1, &n_total, nullptr), H5Sclose);
  h5::Handle ds(H5Dcreate2(parent, name.c_str(), file_type, fspace.id(), H5P_DEFAULT, H5P_DEFAULT,
                           H5P_DEFAULT),
                H5Dclose);
  h5::Handle mspace(H5Screate_simple(1, &n_local, nullptr), H5Sclose);
  H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, &offset, nullptr, &n_local, nullptr);
  if (n_local == 0) {
    H5Sselect_none(fspace.id());
    H5Sselect_none(mspace.id());
  }
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
    : comm_(comm), opt_(opt) {
  if (ids.size() != species.size()) throw Error("H5MD: ids and species differ in length");
  n_local_ = ids.size();
  unsigned long long local = n_local_, before = 0, total = 0;
  MPI_Exscan(&local, &before, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
  MPI_Allreduce(&local, &total, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, comm);
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  offset_ = rank == 0 ? 0 : before;
  n_total_ = total;

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
    force_ = make_series(all.id(), "force", 2, n_total_, metal ? "eV Angstrom-1" : nullptr,
                         "pbms_unit");
  }
  if (opt.internal_energy) {
    internal_energy_ =
        make_series(all.id(), "internal_energy", 1, n_total_, metal ? "eV" : nullptr);
  }

  std::vector<long long> id_ll(ids.begin(), ids.end());
  write_fixed(all.id(), "id", H5T_NATIVE_LLONG, H5T_STD_I64LE, id_ll.data(), n_local_, offset_,
              n_total_, dxpl_.id());
  write_fixed(all.id(), "species", H5T_NATIVE_INT, H5T_STD_I32LE, species.data(), n_local_, offset_,
              n_total_, dxpl_.id());
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

void H5mdWriter::append(TimeSeries& ts, int64_t step, double time, const double* data,
                        hsize_t n_local, hsize_t offset, hsize_t n_total, hsize_t width) {
  const hsize_t t = static_cast<hsize_t>(frames_);
  const hsize_t new1[1] = {t + 1};
  H5Dset_extent(ts.step.id(), new1);
  H5Dset_extent(ts.time.id(), new1);
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  for (auto [ds, type, ptr] : {std::tuple{ts.step.id(), H5T_NATIVE_INT64, (const void*)&step},
                               std::tuple{ts.time.id(), H5T_NATIVE_DOUBLE, (const void*)&time}}) {
    h5::Handle fspace(H5Dget_space(ds), H5Sclose);
    const hsize_t one = 1;
    h5::Handle mspace(H5Screate_simple(1, &one, nullptr), H5Sclose);
    H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, &t, nullptr, &one, nullptr);
    if (rank != 0) {
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
  const hsize_t start3[3] = {t, offset, 0}, count3[3] = {1, n_local, 3};
  const hsize_t start2[2] = {t, offset}, count2[2] = {1, n_local};
  H5Sselect_hyperslab(fspace.id(), H5S_SELECT_SET, vec3 ? start3 : start2, nullptr,
                      vec3 ? count3 : count2, nullptr);
  const hsize_t mcount = n_local * (vec3 ? 3 : 1);
  h5::Handle mspace(H5Screate_simple(1, &mcount, nullptr), H5Sclose);
  if (n_local == 0) {
    H5Sselect_none(fspace.id());
    H5Sselect_none(mspace.id());
  }
  H5Dwrite(ts.value.id(), H5T_NATIVE_DOUBLE, mspace.id(), fspace.id(), dxpl_.id(), data);
}

void H5mdWriter::write_frame(int64_t step, double time_ps, const std::array<double, 3>& box_edges,
                             const std::vector<double>& positions,
                             const std::vector<double>& velocities,
                             const std::vector<double>& forces,
                             const std::vector<double>& internal_energy) {
  // All sizes are checked before the first append, so that a refused frame
  // leaves no series one frame longer than the others.
  if (positions.size() != 3 * n_local_) throw Error("H5MD: position array has the wrong size");
  if (opt_.velocities && velocities.size() != 3 * n_local_) {
    throw Error("H5MD: velocity array has the wrong size");
  }
  if (opt_.forces && forces.size() != 3 * n_local_) {
    throw Error("H5MD: force array has the wrong size");
  }
  if (opt_.internal_energy && internal_energy.size() != n_local_) {
    throw Error("H5MD: internal energy array has the wrong size");
  }
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  const std::array<double, 9> matrix = {box_edges[0], 0.0, 0.0, 0.0,         box_edges[1],
                                        0.0,          0.0, 0.0, box_edges[2]};
  append(edges_, step, time_ps, matrix.data(), rank == 0 ? 3 : 0, 0, 3, 3);
  append(position_, step, time_ps, positions.data(), n_local_, offset_, n_total_, 3);
  if (opt_.velocities) {
    append(velocity_, step, time_ps, velocities.data(), n_local_, offset_, n_total_, 3);
  }
  if (opt_.forces) {
    append(force_, step, time_ps, forces.data(), n_local_, offset_, n_total_, 3);
  }
  if (opt_.internal_energy) {
    append(internal_energy_, step, time_ps, internal_energy.data(), n_local_, offset_, n_total_, 1);
  }
  ++frames_;
  H5Fflush(file_.id(), H5F_SCOPE_GLOBAL);
}

}  // namespace pbms
