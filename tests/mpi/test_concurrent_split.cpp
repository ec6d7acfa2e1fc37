// The concurrent DPD/MPM step split across two programs equals the same
// model advanced in one process (METHOD.md §3, the coupling's central
// test). A copper bar, periodic across, free along x: the left half DPD
// particles (the DPD/MPM-grid model with the pair thermostat on), the
// right half elastic MPM points on the same fcc sites with the
// mesoparticle's mass. The first world ranks play dpd_driver, the rest
// mpm_driver, joined by an intercommunicator (CrossProgramLink); every rank
// also runs the monolithic reference alone (InProcessLink, both sides on
// MPI_COMM_SELF) and compares its own particles with it by id.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <map>
#include <memory>

#include "concurrent_bar.hpp"
#include "pbms/coupling/coupling_scheme.hpp"
#include "pbms/coupling/cross_program_link.hpp"
#include "pbms/coupling/in_process_link.hpp"
#include "two_programs.hpp"

using namespace pbms;
using coupling::InterfaceTreatment;

namespace {

using namespace pbms::testing;
ConcurrentBar kBar;  // 8 x 4 x 4 a_cg, 7 grid cells across

struct State {
  std::map<std::int64_t, std::pair<dpd::Vec3, dpd::Vec3>> by_id;  // x, v
  double vmax = 0.0;
};

void record(State& s, std::int64_t id, const dpd::Vec3& x, const dpd::Vec3& v) {
  s.by_id[id] = {x, v};
  s.vmax = std::max(s.vmax, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
}

void record(State& s, const DpdPart& d) {
  for (std::size_t i = 0; i < d.engine->owned(); ++i) {
    const auto& p = d.engine->particles();
    record(s, p.id[i], p.x[i], p.v[i]);
  }
}

void record(State& s, const MpmPart& m) {
  const auto& p = m.engine->points();
  for (std::size_t i = 0; i < p.size(); ++i) record(s, p.id[i], p.x[i], p.v[i]);
}

State monolithic(InterfaceTreatment t, int steps) {
  DpdPart d = dpd_part(MPI_COMM_SELF, kBar);
  MpmPart m = mpm_part(MPI_COMM_SELF, kBar);
  coupling::InProcessLink link(*d.side, *m.side);
  coupling::CouplingScheme scheme({d.side.get(), m.side.get()}, link, t);
  for (int n = 0; n < steps; ++n) scheme.step();
  State s;
  record(s, d);
  record(s, m);
  return s;
}

void split_equals_monolithic(int dpd_ranks, InterfaceTreatment t) {
  constexpr int kSteps = 200;
  const TwoPrograms job(dpd_ranks);
  const grid::RegularGrid g = kBar.grid();
  const double reach = dpd::cu_cg_morse_parameters().cutoff + kSkin;
  State split;
  if (job.program == 0) {
    DpdPart d = dpd_part(job.local, kBar);
    const grid::GridPartition theirs(g, kPeriodic, job.ranks[1]);
    coupling::CrossProgramLink link(job.inter, *d.side, d.grid->partition(), theirs, kBar.band(),
                                    reach);
    coupling::CouplingScheme scheme({d.side.get()}, link, t);
    for (int n = 0; n < kSteps; ++n) scheme.step();
    record(split, d);
  } else {
    MpmPart m = mpm_part(job.local, kBar);
    const grid::GridPartition theirs(g, kPeriodic, job.ranks[0]);
    coupling::CrossProgramLink link(job.inter, *m.side, m.engine->partition(), theirs, kBar.band(),
                                    reach);
    coupling::CouplingScheme scheme({m.side.get()}, link, t);
    for (int n = 0; n < kSteps; ++n) scheme.step();
    record(split, m);
  }
  const State mono = monolithic(t, kSteps);
  double dx = 0.0, dv = 0.0;
  for (const auto& [id, xv] : split.by_id) {
    const auto& ref = mono.by_id.at(id);
    for (std::size_t a = 0; a < 3; ++a) {
      // Across the periodic axes a position may be held at either image.
      double d = xv.first[a] - ref.first[a];
      if (kPeriodic[a]) {
        const double period = kBar.cells_across * kLattice;
        d -= period * std::round(d / period);
      }
      dx = std::max(dx, std::abs(d));
      dv = std::max(dv, std::abs(xv.second[a] - ref.second[a]));
    }
  }
  double worst[2] = {dx, dv};
  MPI_Allreduce(MPI_IN_PLACE, worst, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  const double length = kBar.length();
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) {
    std::printf("%d+%d ranks: max |dx| = %.2e of the length, max |dv| = %.2e of vmax %.2f Å/ps\n",
                job.ranks[0], job.ranks[1], worst[0] / length, worst[1] / mono.vmax, mono.vmax);
  }
  EXPECT_GT(mono.vmax, 1.0);  // thermal motion, not a body at rest
  EXPECT_LE(worst[0], 1e-11 * length);
  EXPECT_LE(worst[1], 1e-10 * mono.vmax);
}

}  // namespace

TEST(ConcurrentSplit, EqualsMonolithicWithoutInterfaceTreatment) {
  split_equals_monolithic(1, InterfaceTreatment::kNone);
}

TEST(ConcurrentSplit, EqualsMonolithicWithTheSeedsInterfaceTreatment) {
  split_equals_monolithic(1, InterfaceTreatment::kSeed);
}

TEST(ConcurrentSplit, EqualsMonolithicWithTheMomentumConservingInterface) {
  split_equals_monolithic(1, InterfaceTreatment::kMomentumConserving);
}

namespace {

dpd::Vec3 momentum_of_job(const TwoPrograms& job, const DpdPart* d, const MpmPart* m) {
  dpd::Vec3 p{0.0, 0.0, 0.0};
  if (d != nullptr) {
    const auto& q = d->engine->particles();
    for (std::size_t i = 0; i < d->engine->owned(); ++i)
      for (std::size_t a = 0; a < 3; ++a) p[a] += q.mass(i) * q.v[i][a];
  }
  if (m != nullptr) {
    const auto& q = m->engine->points();
    for (std::size_t i = 0; i < q.size(); ++i)
      for (std::size_t a = 0; a < 3; ++a) p[a] += q.mass[i] * q.v[i][a];
  }
  (void)job;
  MPI_Allreduce(MPI_IN_PLACE, p.data(), 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return p;
}

// The largest change of the body's total momentum over `steps`, in units
// of M c (M the body's mass, c = sqrt(E / rho) the bar's sound speed).
double momentum_drift(InterfaceTreatment t, int steps) {
  const TwoPrograms job(1);
  const grid::RegularGrid g = kBar.grid();
  const double reach = dpd::cu_cg_morse_parameters().cutoff + kSkin;
  std::unique_ptr<DpdPart> d;
  std::unique_ptr<MpmPart> m;
  std::unique_ptr<coupling::CrossProgramLink> link;
  std::unique_ptr<coupling::CouplingScheme> scheme;
  if (job.program == 0) {
    d = std::make_unique<DpdPart>(dpd_part(job.local, kBar));
    link = std::make_unique<coupling::CrossProgramLink>(
        job.inter, *d->side, d->grid->partition(), grid::GridPartition(g, kPeriodic, job.ranks[1]),
        kBar.band(), reach);
    scheme = std::make_unique<coupling::CouplingScheme>(
        std::vector<coupling::GridSide*>{d->side.get()}, *link, t);
  } else {
    m = std::make_unique<MpmPart>(mpm_part(job.local, kBar));
    link = std::make_unique<coupling::CrossProgramLink>(
        job.inter, *m->side, m->engine->partition(),
        grid::GridPartition(g, kPeriodic, job.ranks[0]), kBar.band(), reach);
    scheme = std::make_unique<coupling::CouplingScheme>(
        std::vector<coupling::GridSide*>{m->side.get()}, *link, t);
  }
  const dpd::Vec3 p0 = momentum_of_job(job, d.get(), m.get());
  double worst = 0.0;
  for (int n = 0; n < steps; ++n) {
    scheme->step();
    if ((n + 1) % 100 != 0) continue;
    const dpd::Vec3 p = momentum_of_job(job, d.get(), m.get());
    for (std::size_t a = 0; a < 3; ++a) worst = std::max(worst, std::abs(p[a] - p0[a]));
  }
  const double body_mass = 4.0 * kBar.cells_x * kBar.cells_across * kBar.cells_across * kMass;
  const double density = kMass / (kLattice * kLattice * kLattice / 4.0);  // g/mol/Å³
  // E / rho in bar Å³/(g/mol) to Å²/ps²: 1 bar Å³ = 6.2415e-7 eV, and
  // 1 eV/(g/mol) = 9648.53 Å²/ps².
  const double c = std::sqrt(kYoung / density * 6.241509e-7 * 9648.533);
  return worst / (body_mass * c);
}

}  // namespace

// A free body with an interface, no boundary conditions, the pair
// thermostat on: the momentum-conserving interface keeps the total linear
// momentum to 1e-12 of M c over 1,000 steps; the seed's treatment, whose
// pair forces on DPD particles from MPM points have no reaction, does not.
TEST(ConcurrentSplit, MomentumConservingInterfaceKeepsTheMomentum) {
  constexpr int kSteps = 1000;
  const double conserving = momentum_drift(InterfaceTreatment::kMomentumConserving, kSteps);
  const double seed = momentum_drift(InterfaceTreatment::kSeed, kSteps);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) {
    std::printf("momentum change over %d steps, in M c: momentum-conserving %.2e, seed %.2e\n",
                kSteps, conserving, seed);
  }
  EXPECT_LE(conserving, 1e-12);
  EXPECT_GT(seed, 1e-6);
}

// dpd_driver's part decomposed too: 2+2 ranks (on 4 world ranks).
TEST(ConcurrentSplit, EqualsMonolithicWithBothPartsDecomposed) {
  if (world_size() < 4) GTEST_SKIP() << "needs 4 ranks";
  for (const auto t : {InterfaceTreatment::kNone, InterfaceTreatment::kSeed,
                       InterfaceTreatment::kMomentumConserving}) {
    split_equals_monolithic(2, t);
  }
}

// The MPM points with DDMP gradients (the seed's recommended future work).
TEST(ConcurrentSplit, EqualsMonolithicWithDdmpGradients) {
  kBar.ddmp = true;
  split_equals_monolithic(world_size() >= 4 ? 2 : 1, InterfaceTreatment::kMomentumConserving);
  kBar.ddmp = false;
}
