#include "point_migration.hpp"

#include <cstring>
#include <vector>

#include "pbms/mpi/comm.hpp"

namespace pbms::mpm {
namespace {

// One point as raw doubles: id, x, v, mass, volume0, F, the state, material,
// groups and work. Integers travel as doubles; ids below 2^53 are exact.
constexpr size_t kPacked = 1 + 3 + 3 + 1 + 1 + 9 + 6 + 3 + 1 + 1 + 1;

void pack(const grid::MaterialPoints& pts, size_t p, std::vector<double>& out) {
  out.push_back(static_cast<double>(pts.id[p]));
  out.insert(out.end(), pts.x[p].begin(), pts.x[p].end());
  out.insert(out.end(), pts.v[p].begin(), pts.v[p].end());
  out.push_back(pts.mass[p]);
  out.push_back(pts.volume0[p]);
  for (int i = 0; i < 9; ++i) out.push_back(pts.F[p](i / 3, i % 3));
  const auto& s = pts.state[p];
  out.insert(out.end(), s.stress.voigt.begin(), s.stress.voigt.end());
  out.push_back(s.density);
  out.push_back(s.plastic_strain);
  out.push_back(s.internal_energy);
  out.push_back(static_cast<double>(pts.material[p]));
  out.push_back(static_cast<double>(pts.groups[p]));
  out.push_back(pts.work[p]);
}

void unpack(const double* d, grid::MaterialPoints& pts) {
  grid::MaterialPointState s;
  std::copy(d + 18, d + 24, s.stress.voigt.begin());
  s.density = d[24];
  s.plastic_strain = d[25];
  s.internal_energy = d[26];
  pts.add(static_cast<int64_t>(d[0]), {d[1], d[2], d[3]}, d[8], s, static_cast<int>(d[27]),
          static_cast<uint32_t>(d[28]));
  pts.v.back() = {d[4], d[5], d[6]};
  pts.mass.back() = d[7];
  for (int i = 0; i < 9; ++i) pts.F.back()(i / 3, i % 3) = d[9 + i];
  pts.work.back() = d[29];
}

}  // namespace

size_t migrate_points(MPI_Comm comm, const grid::GridPartition& partition,
                      grid::MaterialPoints& points) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) return 0;
  std::vector<std::vector<double>> out(static_cast<size_t>(size));
  size_t sent = 0;
  for (size_t p = 0; p < points.size();) {
    const int owner = partition.owner_of(points.x[p]);
    if (owner == rank) {
      ++p;
      continue;
    }
    pack(points, p, out[static_cast<size_t>(owner)]);
    points.erase(p);  // the last point moves into p: look at p again
    ++sent;
  }
  std::vector<int> send_counts(static_cast<size_t>(size)), recv_counts(static_cast<size_t>(size));
  std::vector<int> send_displs(static_cast<size_t>(size)), recv_displs(static_cast<size_t>(size));
  std::vector<double> send;
  for (size_t r = 0; r < out.size(); ++r) {
    send_displs[r] = static_cast<int>(send.size());
    send_counts[r] = static_cast<int>(out[r].size());
    send.insert(send.end(), out[r].begin(), out[r].end());
  }
  mpi::check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, comm),
             "MPI_Alltoall (migration counts)");
  int total = 0;
  for (size_t r = 0; r < recv_counts.size(); ++r) {
    recv_displs[r] = total;
    total += recv_counts[r];
  }
  std::vector<double> recv(static_cast<size_t>(total));
  mpi::check(MPI_Alltoallv(send.data(), send_counts.data(), send_displs.data(), MPI_DOUBLE,
                           recv.data(), recv_counts.data(), recv_displs.data(), MPI_DOUBLE, comm),
             "MPI_Alltoallv (migration)");
  for (size_t k = 0; k + kPacked <= recv.size(); k += kPacked) unpack(recv.data() + k, points);
  return sent;
}

}  // namespace pbms::mpm
