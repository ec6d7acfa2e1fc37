#include "pbms/io/hdf5.hpp"

#include <cstdio>
#include <exception>
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

namespace {
// Closer of a file opened through MPI-IO. Its close is collective: while an
// exception unwinds on this rank, the others may be inside another
// collective (a step's sums, a migration) and would never meet it, so the
// rank would hang instead of reporting its failure. Then the file stays
// open; the writers flush after every frame, so what they wrote is on disk,
// and the job that is ending closes it, or MPI_Finalize does.
herr_t close_collective_file(hid_t f) {
  if (std::uncaught_exceptions() > 0) return 0;
  return H5Fclose(f);
}
}  // namespace

Handle create_truncate(const std::string& path, MPI_Comm comm) {
  Handle fapl = file_access(comm);
  const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id());
  if (f < 0) throw Error(fmt::format("cannot create HDF5 file '{}'", path));
  int size = 1;
  MPI_Comm_size(comm, &size);
  return Handle(f, size > 1 ? close_collective_file : H5Fclose);
}

Handle open_read_write(const std::string& path, MPI_Comm comm) {
  Handle fapl = file_access(comm);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl.id());
  if (f < 0) throw Error(fmt::format("cannot open HDF5 file '{}' to write", path));
  int size = 1;
  MPI_Comm_size(comm, &size);
  return Handle(f, size > 1 ? close_collective_file : H5Fclose);
}

namespace {
constexpr const char* kUpdateSuffix = ".tmp";

// Closer of open_or_create()'s handle: closes the copy, then publishes it by
// a rename (atomic within a directory), or drops it when the close failed
// or an exception is unwinding. A closer cannot throw; it says what failed.
herr_t close_and_publish(hid_t f) {
  const ssize_t len = H5Fget_name(f, nullptr, 0);
  std::string copy(len > 0 ? static_cast<std::size_t>(len) : 0, '\0');
  if (len > 0) H5Fget_name(f, copy.data(), copy.size() + 1);
  const herr_t closed = H5Fclose(f);
  const std::string suffix = kUpdateSuffix;
  if (copy.size() <= suffix.size()) return closed;
  const std::string path = copy.substr(0, copy.size() - suffix.size());
  std::error_code ec;
  if (closed < 0 || std::uncaught_exceptions() > 0) {
    std::filesystem::remove(copy, ec);
    if (closed < 0) {
      fmt::print(stderr, "pbms: closing '{}' failed; '{}' is unchanged\n", copy, path);
    }
    return closed;
  }
  std::filesystem::rename(copy, path, ec);
  if (ec) {
    fmt::print(stderr, "pbms: cannot rename '{}' to '{}': {}\n", copy, path, ec.message());
    return -1;
  }
  return 0;
}
}  // namespace

Handle open_or_create(const std::string& path) {
  const std::string copy = path + kUpdateSuffix;
  std::error_code ec;
  const bool existed = std::filesystem::exists(path);
  if (existed) {
    std::filesystem::copy_file(path, copy, std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw Error(fmt::format("cannot copy '{}' to '{}': {}", path, copy, ec.message()));
  }
  // Closing the file closes whatever is still open in it, so that the
  // rename never publishes a file with unwritten objects.
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(fapl.id(), H5F_CLOSE_STRONG);
  // A copy left by a crash is overwritten either way.
  const hid_t f = existed ? H5Fopen(copy.c_str(), H5F_ACC_RDWR, fapl.id())
                          : H5Fcreate(copy.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.id());
  if (f < 0) throw Error(fmt::format("cannot open HDF5 file '{}'", copy));
  return Handle(f, close_and_publish);
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

std::string read_string_attribute(hid_t obj, const std::string& name) {
  if (H5Aexists(obj, name.c_str()) <= 0) throw Error(fmt::format("no attribute '{}'", name));
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle type(H5Aget_type(attr.id()), H5Tclose);
  if (H5Tget_class(type.id()) != H5T_STRING || H5Tis_variable_str(type.id()) > 0) {
    throw Error(fmt::format("attribute '{}' is not a fixed-length string", name));
  }
  std::string value(H5Tget_size(type.id()), '\0');
  H5Aread(attr.id(), type.id(), value.data());
  return value.substr(0, value.find('\0'));
}

void write_vlen_attribute(hid_t obj, const std::string& name, const std::string& value) {
  if (H5Aexists(obj, name.c_str()) > 0) H5Adelete(obj, name.c_str());
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.id(), H5T_VARIABLE);
  H5Tset_cset(type.id(), H5T_CSET_ASCII);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj, name.c_str(), type.id(), space.id(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  const char* text = value.c_str();
  H5Awrite(attr.id(), type.id(), &text);
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
