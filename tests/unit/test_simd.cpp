#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "pbms/simd/lanes8_transpose.hpp"

using namespace pbms;

namespace {
// A value that names its row and column, so that a misplaced one says where
// it came from.
double tag(int row, int col) {
  return 100.0 * row + col;
}
}  // namespace

TEST(Lanes8Transpose, Transpose8SwapsRowsAndColumnsAndIsItsOwnInverse) {
  Lanes8 r[8];
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) r[i][j] = tag(i, j);
  }
  simd::transpose8(r);
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) EXPECT_EQ(r[i][j], tag(j, i)) << i << "," << j;
  }
  simd::transpose8(r);
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) EXPECT_EQ(r[i][j], tag(i, j));
  }
}

TEST(Lanes8Transpose, ThreeVectorsSplitIntoComponentsAndBack) {
  std::array<std::array<double, 3>, 10> v{};  // 8 used, guards either side
  for (int k = 0; k < 10; ++k) {
    for (int d = 0; d < 3; ++d) v[k][d] = tag(k, d);
  }
  Lanes8 c[3];
  simd::deinterleave3(&v[1], c);
  for (int d = 0; d < 3; ++d) {
    for (int k = 0; k < 8; ++k) EXPECT_EQ(c[d][k], tag(k + 1, d));
  }
  for (int d = 0; d < 3; ++d) c[d] += 0.5;
  simd::interleave3(c, &v[1]);
  for (int k = 0; k < 10; ++k) {
    const double shift = (k >= 1 && k <= 8) ? 0.5 : 0.0;
    for (int d = 0; d < 3; ++d) EXPECT_EQ(v[k][d], tag(k, d) + shift) << k << "," << d;
  }
}

TEST(Lanes8Transpose, NineFieldRecordsLoadAndStoreInPlace) {
  std::vector<double> records(9 * 8 + 2);  // one guard value after
  for (int k = 0; k < 8; ++k) {
    for (int f = 0; f < 9; ++f) records[9 * k + f] = tag(k, f);
  }
  records[72] = -1.0;
  records[73] = -2.0;
  Lanes8 c[9];
  simd::load_records9(records.data(), c);
  for (int f = 0; f < 9; ++f) {
    for (int k = 0; k < 8; ++k) EXPECT_EQ(c[f][k], tag(k, f));
  }
  for (int f = 0; f < 9; ++f) c[f] *= 2.0;
  simd::store_records9(c, records.data());
  for (int k = 0; k < 8; ++k) {
    for (int f = 0; f < 9; ++f) EXPECT_EQ(records[9 * k + f], 2.0 * tag(k, f));
  }
  EXPECT_EQ(records[72], -1.0);
  EXPECT_EQ(records[73], -2.0);
}
