// The lane layout changes (simd/lane_transpose.hpp) at every width, 2, 4
// and 8; point_lanes_tests_<set> also runs them built for each instruction
// set the machine runs.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "pbms/simd/lane_transpose.hpp"

using namespace pbms;

namespace {
// A value that names its row and column, so that a misplaced one says where
// it came from.
double tag(int row, int col) {
  return 100.0 * row + col;
}

template <class T>
class LaneTranspose : public testing::Test {};
template <int N>
struct Width {
  static constexpr int W = N;
};
using Widths = testing::Types<Width<2>, Width<4>, Width<8>>;
TYPED_TEST_SUITE(LaneTranspose, Widths);

}  // namespace

TYPED_TEST(LaneTranspose, SwapsRowsAndColumnsAndIsItsOwnInverse) {
  constexpr int W = TypeParam::W;
  simd::Lanes<W> r[W];
  for (int i = 0; i < W; ++i) {
    for (int j = 0; j < W; ++j) r[i][j] = tag(i, j);
  }
  simd::transpose<W>(r);
  for (int i = 0; i < W; ++i) {
    for (int j = 0; j < W; ++j) EXPECT_EQ(r[i][j], tag(j, i)) << i << "," << j;
  }
  simd::transpose<W>(r);
  for (int i = 0; i < W; ++i) {
    for (int j = 0; j < W; ++j) EXPECT_EQ(r[i][j], tag(i, j));
  }
}

TYPED_TEST(LaneTranspose, ThreeVectorsSplitIntoComponentsAndBack) {
  constexpr int W = TypeParam::W;
  std::array<std::array<double, 3>, W + 2> v{};  // W used, guards either side
  for (int k = 0; k < W + 2; ++k) {
    for (int d = 0; d < 3; ++d) v[k][d] = tag(k, d);
  }
  simd::Lanes<W> c[3];
  simd::deinterleave3<W>(&v[1], c);
  for (int d = 0; d < 3; ++d) {
    for (int k = 0; k < W; ++k) EXPECT_EQ(c[d][k], tag(k + 1, d));
  }
  for (int d = 0; d < 3; ++d) c[d] += 0.5;
  simd::interleave3<W>(c, &v[1]);
  for (int k = 0; k < W + 2; ++k) {
    const double shift = (k >= 1 && k <= W) ? 0.5 : 0.0;
    for (int d = 0; d < 3; ++d) EXPECT_EQ(v[k][d], tag(k, d) + shift) << k << "," << d;
  }
}

// Nine fields: whole W x W blocks plus a remainder at every width.
TYPED_TEST(LaneTranspose, NineFieldRecordsLoadAndStoreInPlace) {
  constexpr int W = TypeParam::W;
  std::vector<double> records(9 * W + 2);  // two guard values after
  for (int k = 0; k < W; ++k) {
    for (int f = 0; f < 9; ++f) records[9 * k + f] = tag(k, f);
  }
  records[9 * W] = -1.0;
  records[9 * W + 1] = -2.0;
  simd::Lanes<W> c[9];
  simd::load_records<W, 9>(records.data(), c);
  for (int f = 0; f < 9; ++f) {
    for (int k = 0; k < W; ++k) EXPECT_EQ(c[f][k], tag(k, f));
  }
  for (int f = 0; f < 9; ++f) c[f] *= 2.0;
  simd::store_records<W, 9>(c, records.data());
  for (int k = 0; k < W; ++k) {
    for (int f = 0; f < 9; ++f) EXPECT_EQ(records[9 * k + f], 2.0 * tag(k, f));
  }
  EXPECT_EQ(records[9 * W], -1.0);
  EXPECT_EQ(records[9 * W + 1], -2.0);
}

// Node records (eight doubles, scattered in memory) to lanes and back.
TYPED_TEST(LaneTranspose, EightFieldRecordsToLanesAndBack) {
  constexpr int W = TypeParam::W;
  struct alignas(64) Node {
    Lanes8 lanes;
  };
  std::vector<Node> nodes(3 * W);
  const Lanes8* rec[W];
  for (int k = 0; k < W; ++k) {
    Lanes8& r = nodes[static_cast<size_t>(3 * W - 1 - 2 * k)].lanes;  // out of order
    for (int f = 0; f < 8; ++f) r[f] = tag(k, f);
    rec[k] = &r;
  }
  simd::Lanes<W> c[8];
  simd::records8_to_lanes<W>(rec, c);
  for (int f = 0; f < 8; ++f) {
    for (int k = 0; k < W; ++k) EXPECT_EQ(c[f][k], tag(k, f));
  }
  Lanes8 back[W];
  simd::lanes_to_records8<W>(c, back);
  for (int k = 0; k < W; ++k) {
    for (int f = 0; f < 8; ++f) EXPECT_EQ(back[k][f], tag(k, f));
  }
}

TYPED_TEST(LaneTranspose, AllLanesSetNeedsEveryLane) {
  constexpr int W = TypeParam::W;
  using Mask = simd::IndexLanes<W>;
  const simd::Lanes<W> zero{};
  EXPECT_TRUE(simd::all_lanes_set<W>(zero == 0.0));
  for (int k = 0; k < W; ++k) {
    simd::Lanes<W> x{};
    x[k] = 1.0;
    const Mask m = x == 0.0;
    EXPECT_FALSE(simd::all_lanes_set<W>(m)) << "lane " << k;
  }
}
