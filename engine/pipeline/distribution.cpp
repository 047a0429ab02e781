#include "engine/pipeline/distribution.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

namespace fibrenet::pipeline {

namespace {

constexpr double kTwoPi = 6.28318530717958647692;
constexpr int kMaxRejections = 10000;

// Draws from `draw` until the value lies in [lo, hi]; clamps after too many tries (only
// reachable for a window far out in the tail, which Validate does not forbid).
template <class Draw>
double Truncated(Draw draw, double lo, double hi) {
  double x = draw();
  for (int k = 0; k < kMaxRejections && (x < lo || x > hi); ++k) x = draw();
  return std::clamp(x, lo, hi);
}

}  // namespace

const char* DistributionName(DistributionKind kind) {
  switch (kind) {
    case DistributionKind::kFixed: return "fixed";
    case DistributionKind::kNormal: return "normal";
    case DistributionKind::kLognormal: return "lognormal";
    case DistributionKind::kUniform: return "uniform";
    case DistributionKind::kTable: return "table";
  }
  return "?";
}

double UniformUnit(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

double StandardNormal(std::mt19937_64& rng) {
  const double u1 = 1.0 - UniformUnit(rng);  // in (0, 1]
  const double u2 = UniformUnit(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

Distribution Distribution::Fixed(double v) {
  Distribution d;
  d.value = v;
  return d;
}

Distribution Distribution::Uniform(double lo, double hi) {
  Distribution d;
  d.kind = DistributionKind::kUniform;
  d.min = lo;
  d.max = hi;
  return d;
}

Distribution Distribution::Normal(double mean, double sd) {
  Distribution d;
  d.kind = DistributionKind::kNormal;
  d.mean = mean;
  d.sd = sd;
  return d;
}

double Distribution::Sample(std::mt19937_64& rng) const {
  switch (kind) {
    case DistributionKind::kFixed:
      return value;
    case DistributionKind::kUniform:
      return min + (max - min) * UniformUnit(rng);
    case DistributionKind::kNormal:
      if (sd == 0.0) return std::clamp(mean, min, max);
      return Truncated([&] { return mean + sd * StandardNormal(rng); }, min, max);
    case DistributionKind::kLognormal: {
      if (sd == 0.0) return std::clamp(mean, min, max);
      const double s2 = std::log1p((sd * sd) / (mean * mean));
      const double mu = std::log(mean) - 0.5 * s2;
      const double s = std::sqrt(s2);
      return Truncated([&] { return std::exp(mu + s * StandardNormal(rng)); }, min, max);
    }
    case DistributionKind::kTable: {
      if (weights.empty()) {
        const auto k = static_cast<std::size_t>(UniformUnit(rng) * values.size());
        return values[std::min(k, values.size() - 1)];
      }
      const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
      double u = UniformUnit(rng) * total;
      for (std::size_t k = 0; k < values.size(); ++k) {
        if (u < weights[k]) return values[k];
        u -= weights[k];
      }
      return values.back();
    }
  }
  return value;
}

double Distribution::Mean() const {
  switch (kind) {
    case DistributionKind::kFixed: return value;
    case DistributionKind::kUniform: return 0.5 * (min + max);
    case DistributionKind::kNormal:
    case DistributionKind::kLognormal: return mean;
    case DistributionKind::kTable: {
      if (values.empty()) return 0.0;
      if (weights.empty())
        return std::accumulate(values.begin(), values.end(), 0.0) / values.size();
      double sw = 0.0, swx = 0.0;
      for (std::size_t k = 0; k < values.size(); ++k) {
        sw += weights[k];
        swx += weights[k] * values[k];
      }
      return swx / sw;
    }
  }
  return value;
}

double Distribution::Lowest() const {
  switch (kind) {
    case DistributionKind::kFixed: return value;
    case DistributionKind::kUniform: return min;
    case DistributionKind::kNormal: return sd == 0.0 ? std::clamp(mean, min, max) : min;
    case DistributionKind::kLognormal: return sd == 0.0 ? mean : std::max(min, 0.0);
    case DistributionKind::kTable:
      return values.empty() ? 0.0 : *std::min_element(values.begin(), values.end());
  }
  return value;
}

double Distribution::Highest() const {
  switch (kind) {
    case DistributionKind::kFixed: return value;
    case DistributionKind::kUniform: return max;
    case DistributionKind::kNormal:
    case DistributionKind::kLognormal: return sd == 0.0 ? std::clamp(mean, min, max) : max;
    case DistributionKind::kTable:
      return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
  }
  return value;
}

Distribution Distribution::Scaled(double factor) const {
  Distribution d = *this;
  d.value *= factor;
  d.mean *= factor;
  d.sd *= factor;
  d.min *= factor;
  d.max *= factor;
  for (double& v : d.values) v *= factor;
  return d;
}

std::string Distribution::Validate() const {
  auto finite = [](double v) { return std::isfinite(v); };
  switch (kind) {
    case DistributionKind::kFixed:
      if (!finite(value)) return "value must be finite";
      return {};
    case DistributionKind::kUniform:
      if (!finite(min) || !finite(max)) return "uniform needs finite min and max";
      if (!(min <= max)) return fmt::format("uniform needs min <= max (got {} > {})", min, max);
      return {};
    case DistributionKind::kNormal:
    case DistributionKind::kLognormal:
      if (!finite(mean) || !finite(sd) || sd < 0.0)
        return "needs a finite mean and a finite sd >= 0";
      if (kind == DistributionKind::kLognormal && !(mean > 0.0))
        return fmt::format("lognormal needs mean > 0 (got {})", mean);
      if (!(min <= max)) return fmt::format("truncation needs min <= max (got {} > {})", min, max);
      if (sd == 0.0 && (mean < min || mean > max))
        return "mean lies outside [min, max] with sd = 0";
      return {};
    case DistributionKind::kTable:
      if (values.empty()) return "table needs at least one value";
      for (double v : values)
        if (!finite(v)) return "table values must be finite";
      if (!weights.empty()) {
        if (weights.size() != values.size())
          return fmt::format("table has {} values but {} weights", values.size(), weights.size());
        double total = 0.0;
        for (double w : weights) {
          if (!finite(w) || w < 0.0) return "table weights must be finite and >= 0";
          total += w;
        }
        if (!(total > 0.0)) return "table weights must not all be zero";
      }
      return {};
  }
  return {};
}

}  // namespace fibrenet::pipeline
