#include "optimizer/doe.h"

#include <gtest/gtest.h>

#include <set>

#include "engine/core/error.h"
#include "optimizer/sobol.h"

namespace fibrenet::optimizer {
namespace {

TEST(Sobol, FirstPointsMatchTheJoeKuoSequence) {
  // Points 0..7 of the Gray-code Sobol sequence in three dimensions (as SciPy's
  // scipy.stats.qmc.Sobol(3, scramble=False) gives them).
  const double expected[8][3] = {{0, 0, 0},
                                 {0.5, 0.5, 0.5},
                                 {0.75, 0.25, 0.25},
                                 {0.25, 0.75, 0.75},
                                 {0.375, 0.375, 0.625},
                                 {0.875, 0.875, 0.125},
                                 {0.625, 0.125, 0.875},
                                 {0.125, 0.625, 0.375}};
  SobolSequence s(3);
  for (const auto& row : expected) {
    const auto p = s.Next();
    for (int d = 0; d < 3; ++d) EXPECT_DOUBLE_EQ(p[d], row[d]);
  }
}

// The defining property of a (t, s)-sequence in base 2 for each one-dimensional projection:
// the first 2^m points put exactly one point in each interval [k / 2^m, (k + 1) / 2^m).
TEST(Sobol, EveryDimensionIsStratified) {
  const int m = 10, n = 1 << m;
  SobolSequence s(SobolSequence::kMaxDimensions);
  std::vector<std::vector<double>> points;
  for (int i = 0; i < n; ++i) points.push_back(s.Next());
  for (int d = 0; d < SobolSequence::kMaxDimensions; ++d) {
    std::set<int> cells;
    for (const auto& p : points) {
      ASSERT_GE(p[d], 0.0);
      ASSERT_LT(p[d], 1.0);
      cells.insert(static_cast<int>(p[d] * n));
    }
    EXPECT_EQ(static_cast<int>(cells.size()), n) << "dimension " << d + 1;
  }
}

// The quality parameter t of a two-dimensional projection: the first 2^m points form a
// (t, m, 2)-net when every elementary interval [a / 2^i, (a + 1) / 2^i) x [b / 2^j, ...) with
// i + j = m - t holds exactly 2^t points. Joe and Kuo chose their direction numbers for small t
// in two dimensions; a wrong table entry shows up as a large t.
int NetQuality(const std::vector<std::vector<double>>& points, int m, int a, int b) {
  for (int t = 0; t <= m; ++t) {
    bool net = true;
    for (int i = 0; i <= m - t && net; ++i) {
      const int j = m - t - i;
      std::vector<int> counts(std::size_t{1} << (m - t), 0);
      for (const auto& p : points) {
        const int x = static_cast<int>(p[a] * (1 << i)), y = static_cast<int>(p[b] * (1 << j));
        ++counts[static_cast<std::size_t>((x << j) | y)];
      }
      for (int c : counts) net = net && c == (1 << t);
    }
    if (net) return t;
  }
  return m;
}

TEST(Sobol, TwoDimensionalProjectionsAreNets) {
  const int m = 10;
  SobolSequence s(12);
  std::vector<std::vector<double>> points;
  for (int i = 0; i < (1 << m); ++i) points.push_back(s.Next());
  EXPECT_EQ(NetQuality(points, m, 0, 1), 0);  // dimensions 1 and 2: a (0, m, 2)-net
  for (int a = 0; a < 12; ++a) {
    for (int b = a + 1; b < 12; ++b) {
      EXPECT_LE(NetQuality(points, m, a, b), 4) << "dimensions " << a + 1 << ", " << b + 1;
    }
  }
}

TEST(Sobol, SkipEqualsDrawing) {
  SobolSequence a(5), b(5);
  for (int i = 0; i < 37; ++i) a.Next();
  b.Skip(37);
  EXPECT_EQ(a.Next(), b.Next());
  EXPECT_THROW(SobolSequence(0), InputError);
  EXPECT_THROW(SobolSequence(SobolSequence::kMaxDimensions + 1), InputError);
}

TEST(Doe, SobolSweepSkipsTheOrigin) {
  DoeOptions o;
  o.points = 4;
  const auto points = GenerateDoe(o, 2);
  ASSERT_EQ(points.size(), 4u);
  EXPECT_EQ(points[0], (std::vector<double>{0.5, 0.5}));
  EXPECT_EQ(points[1], (std::vector<double>{0.75, 0.25}));
}

TEST(Doe, LatinHypercubeHasOnePointPerStratum) {
  const int n = 50, dims = 6;
  const auto points = LatinHypercube(n, dims, 42);
  ASSERT_EQ(static_cast<int>(points.size()), n);
  for (int d = 0; d < dims; ++d) {
    std::set<int> strata;
    for (const auto& p : points) strata.insert(static_cast<int>(p[d] * n));
    EXPECT_EQ(static_cast<int>(strata.size()), n);
  }
  EXPECT_EQ(LatinHypercube(n, dims, 42), points);  // reproducible
  EXPECT_NE(LatinHypercube(n, dims, 43), points);
}

TEST(Doe, RejectsBadSizes) {
  DoeOptions o;
  o.points = 0;
  EXPECT_THROW(GenerateDoe(o, 2), InputError);
  o.points = 4;
  EXPECT_THROW(GenerateDoe(o, 0), InputError);
  o.method = DoeMethod::kLatinHypercube;
  EXPECT_THROW(GenerateDoe(o, 0), InputError);
}

}  // namespace
}  // namespace fibrenet::optimizer
