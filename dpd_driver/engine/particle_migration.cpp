#include "engine/particle_migration.hpp"

#include <cmath>
#include <cstdint>
#include <vector>

#include "pbms/mpi/comm.hpp"

namespace pbms::dpd {

namespace {

constexpr int kRecordWidth = 13;  // id, type, x3, v3, image3, internal energy, group mask

void pack(const DpdParticles& p, std::size_t i, std::vector<double>& out) {
  out.insert(out.end(),
             {static_cast<double>(p.id[i]), static_cast<double>(p.type[i]), p.x[i][0], p.x[i][1],
              p.x[i][2], p.v[i][0], p.v[i][1], p.v[i][2], static_cast<double>(p.image[i][0]),
              static_cast<double>(p.image[i][1]), static_cast<double>(p.image[i][2]),
              p.internal_energy[i], static_cast<double>(p.group_mask[i])});
}

void unpack(const double* r, DpdParticles& p) {
  p.add(static_cast<std::int64_t>(r[0]), static_cast<int>(r[1]), {r[2], r[3], r[4]},
        {r[5], r[6], r[7]});
  p.image.back() = {static_cast<int>(r[8]), static_cast<int>(r[9]), static_cast<int>(r[10])};
  p.internal_energy.back() = r[11];
  p.group_mask.back() = static_cast<std::uint32_t>(r[12]);
}

}  // namespace

void migrate_particles(const DomainDecomposition& domain, DpdParticles& particles) {
  const OrthogonalBox& box = domain.box();
  std::vector<double> out[2], in;
  for (int a = 0; a < 3; ++a) {
    if (!domain.split(a)) continue;
    const bool first = domain.coords()[a] == 0;
    const bool last = domain.coords()[a] + 1 == domain.dims()[a];
    const bool periodic = box.periodic[a];
    out[0].clear();
    out[1].clear();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const double x = particles.x[i][a];
      int side = -1;  // 0 down, 1 up, -1 stays
      if (x < domain.sub_lo(a) && !(first && !periodic)) side = 0;
      if (x >= domain.sub_hi(a) && !(last && !periodic)) side = 1;
      if (side >= 0 && periodic) {
        // Wrapped positions: one that left the first box downwards now
        // lies near the top of the box. The way back to the sub-box that
        // is shorter around the ring is the way it went.
        const double below = std::fmod(domain.sub_lo(a) - x + 2.0 * box.length(a), box.length(a));
        const double above = std::fmod(x - domain.sub_hi(a) + 2.0 * box.length(a), box.length(a));
        side = below < above ? 0 : 1;
      }
      if (side < 0) {
        if (kept != i) {
          particles.id[kept] = particles.id[i];
          particles.type[kept] = particles.type[i];
          particles.x[kept] = particles.x[i];
          particles.v[kept] = particles.v[i];
          particles.f[kept] = particles.f[i];
          particles.image[kept] = particles.image[i];
          particles.internal_energy[kept] = particles.internal_energy[i];
          particles.group_mask[kept] = particles.group_mask[i];
        }
        ++kept;
        continue;
      }
      pack(particles, i, out[side]);
    }
    particles.truncate(kept);
    for (int side = 0; side < 2; ++side) {
      const int direction = side == 0 ? -1 : 1;
      int to = domain.neighbour(a, direction), from = domain.neighbour(a, -direction);
      if (to < 0) to = MPI_PROC_NULL;
      if (from < 0) from = MPI_PROC_NULL;
      long long n_out = static_cast<long long>(out[side].size()), n_in = 0;
      mpi::check(MPI_Sendrecv(&n_out, 1, MPI_LONG_LONG, to, 400 + side, &n_in, 1, MPI_LONG_LONG,
                              from, 400 + side, domain.comm(), MPI_STATUS_IGNORE),
                 "MPI_Sendrecv (migration counts)");
      if (from == MPI_PROC_NULL) n_in = 0;
      in.resize(static_cast<std::size_t>(n_in));
      mpi::check(MPI_Sendrecv(out[side].data(), static_cast<int>(n_out), MPI_DOUBLE, to, 410 + side,
                              in.data(), static_cast<int>(n_in), MPI_DOUBLE, from, 410 + side,
                              domain.comm(), MPI_STATUS_IGNORE),
                 "MPI_Sendrecv (migration)");
      for (std::size_t k = 0; k + kRecordWidth <= in.size(); k += kRecordWidth) {
        unpack(&in[k], particles);
      }
    }
  }
}

void redistribute_particles(const DomainDecomposition& domain, DpdParticles& particles) {
  std::vector<double> mine;
  mine.reserve(particles.size() * kRecordWidth);
  for (std::size_t i = 0; i < particles.size(); ++i) pack(particles, i, mine);
  const int ranks = domain.size();
  std::vector<int> counts(static_cast<std::size_t>(ranks)), offsets(counts.size(), 0);
  const int count = static_cast<int>(mine.size());
  mpi::check(MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, domain.comm()),
             "MPI_Allgather (redistribution counts)");
  for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<std::size_t>(offsets.back() + counts.back()));
  mpi::check(MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(),
                            offsets.data(), MPI_DOUBLE, domain.comm()),
             "MPI_Allgatherv (redistribution)");
  particles.truncate(0);
  for (std::size_t k = 0; k + kRecordWidth <= all.size(); k += kRecordWidth) {
    if (domain.owns({all[k + 2], all[k + 3], all[k + 4]})) unpack(&all[k], particles);
  }
}

}  // namespace pbms::dpd
