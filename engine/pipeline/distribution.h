// A fibre property given as a fixed value or a statistical distribution, sampled with a
// seeded std::mt19937_64. Sampling is written out here (not std::normal_distribution,
// whose algorithm differs between standard libraries) so that a seed gives the same
// network on every platform: campaigns rely on common random numbers across candidates.
//
// Kinds and their parameters (all in the unit of the property, SI inside the engine):
//   fixed      value
//   normal     mean, sd; truncated to [min, max] by rejection
//   lognormal  mean, sd of the variable itself (not of its logarithm); truncated likewise
//   uniform    min, max
//   table      values (measured data), optional weights; a sample is one of the values
#pragma once

#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace fibrenet::pipeline {

enum class DistributionKind { kFixed, kNormal, kLognormal, kUniform, kTable };

// Name used in scene files ("fixed", "normal", ...).
const char* DistributionName(DistributionKind kind);

struct Distribution {
  DistributionKind kind = DistributionKind::kFixed;
  double value = 0.0;  // kFixed
  double mean = 0.0;   // kNormal, kLognormal
  double sd = 0.0;     // kNormal, kLognormal
  double min = -std::numeric_limits<double>::infinity();  // kUniform; truncation otherwise
  double max = std::numeric_limits<double>::infinity();
  std::vector<double> values;   // kTable
  std::vector<double> weights;  // kTable; empty = equal weights

  static Distribution Fixed(double v);
  static Distribution Uniform(double lo, double hi);
  static Distribution Normal(double mean, double sd);

  double Sample(std::mt19937_64& rng) const;
  // Expected value (of the untruncated law for normal and lognormal).
  double Mean() const;
  // Smallest and largest value a sample can take (infinite when unbounded).
  double Lowest() const;
  double Highest() const;
  // The same law for the variable multiplied by factor > 0 (unit conversion).
  Distribution Scaled(double factor) const;
  // Empty when the parameters are consistent; otherwise what is wrong (no key name: the
  // caller adds it).
  std::string Validate() const;
};

// Uniform double in [0, 1) from 53 random bits.
double UniformUnit(std::mt19937_64& rng);
// Standard normal sample (Box-Muller, one of the pair).
double StandardNormal(std::mt19937_64& rng);

}  // namespace fibrenet::pipeline
