#include "pbms/io/hdf5.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "pbms/error.hpp"

namespace pbms::h5 {

Handle::Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {
  if (id < 0) throw Error("HDF5 call failed (see the HDF5 error stack above)");
}

void Handle::reset() {
  if (id_ >= 0 && closer_) closer_(id_);
  id_ = -1;
}

namespace {
Handle file_access(MPI_Comm comm) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size > 1) H5Pset_fapl_mpio(fapl.id(), comm, MPI_INFO_NULL);
  return fapl;
}
}  // namespace

Handle create_truncate(const std::string& path, MPI_Comm comm) {
  Handle fapl = file_access(comm);
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id());
  if (f < 0) throw Error(fmt::format("cannot create HDF5 file '{}'", path));
  return Handle(f, H5Fclose);
}

Handle open_or_create(const std::string& path, MPI_Comm comm) {
  if (!std::filesystem::exists(path)) return create_truncate(path, comm);
  Handle fapl = file_access(comm);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id());
  if (f < 0) throw Error(fmt::format("cannot open HDF5 file '{}'", path));
  return Handle(f, H5Fclose);
}

bool exists(hid_t parent, const std::string& name) {
  // H5Lexists fails, printing an error stack, when an intermediate group of
  // a path is missing: test "a", then "a/b", then "a/b/c".
  std::size_t end = 0;
  while (end != std::string::npos) {
    end = name.find('/', end + 1);
    const std::string prefix = name.substr(0, end);
    if (prefix.empty()) continue;
    if (H5Lexists(parent, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

void delete_link_if_exists(hid_t parent, const std::string& name) {
  if (exists(parent, name)) H5Ldelete(parent, name.c_str(), H5P_DEFAULT);
}

Handle require_group(hid_t parent, const std::string& path) {
  Handle lcpl(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(lcpl.id(), 1);
  if (exists(parent, path)) return Handle(H5Gopen2(parent, path.c_str(), H5P_DEFAULT), H5Gclose);
  return Handle(H5Gcreate2(parent, path.c_str(), lcpl.id(), H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
}

void write_attribute(hid_t obj, const std::string& name, const std::string& value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id(), std::max<size_t>(1, value.size()));
  H5Tset_cset(type.id(), H5T_CSET_UTF8);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  H5Awrite(attr.id(), type.id(), value.empty() ? "" : value.c_str());
}

void write_attribute(hid_t obj, const std::string& name, double value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(
      H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, space.id(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  H5Awrite(attr.id(), H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(hid_t obj, const std::string& name, const std::vector<int>& value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  const hsize_t n = value.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  Handle attr(H5Acreate2(obj, name.c_str(), H5T_NATIVE_INT, space.id(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  H5Awrite(attr.id(), H5T_NATIVE_INT, value.data());
}

void write_vector(hid_t parent, const std::string& name, const std::vector<double>& data,
                  const std::string& unit) {
  delete_link_if_exists(parent, name);
  const hsize_t n = data.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  Handle ds(H5Dcreate2(parent, name.c_str(), H5T_NATIVE_DOUBLE, space.id(), H5P_DEFAULT,
                       H5P_DEFAULT, H5P_DEFAULT),
            H5Dclose);
  if (n > 0) H5Dwrite(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data());
  write_attribute(ds.id(), "unit", unit);
}

void write_scalar(hid_t parent, const std::string& name, double value, const std::string& unit) {
  delete_link_if_exists(parent, name);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle ds(H5Dcreate2(parent, name.c_str(), H5T_NATIVE_DOUBLE, space.id(), H5P_DEFAULT,
                       H5P_DEFAULT, H5P_DEFAULT),
            H5Dclose);
  H5Dwrite(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, &value);
  write_attribute(ds.id(), "unit", unit);
}

}  // namespace pbms::h5
