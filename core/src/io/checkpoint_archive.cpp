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

// Rank 0's list, on every rank.
void broadcast_names(std::vector<std::string>& names, MPI_Comm comm) {
  auto n = static_cast<std::uint64_t>(names.size());
  mpi::check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
  names.resize(n);
  for (std::string& name : names) broadcast_string(name, comm);
}

// Collective: a dataset of `n` values of `type`, of which this rank writes
// its `count` at `data` from `offset` (a rank with nothing to write takes
// part all the same).
void write_slab(hid_t file, const std::string& name, hid_t type, std::uint64_t n,
                std::uint64_t offset, const void* data, std::uint64_t count, hid_t dxpl) {
  const hsize_t extent = n;
  h5::Handle space(H5Screate_simple(1, &extent, nullptr), H5Sclose);
  h5::Handle ds(
      H5Dcreate2(file, name.c_str(), type, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (n == 0) return;
  const hsize_t start = offset, size = count, one = 1;
  h5::Handle memory(H5Screate_simple(1, size > 0 ? &size : &one, nullptr), H5Sclose);
  if (size > 0) {
    H5Sselect_hyperslab(space.id(), H5S_SELECT_SET, &start, nullptr, &size, nullptr);
  } else {
    H5Sselect_none(space.id());
    H5Sselect_none(memory.id());
  }
  const double dummy = 0.0;
  if (H5Dwrite(ds.id(), type, memory.id(), space.id(), dxpl, size > 0 ? data : &dummy) < 0) {
    throw Error(fmt::format("cannot write the checkpoint's entry '{}'", entry_name(name)));
  }
}
void write_slab(hid_t file, const std::string& name, std::uint64_t n, std::uint64_t offset,
                const std::vector<double>& mine, hid_t dxpl) {
  write_slab(file, name, H5T_NATIVE_DOUBLE, n, offset, mine.data(), mine.size(), dxpl);
}

template <class Map>
const typename Map::mapped_type& entry_of(const Map& map, const std::string& name,
                                          const std::filesystem::path& source) {
  const auto it = map.find(name);
  if (it == map.end()) {
    throw Error(
        fmt::format("checkpoint {} holds no '{}': it was written by another stage kind or "
                    "version",
                    source.string(), name));
  }
  return it->second;
}
}  // namespace

void CheckpointArchive::put(const std::string& name, std::vector<double> values) {
  arrays_[name] = std::move(values);
}

const std::vector<double>& CheckpointArchive::get(const std::string& name) const {
  return entry_of(arrays_, name, source_);
}

void CheckpointArchive::put_bytes(const std::string& name, std::string bytes) {
  bytes_[name] = std::move(bytes);
}

const std::string& CheckpointArchive::bytes(const std::string& name) const {
  return entry_of(bytes_, name, source_);
}

void CheckpointArchive::put_rows(const std::string& name, std::vector<double> mine,
                                 std::size_t width) {
  if (width == 0 || mine.size() % width != 0) {
    throw Error(fmt::format("checkpoint entry '{}': {} values are not rows of {}", name,
                            mine.size(), width));
  }
  rows_[name] = {std::move(mine), width};
}

void CheckpointArchive::write(const std::filesystem::path& file, const std::string& identity,
                              MPI_Comm comm) const {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::filesystem::path partial = file.string() + ".partial";
  if (rank == 0) std::filesystem::create_directories(file.parent_path());
  mpi::check(MPI_Barrier(comm), "MPI_Barrier");
  {
    h5::Handle f = h5::create_truncate(partial.string(), comm);
    h5::write_attribute(f.id(), "identity", identity);
    write_contents(f.id(), comm);
    H5Fflush(f.id(), H5F_SCOPE_GLOBAL);
  }
  if (rank == 0) {
    pause_for_tests(file);
    std::filesystem::rename(partial, file);
  }
}

void CheckpointArchive::write_contents(hid_t file, MPI_Comm comm) const {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  h5::Handle dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose);
  if (ranks > 1) H5Pset_dxpl_mpio(dxpl.id(), H5FD_MPIO_COLLECTIVE);
  const std::vector<double> none;

  // Rank 0's arrays for the whole program.
  std::vector<std::string> names;
  for (const auto& entry : arrays_) names.push_back(entry.first);
  broadcast_names(names, comm);
  for (const std::string& name : names) {
    const std::vector<double>& values = rank == 0 ? arrays_.at(name) : none;
    auto n = static_cast<std::uint64_t>(values.size());
    mpi::check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
    write_slab(file, dataset_name(name), n, 0, values, dxpl.id());
  }

  // Rank 0's byte strings.
  names.clear();
  for (const auto& entry : bytes_) names.push_back(entry.first);
  broadcast_names(names, comm);
  for (const std::string& name : names) {
    std::string text = rank == 0 ? bytes_.at(name) : std::string();
    auto n = static_cast<std::uint64_t>(text.size());
    mpi::check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
    if (rank != 0) text.clear();
    write_slab(file, dataset_name(name), H5T_NATIVE_UCHAR, n, 0, text.data(), text.size(),
               dxpl.id());
  }

  // Every rank's rows at its place, rank after rank, and how many.
  names.clear();
  for (const auto& entry : rows_) names.push_back(entry.first);
  broadcast_names(names, comm);
  for (const std::string& name : names) {
    const auto it = rows_.find(name);
    const std::vector<double>& mine = it != rows_.end() ? it->second.mine : none;
    auto width = static_cast<std::uint64_t>(it != rows_.end() ? it->second.width : 1);
    mpi::check(MPI_Bcast(&width, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
    std::uint64_t count = mine.size() / width;
    std::vector<std::uint64_t> counts(static_cast<std::size_t>(ranks));
    mpi::check(MPI_Allgather(&count, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, comm),
               "MPI_Allgather");
    std::uint64_t offset = 0, total = 0;
    for (int r = 0; r < ranks; ++r) {
      if (r < rank) offset += counts[static_cast<std::size_t>(r)];
      total += counts[static_cast<std::size_t>(r)];
    }
    write_slab(file, dataset_name(name), total * width, offset * width, mine, dxpl.id());
    const std::vector<double> per_rank(counts.begin(), counts.end());
    write_slab(file, dataset_name(name + kRankCountsSuffix), per_rank.size(), 0,
               rank == 0 ? per_rank : none, dxpl.id());
  }
}

void CheckpointArchive::read_entries(hid_t file) {
  H5G_info_t info{};
  H5Gget_info(file, &info);
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len =
        H5Lget_name_by_idx(file, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    std::string name(static_cast<std::size_t>(std::max<ssize_t>(len, 0)), '\0');
    H5Lget_name_by_idx(file, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1,
                       H5P_DEFAULT);
    h5::Handle ds(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
    h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
    h5::Handle type(H5Dget_type(ds.id()), H5Tclose);
    const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id()));
    herr_t status = 0;
    if (H5Tget_class(type.id()) == H5T_INTEGER) {
      std::string& text = bytes_[entry_name(name)];
      text.resize(n);
      if (n > 0)
        status = H5Dread(ds.id(), H5T_NATIVE_UCHAR, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data());
    } else {
      std::vector<double>& v = arrays_[entry_name(name)];
      v.resize(n);
      if (n > 0)
        status = H5Dread(ds.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    }
    if (status < 0) throw Error(fmt::format("its entry '{}' cannot be read", entry_name(name)));
  }
}

void CheckpointArchive::broadcast_entries(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<std::string> names;
  for (const auto& entry : arrays_) names.push_back(entry.first);
  broadcast_names(names, comm);
  for (const std::string& name : names) {
    std::vector<double>& v = arrays_[name];
    auto n = static_cast<std::uint64_t>(v.size());
    mpi::check(MPI_Bcast(&n, 1, MPI_UINT64_T, 0, comm), "MPI_Bcast");
    v.resize(n);
    mpi::check(MPI_Bcast(v.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm), "MPI_Bcast");
  }
  names.clear();
  for (const auto& entry : bytes_) names.push_back(entry.first);
  broadcast_names(names, comm);
  for (const std::string& name : names) broadcast_string(bytes_[name], comm);
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
      a.read_entries(f.id());
    } catch (const std::exception& e) {
      problem = e.what();
    }
  }
  broadcast_string(problem, comm);
  if (!problem.empty()) {
    throw Error(fmt::format("cannot resume from the checkpoint {}: {}", file.string(), problem));
  }
  a.broadcast_entries(comm);
  return a;
}

}  // namespace pbms
