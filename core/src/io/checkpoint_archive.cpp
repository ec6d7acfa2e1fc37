#include "pbms/io/checkpoint_archive.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "pbms/error.hpp"
#include "pbms/io/hdf5.hpp"
#include "pbms/mpi/comm.hpp"

namespace pbms {
namespace {

// Datasets sit side by side in the file's root: '/' in a name becomes '|'.
std::string dataset_name(std::string name) {
  for (char& c : name) c = c == '/' ? '|' : c;
  return name;
}
std::string entry_name(std::string name) {
  for (char& c : name) c = c == '|' ? '/' : c;
  return name;
}

std::string read_identity(hid_t file) {
  if (H5Aexists(file, "identity") <= 0) return {};
  h5::Handle a(H5Aopen(file, "identity", H5P_DEFAULT), H5Aclose);
  h5::Handle type(H5Aget_type(a.id()), H5Tclose);
  std::string out(H5Tget_size(type.id()), '\0');
  if (H5Aread(a.id(), type.id(), out.data()) < 0) return {};
  return out.substr(0, out.find('\0'));
}

// PBMS_TEST_CHECKPOINT_PAUSE="NAME:SECONDS": the writer of a file whose
// name holds NAME waits that long between its data and its rename.
void pause_for_tests(const std::filesystem::path& file) {
  const char* env = std::getenv("PBMS_TEST_CHECKPOINT_PAUSE");
  if (!env || !*env) return;
  const std::string spec(env);
  const auto colon = spec.rfind(':');
  if (colon == std::string::npos) return;
  if (file.filename().string().find(spec.substr(0, colon)) == std::string::npos) return;
  std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(spec.c_str() + colon + 1)));
}

std::vector<std::string> identity_parts(const std::string& identity) {
  std::vector<std::string> parts;
  std::size_t from = 0;
  for (std::size_t at = identity.find("; "); at != std::string::npos;
       at = identity.find("; ", from)) {
    parts.push_back(identity.substr(from, at - from));
    from = at + 2;
  }
  parts.push_back(identity.substr(from));
  return parts;
}

// Names the first part of the two identities that differs (the stage and
// its parameters, then the program's version).
std::string identity_mismatch(const std::string& theirs, const std::string& mine) {
  const auto a = identity_parts(theirs), b = identity_parts(mine);
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    if (a[k] != b[k]) return fmt::format("it holds the state of {}; this run is {}", a[k], b[k]);
  }
  return fmt::format("it holds the state of {}; this run is {}", theirs, mine);
}

void broadcast_string(std::string& s, MPI_Comm comm) {
  auto n = static_cast<std::uint64_t>(s.size());
  mpi::check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
  s.resize(n);
  mpi::check(MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, 0, comm), "MPI_Bcast");
}

}  // namespace

void CheckpointArchive::put(const std::string& name, std::vector<double> values) {
  arrays_[name] = std::move(values);
}

const std::vector<double>& CheckpointArchive::get(const std::string& name) const {
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) {
    throw Error(
        fmt::format("checkpoint {} holds no '{}': it was written by another stage kind or "
                    "version",
                    source_.string(), name));
  }
  return it->second;
}

void CheckpointArchive::write(const std::filesystem::path& file,
                              const std::string& identity) const {
  std::filesystem::create_directories(file.parent_path());
  const std::filesystem::path partial = file.string() + ".partial";
  {
    h5::Handle f = h5::create_truncate(partial.string());
    h5::write_attribute(f.id(), "identity", identity);
    for (const auto& [name, values] : arrays_) {
      h5::write_vector(f.id(), dataset_name(name), values, "");
    }
    H5Fflush(f.id(), H5F_SCOPE_GLOBAL);
  }
  pause_for_tests(file);
  std::filesystem::rename(partial, file);
}

CheckpointArchive CheckpointArchive::read(const std::filesystem::path& file,
                                          const std::string& identity, MPI_Comm comm) {
  CheckpointArchive a;
  a.source_ = file;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string problem;
  if (rank == 0) {
    try {
      if (!std::filesystem::exists(file)) throw Error("it does not exist");
      h5::Handle f(H5Fopen(file.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
      const std::string theirs = read_identity(f.id());
      if (theirs != identity) throw Error(identity_mismatch(theirs, identity));
      H5G_info_t info{};
      H5Gget_info(f.id(), &info);
      for (hsize_t k = 0; k < info.nlinks; ++k) {
        const ssize_t len =
            H5Lget_name_by_idx(f.id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
        std::string name(static_cast<std::size_t>(std::max<ssize_t>(len, 0)), '\0');
        H5Lget_name_by_idx(f.id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1,
                           H5P_DEFAULT);
        h5::Handle ds(H5Dopen2(f.id(), name.c_str(), H5P_DEFAULT), H5Dclose);
        h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
        std::vector<double> v(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id())));
        if (!v.empty() &&
            H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0) {
          throw Error(fmt::format("its entry '{}' cannot be read", entry_name(name)));
        }
        a.arrays_[entry_name(name)] = std::move(v);
      }
    } catch (const std::exception& e) {
      problem = e.what();
    }
  }
  broadcast_string(problem, comm);
  if (!problem.empty()) {
    throw Error(fmt::format("cannot resume from the checkpoint {}: {}", file.string(), problem));
  }
  auto count = static_cast<std::uint64_t>(a.arrays_.size());
  mpi::check(MPI_Bcast(&count, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
  auto it = a.arrays_.begin();
  for (std::uint64_t k = 0; k < count; ++k) {
    std::string name = rank == 0 ? it->first : std::string();
    broadcast_string(name, comm);
    std::vector<double>& v = a.arrays_[name];
    auto n = static_cast<std::uint64_t>(v.size());
    mpi::check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
    v.resize(n);
    mpi::check(MPI_Bcast(v.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm), "MPI_Bcast");
    if (rank == 0) ++it;
  }
  return a;
}

}  // namespace pbms
