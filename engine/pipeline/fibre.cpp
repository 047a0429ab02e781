#include "engine/pipeline/fibre.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

namespace fibrenet::pipeline {

namespace {

// Checks that every value the distribution can produce lies in (lo, hi].
std::string CheckRange(const char* name, const Distribution& d, double lo, double hi,
                       const char* unit) {
  if (std::string why = d.Validate(); !why.empty()) return fmt::format("{}: {}", name, why);
  if (!(d.Lowest() > lo) || !(d.Highest() <= hi))
    return fmt::format("{}: values must lie in ({:g}, {:g}] {}", name, lo, hi, unit);
  return {};
}

}  // namespace

std::string FibreSpec::Validate() const {
  const double inf = std::numeric_limits<double>::infinity();
  for (const std::string& why :
       {CheckRange("length", length, 0.0, 1.0, "m"),
        CheckRange("diameter", diameter, 0.0, 1e-3, "m"),
        CheckRange("coarseness", coarseness, 0.0, 1e-3, "kg/m"),
        CheckRange("youngs_modulus", youngs_modulus, 0.0, 1e12, "Pa"),
        CheckRange("shear_modulus", shear_modulus, 0.0, 1e12, "Pa"),
        CheckRange("strength", strength, 0.0, inf, "N"),
        CheckRange("bend_angle", bend_angle, -kPi - 1e-12, kPi, "rad"),
        CheckRange("twist_angle", twist_angle, -2 * kPi - 1e-12, 2 * kPi, "rad")})
    if (!why.empty()) return why;
  if (segments < 1 || segments > 10000)
    return fmt::format("segments = {}: must lie in [1, 10000]", segments);
  if (!(maxwell_tau >= 0.0) || std::isinf(maxwell_tau))
    return fmt::format("maxwell_tau = {} s: must be >= 0 and finite (0 = elastic)", maxwell_tau);
  if (!(yield_moment > 0.0)) return fmt::format("yield_moment = {} N m: must be > 0", yield_moment);
  if (diameter.Highest() >= length.Lowest())
    return "diameter: the thickest fibre must be shorter than its length (diameter < length)";
  return {};
}

FibreProperties SampleFibre(const FibreSpec& spec, std::mt19937_64& rng) {
  FibreProperties f;
  f.length = spec.length.Sample(rng);
  f.diameter = spec.diameter.Sample(rng);
  f.coarseness = spec.coarseness.Sample(rng);
  f.youngs_modulus = spec.youngs_modulus.Sample(rng);
  f.shear_modulus = spec.shear_modulus.Sample(rng);
  f.strength = spec.strength.Sample(rng);
  f.bend.resize(spec.segments - 1);
  f.twist.resize(spec.segments - 1);
  for (int s = 0; s + 1 < spec.segments; ++s) {
    f.bend[s] = spec.bend_angle.Sample(rng);
    f.twist[s] = spec.twist_angle.Sample(rng);
  }
  return f;
}

std::vector<Vec3> Centreline(const FibreProperties& f) {
  const std::size_t segments = f.bend.size() + 1;
  const double step = f.length / static_cast<double>(segments);
  std::vector<Vec3> points{Vec3::Zero()};
  Vec3 t = Vec3::UnitX();  // direction of the current segment
  Vec3 n = Vec3::UnitZ();  // normal of the current bending plane
  points.push_back(t * step);
  for (std::size_t s = 0; s + 1 < segments; ++s) {
    n = Eigen::AngleAxisd(f.twist[s], t) * n;
    t = (Eigen::AngleAxisd(f.bend[s], n) * t).normalized();
    n = (n - n.dot(t) * t).normalized();  // keep the frame orthonormal against round-off
    points.push_back(points.back() + t * step);
  }
  return points;
}

int ParticlesPerFibre(double length, double spacing) {
  return std::max(2, static_cast<int>(std::lround(length / spacing)));
}

std::vector<Vec3> PointsAlong(const std::vector<Vec3>& polyline, int n) {
  std::vector<double> cumulative{0.0};
  for (std::size_t k = 1; k < polyline.size(); ++k)
    cumulative.push_back(cumulative.back() + (polyline[k] - polyline[k - 1]).norm());
  const double total = cumulative.back();
  std::vector<Vec3> points;
  points.reserve(n);
  std::size_t seg = 1;
  for (int k = 0; k < n; ++k) {
    const double s = (k + 0.5) * total / n;
    while (seg + 1 < polyline.size() && cumulative[seg] < s) ++seg;
    const double span = cumulative[seg] - cumulative[seg - 1];
    const double a = span > 0.0 ? (s - cumulative[seg - 1]) / span : 0.0;
    points.push_back(polyline[seg - 1] + a * (polyline[seg] - polyline[seg - 1]));
  }
  return points;
}

}  // namespace fibrenet::pipeline
