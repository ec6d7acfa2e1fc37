// PointGhostsAcrossPrograms: the sending program's ranks each hold the
// points of one box of a grid partition; the receiving program's ranks
// each need every point within reach of their slab, periodic images
// included. Each receiver must get exactly the (point, image) pairs a
// brute-force search over every point finds, with the sender's velocity
// and mass, and only senders within reach may talk to it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include "pbms/coupling/point_ghosts_across_programs.hpp"
#include "pbms/grid/grid_partition.hpp"
#include "two_programs.hpp"

using namespace pbms;
using namespace pbms::coupling;

namespace {

struct Body {
  std::vector<std::int64_t> id;
  std::vector<Vec3> x, v;
  std::vector<double> mass;
};

// The same points on every rank: uniform in the grid's box.
Body all_points(const grid::RegularGrid& g, int n) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Body b;
  for (int i = 0; i < n; ++i) {
    Vec3 x{};
    for (size_t a = 0; a < 3; ++a) x[a] = g.origin()[a] + u(rng) * (g.upper()[a] - g.origin()[a]);
    b.id.push_back(1000 + i);
    b.x.push_back(x);
    b.v.push_back({u(rng), -u(rng), 2.0 * u(rng)});
    b.mass.push_back(1.0 + u(rng));
  }
  return b;
}

// Receiver r of n: a slab along x (free beyond the box on y and z when
// those axes are not periodic, as the DPD decomposition's edge ranks).
SpaceBox slab(const grid::RegularGrid& g, int r, int n, const std::array<bool, 3>& periodic) {
  const double inf = std::numeric_limits<double>::infinity();
  const double lx = g.upper()[0] - g.origin()[0];
  SpaceBox b{{g.origin()[0] + lx * r / n, -inf, -inf},
             {g.origin()[0] + lx * (r + 1) / n, inf, inf}};
  if (!periodic[0]) {
    if (r == 0) b.lo[0] = -inf;
    if (r == n - 1) b.hi[0] = inf;
  }
  for (size_t a = 1; a < 3; ++a) {
    if (periodic[a]) {
      b.lo[a] = g.origin()[a];
      b.hi[a] = g.upper()[a];
    }
  }
  return b;
}

using Key = std::tuple<std::int64_t, long, long, long>;  // id and image position, 1e-9 Å

Key key(std::int64_t id, const Vec3& x) {
  return {id, std::lround(x[0] * 1e9), std::lround(x[1] * 1e9), std::lround(x[2] * 1e9)};
}

void check_split(int first, const std::array<bool, 3>& periodic) {
  const TwoPrograms job(first);
  const grid::RegularGrid g({0.0, -2.0, 1.0}, 2.0, {10, 6, 5});
  const double reach = 3.1;
  PeriodicLengths lengths;
  for (size_t a = 0; a < 3; ++a)
    if (periodic[a]) lengths.length[a] = g.upper()[a] - g.origin()[a];
  const Body body = all_points(g, 3000);
  const grid::GridPartition senders(g, periodic, job.ranks[0]);
  const auto cell_box = [&](int r) {
    const auto c = senders.cells_of(r);
    SpaceBox b;
    for (size_t a = 0; a < 3; ++a) {
      b.lo[a] = g.origin()[a] + c.lo[a] * g.cell_size();
      b.hi[a] = g.origin()[a] + c.hi[a] * g.cell_size();
    }
    return b;
  };

  if (job.program == 0) {  // the MPM side
    Body mine;
    for (size_t i = 0; i < body.id.size(); ++i) {
      if (senders.owner_of(body.x[i]) != job.rank) continue;
      mine.id.push_back(body.id[i]);
      mine.x.push_back(body.x[i]);
      mine.v.push_back(body.v[i]);
      mine.mass.push_back(body.mass[i]);
    }
    PointGhostsAcrossPrograms ghosts(job.inter, PointGhostsAcrossPrograms::Side::kSender,
                                     cell_box(job.rank), reach, lengths);
    ghosts.send(mine.id, mine.x, mine.v, mine.mass);
    return;
  }
  const SpaceBox box = slab(g, job.rank, job.ranks[1], periodic);
  PointGhostsAcrossPrograms ghosts(job.inter, PointGhostsAcrossPrograms::Side::kReceiver, box,
                                   reach, lengths);
  const auto& got = ghosts.receive();

  // Brute force: every image of every point within reach of the box.
  std::set<Key> expect, seen;
  for (size_t i = 0; i < body.id.size(); ++i) {
    for (int sz = -1; sz <= 1; ++sz)
      for (int sy = -1; sy <= 1; ++sy)
        for (int sx = -1; sx <= 1; ++sx) {
          const std::array<int, 3> s{sx, sy, sz};
          Vec3 x = body.x[i];
          bool ok = true;
          for (size_t a = 0; a < 3; ++a) {
            if (s[a] != 0 && !periodic[a]) ok = false;
            x[a] += s[a] * lengths.length[a];
            const double gap = std::max({box.lo[a] - x[a], x[a] - box.hi[a], 0.0});
            ok = ok && gap <= reach;
          }
          if (ok) expect.insert(key(body.id[i], x));
        }
  }
  int wrong = 0;
  for (const auto& gp : got) {
    const auto i = static_cast<size_t>(gp.id - 1000);
    wrong += (gp.v != body.v[i] || gp.mass != body.mass[i]) ? 1 : 0;
    wrong += seen.insert(key(gp.id, gp.x)).second ? 0 : 1;  // no duplicates
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(seen, expect) << "receiver " << job.rank << " of split " << first << "+"
                          << job.ranks[1];
  EXPECT_FALSE(expect.empty());
  // Only senders whose cells come within reach talk to this rank.
  for (const int peer : ghosts.peers()) {
    const SpaceBox c = cell_box(peer);
    bool near = false;
    for (int sx = -1; sx <= 1; ++sx) {
      if (sx != 0 && !periodic[0]) continue;
      const double lo = c.lo[0] + sx * lengths.length[0], hi = c.hi[0] + sx * lengths.length[0];
      near = near || (lo <= box.hi[0] + reach && hi >= box.lo[0] - reach);
    }
    EXPECT_TRUE(near) << "sender " << peer << " talks to receiver " << job.rank;
  }
}

}  // namespace

TEST(PointGhostsAcrossPrograms, ReceiversGetExactlyThePointsWithinReach) {
  for (int first = 1; first < world_size(); ++first) {
    for (const auto periodic :
         {std::array<bool, 3>{false, false, false}, std::array<bool, 3>{true, false, true},
          std::array<bool, 3>{true, true, true}}) {
      check_split(first, periodic);
    }
  }
}
