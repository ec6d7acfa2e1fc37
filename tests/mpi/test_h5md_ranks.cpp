// H5mdWriter on 1, 2 and 3 ranks of this job (as many as it has): each
// rank passes the particles it holds, in a scrambled order that changes
// every frame, and particles change ranks between frames, as they migrate
// in a run. Every dataset of every file must hold the same bytes, and the
// values of the particle with the row's id (rows in ascending id): what
// gathering on rank 0 and sorting wrote before. Dense ids (one range) and
// sparse ones take the writer's two ways to a particle's row.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "pbms/error.hpp"
#include "pbms/io/h5md_writer.hpp"
#include "pbms/mpi/comm.hpp"

using namespace pbms;

namespace {

constexpr int kFrames = 4;
constexpr std::size_t kParticles = 1000;

int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// The first `ranks` ranks of the job; a null communicator on the others.
mpi::Comm first_ranks(int ranks) {
  MPI_Comm c = MPI_COMM_NULL;
  MPI_Comm_split(MPI_COMM_WORLD, world_rank() < ranks ? 0 : MPI_UNDEFINED, world_rank(), &c);
  return mpi::Comm(c);
}

// Values with all mantissa bits in use, so that a swapped row shows.
double value(std::int64_t id, int frame, int component) {
  return static_cast<double>(id) / 3.0 + frame * 0.7 + component * 11.1;
}

std::vector<std::int64_t> particle_ids(bool dense) {
  std::vector<std::int64_t> ids(kParticles);
  for (std::size_t i = 0; i < kParticles; ++i) {
    ids[i] = dense ? 500 + static_cast<std::int64_t>(i) : 7 * static_cast<std::int64_t>(i * i) - 3;
  }
  return ids;
}

// The particles rank `rank` of `ranks` holds at `frame` (-1: when the writer
// is made), in a scrambled order. Frame 1 leaves the last rank empty.
std::vector<std::int64_t> held(const std::vector<std::int64_t>& all, int rank, int ranks,
                               int frame) {
  std::vector<std::int64_t> mine;
  for (std::size_t i = 0; i < all.size(); ++i) {
    int owner = static_cast<int>((i * 2654435761u + static_cast<std::size_t>(frame + 1) * 97) %
                                 static_cast<std::size_t>(ranks));
    if (frame == 1 && ranks > 1 && owner == ranks - 1) owner = 0;
    if (owner == rank) mine.push_back(all[i]);
  }
  std::mt19937 rng(static_cast<unsigned>(1000 * frame + 10 * rank + ranks + 7));
  std::shuffle(mine.begin(), mine.end(), rng);
  return mine;
}

int species_of(std::int64_t id) {
  return static_cast<int>(id % 3);
}

void write(MPI_Comm comm, const std::string& path, const std::vector<std::int64_t>& all) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  H5mdWriter::Options o;
  o.path = path;
  o.periodic = {true, false, true};
  o.velocities = o.forces = o.internal_energy = true;
  const auto ids0 = held(all, rank, ranks, -1);
  std::vector<int> species;
  for (const auto id : ids0) species.push_back(species_of(id));
  H5mdWriter w(comm, o, ids0, species);
  for (int frame = 0; frame < kFrames; ++frame) {
    const auto ids = held(all, rank, ranks, frame);
    std::vector<double> x, v, f, u;
    for (const auto id : ids) {
      for (int c = 0; c < 3; ++c) {
        x.push_back(value(id, frame, c));
        v.push_back(-value(id, frame, c));
        f.push_back(value(id, frame, c) * 1e-3);
      }
      u.push_back(value(id, frame, 5));
    }
    w.write_frame(10 * frame, 0.002 * 10 * frame, {10.0, 11.0, 12.0 + frame}, ids, x, v, f, u);
  }
}

struct Dataset {
  std::vector<hsize_t> dims;
  std::vector<unsigned char> bytes;  // in the file's type
};

Dataset read(const std::string& path, const std::string& name) {
  h5::Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  h5::Handle ds(H5Dopen2(file.id(), name.c_str(), H5P_DEFAULT), H5Dclose);
  h5::Handle space(H5Dget_space(ds.id()), H5Sclose);
  h5::Handle type(H5Dget_type(ds.id()), H5Tclose);
  Dataset d;
  d.dims.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.id())));
  H5Sget_simple_extent_dims(space.id(), d.dims.data(), nullptr);
  d.bytes.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id())) *
                 H5Tget_size(type.id()));
  H5Dread(ds.id(), type.id(), H5S_ALL, H5S_ALL, H5P_DEFAULT, d.bytes.data());
  return d;
}

template <class T>
std::vector<T> as(const Dataset& d) {
  std::vector<T> out(d.bytes.size() / sizeof(T));
  std::copy_n(d.bytes.data(), d.bytes.size(), reinterpret_cast<unsigned char*>(out.data()));
  return out;
}

std::string scratch_dir() {
  // Rank 0's pid, so that concurrent jobs never share files.
  int pid = world_rank() == 0 ? static_cast<int>(getpid()) : 0;
  MPI_Bcast(&pid, 1, MPI_INT, 0, MPI_COMM_WORLD);
  const auto dir =
      std::filesystem::temp_directory_path() / ("pbms_h5md_ranks_" + std::to_string(pid));
  if (world_rank() == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  return dir.string();
}

void check_same_files_whatever_the_ranks(bool dense) {
  const auto all = particle_ids(dense);
  const std::string dir = scratch_dir();
  const int max_ranks = std::min(3, world_size());
  std::vector<std::string> paths;
  for (int ranks = 1; ranks <= max_ranks; ++ranks) {
    paths.push_back(dir + "/ranks_" + std::to_string(ranks) + ".h5md");
    const mpi::Comm comm = first_ranks(ranks);
    if (comm.valid()) write(comm.get(), paths.back(), all);
    MPI_Barrier(MPI_COMM_WORLD);
  }
  if (world_rank() == 0) {
    std::vector<std::int64_t> sorted = all;
    std::sort(sorted.begin(), sorted.end());
    const auto ids = as<std::int64_t>(read(paths[0], "particles/all/id"));
    EXPECT_EQ(ids, sorted);
    const auto species = as<int>(read(paths[0], "particles/all/species"));
    const auto x = as<double>(read(paths[0], "particles/all/position/value"));
    const auto u = as<double>(read(paths[0], "particles/all/internal_energy/value"));
    ASSERT_EQ(x.size(), kFrames * kParticles * 3);
    int wrong = 0;
    for (std::size_t row = 0; row < kParticles; ++row) {
      wrong += species[row] != species_of(sorted[row]);
      for (int frame = 0; frame < kFrames; ++frame) {
        const std::size_t at = static_cast<std::size_t>(frame) * kParticles + row;
        wrong += u[at] != value(sorted[row], frame, 5);
        for (int c = 0; c < 3; ++c)
          wrong += x[3 * at + static_cast<std::size_t>(c)] != value(sorted[row], frame, c);
      }
    }
    EXPECT_EQ(wrong, 0) << "values not at the row of their id";
    for (const char* name :
         {"particles/all/id", "particles/all/species", "particles/all/position/step",
          "particles/all/position/time", "particles/all/position/value",
          "particles/all/velocity/value", "particles/all/force/value",
          "particles/all/internal_energy/value", "particles/all/internal_energy/step",
          "particles/all/box/edges/value", "particles/all/box/edges/step"}) {
      const Dataset one = read(paths[0], name);
      for (std::size_t k = 1; k < paths.size(); ++k) {
        const Dataset other = read(paths[k], name);
        EXPECT_EQ(other.dims, one.dims) << name << " on " << k + 1 << " ranks";
        EXPECT_TRUE(other.bytes == one.bytes) << name << " on " << k + 1 << " ranks";
      }
    }
    std::filesystem::remove_all(dir);
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace

TEST(H5mdRanks, DenseIdsSameFileWhateverTheRanks) {
  check_same_files_whatever_the_ranks(true);
}

TEST(H5mdRanks, SparseIdsSameFileWhateverTheRanks) {
  check_same_files_whatever_the_ranks(false);
}

// A frame that loses a particle, or holds one the file does not have, is
// refused on every rank: none is left waiting in a collective write.
TEST(H5mdRanks, MissingOrStrangeParticleRefusedOnEveryRank) {
  const std::string dir = scratch_dir();
  const int rank = world_rank(), ranks = world_size();
  for (const bool dense : {true, false}) {
    const auto all = particle_ids(dense);
    H5mdWriter::Options o;
    o.path = dir + "/refused.h5md";
    const auto ids0 = held(all, rank, ranks, -1);
    H5mdWriter w(MPI_COMM_WORLD, o, ids0, std::vector<int>(ids0.size(), 0));
    auto ids = held(all, rank, ranks, 0);
    if (rank == 0 && !ids.empty()) ids.pop_back();
    EXPECT_THROW(w.write_frame(0, 0.0, {1, 1, 1}, ids, std::vector<double>(3 * ids.size())), Error);
    if (rank == 0) ids.push_back(dense ? -5 : 8);
    EXPECT_THROW(w.write_frame(0, 0.0, {1, 1, 1}, ids, std::vector<double>(3 * ids.size())), Error);
    EXPECT_EQ(w.frames(), 0);
  }
  auto repeated = held(particle_ids(false), rank, ranks, -1);
  if (rank == ranks - 1) repeated.push_back(particle_ids(false)[0]);
  H5mdWriter::Options o;
  o.path = dir + "/repeated.h5md";
  EXPECT_THROW(H5mdWriter(MPI_COMM_WORLD, o, repeated, std::vector<int>(repeated.size(), 0)),
               Error);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) std::filesystem::remove_all(dir);
}
