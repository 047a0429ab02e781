#include "engine/pipeline/distribution.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace fibrenet::pipeline {
namespace {

double SampleMean(const Distribution& d, int n, std::uint64_t seed, double* sd = nullptr) {
  std::mt19937_64 rng(seed);
  double s = 0.0, s2 = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = d.Sample(rng);
    s += x;
    s2 += x * x;
  }
  const double mean = s / n;
  if (sd) *sd = std::sqrt(s2 / n - mean * mean);
  return mean;
}

TEST(Distribution, FixedAlwaysGivesItsValue) {
  std::mt19937_64 rng(1);
  const Distribution d = Distribution::Fixed(1.92e-3);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(d.Sample(rng), 1.92e-3);
  EXPECT_EQ(d.Mean(), 1.92e-3);
}

TEST(Distribution, UniformStaysInItsBoundsWithTheRightMean) {
  const Distribution d = Distribution::Uniform(16.0, 35.0);
  std::mt19937_64 rng(3);
  for (int k = 0; k < 1000; ++k) {
    const double x = d.Sample(rng);
    EXPECT_GE(x, 16.0);
    EXPECT_LE(x, 35.0);
  }
  EXPECT_NEAR(SampleMean(d, 100000, 5), 25.5, 0.1);
}

TEST(Distribution, NormalAndLognormalMatchTheirMoments) {
  double sd = 0.0;
  EXPECT_NEAR(SampleMean(Distribution::Normal(2.0, 0.5), 200000, 7, &sd), 2.0, 0.01);
  EXPECT_NEAR(sd, 0.5, 0.01);
  Distribution ln;
  ln.kind = DistributionKind::kLognormal;
  ln.mean = 2.0;
  ln.sd = 0.6;
  EXPECT_NEAR(SampleMean(ln, 200000, 9, &sd), 2.0, 0.01);
  EXPECT_NEAR(sd, 0.6, 0.02);
}

TEST(Distribution, TruncationKeepsSamplesInside) {
  Distribution d = Distribution::Normal(0.0, 1.0);
  d.min = -0.5;
  d.max = 0.5;
  std::mt19937_64 rng(11);
  for (int k = 0; k < 1000; ++k) {
    const double x = d.Sample(rng);
    EXPECT_GE(x, -0.5);
    EXPECT_LE(x, 0.5);
  }
}

TEST(Distribution, TableDrawsItsValuesByWeight) {
  Distribution d;
  d.kind = DistributionKind::kTable;
  d.values = {1.0, 2.0};
  d.weights = {3.0, 1.0};
  EXPECT_NEAR(SampleMean(d, 100000, 13), 1.25, 0.01);
  EXPECT_DOUBLE_EQ(d.Mean(), 1.25);
}

TEST(Distribution, SameSeedSameSequence) {
  const Distribution d = Distribution::Normal(1.0, 0.2);
  std::mt19937_64 a(42), b(42);
  for (int k = 0; k < 100; ++k) EXPECT_EQ(d.Sample(a), d.Sample(b));
}

TEST(Distribution, ValidateNamesTheProblem) {
  EXPECT_EQ(Distribution::Uniform(1.0, 2.0).Validate(), "");
  EXPECT_NE(Distribution::Uniform(2.0, 1.0).Validate(), "");
  EXPECT_NE(Distribution::Normal(1.0, -1.0).Validate(), "");
  Distribution empty;
  empty.kind = DistributionKind::kTable;
  EXPECT_NE(empty.Validate(), "");
}

TEST(Distribution, ScaledConvertsUnits) {
  const Distribution d = Distribution::Uniform(16.0, 35.0).Scaled(1e-8);
  EXPECT_DOUBLE_EQ(d.min, 16e-8);
  EXPECT_DOUBLE_EQ(d.max, 35e-8);
}

}  // namespace
}  // namespace fibrenet::pipeline
