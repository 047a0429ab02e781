#include "engine/validation/elastica.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "engine/core/error.h"

namespace fibrenet::validation {

namespace {

// State along the beam: theta, theta', x / L, y / L.
using State = std::array<double, 4>;

// d/ds of the state, s the rest arc length; stretch = 1 + lambda sin(theta).
State Derivative(const State& y, double alpha, double lambda) {
  const double c = std::cos(y[0]), s = std::sin(y[0]), stretch = 1.0 + lambda * s;
  return {y[1], -alpha * stretch * c, stretch * c, stretch * s};
}

State Axpy(const State& y, double h, const State& k) {
  return {y[0] + h * k[0], y[1] + h * k[1], y[2] + h * k[2], y[3] + h * k[3]};
}

// Integrates from the clamp with root curvature kappa0 to the tip (s = 1).
State Shoot(double alpha, double lambda, double kappa0, int steps) {
  State y = {0.0, kappa0, 0.0, 0.0};
  const double h = 1.0 / steps;
  for (int k = 0; k < steps; ++k) {
    const State k1 = Derivative(y, alpha, lambda);
    const State k2 = Derivative(Axpy(y, 0.5 * h, k1), alpha, lambda);
    const State k3 = Derivative(Axpy(y, 0.5 * h, k2), alpha, lambda);
    const State k4 = Derivative(Axpy(y, h, k3), alpha, lambda);
    for (int c = 0; c < 4; ++c) y[c] += h / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
  }
  return y;
}

}  // namespace

ElasticaTip SolveElastica(double alpha, int steps) {
  return SolveExtensibleElastica(alpha, 0.0, steps);
}

ElasticaTip SolveExtensibleElastica(double alpha, double lambda, int steps) {
  if (!(alpha >= 0.0 && alpha <= 100.0))
    throw InputError(fmt::format("elastica alpha = {}: must be in [0, 100]", alpha));
  if (steps < 10 || steps > 10'000'000)
    throw InputError(fmt::format("elastica steps = {}: must be in [10, 1e7]", steps));
  if (!(lambda >= 0.0 && lambda <= 0.1))
    throw InputError(fmt::format("elastica lambda = {}: must be in [0, 0.1]", lambda));
  ElasticaTip tip;
  if (alpha == 0.0) return tip;
  // The tip curvature theta'(1) grows with the root curvature theta'(0) = alpha x_tip,
  // which lies in (0, alpha (1 + lambda)]: negative at 0 (the load bends the beam back),
  // positive at the top (x_tip < 1 + lambda). Bisection keeps the bracket, so it cannot
  // wander to another branch.
  double lo = 0.0, hi = alpha * (1.0 + lambda);
  for (int it = 0; it < 200 && hi - lo > 1e-15 * alpha; ++it) {
    const double mid = 0.5 * (lo + hi);
    (Shoot(alpha, lambda, mid, steps)[1] < 0.0 ? lo : hi) = mid;
  }
  const double kappa0 = 0.5 * (lo + hi);
  const State end = Shoot(alpha, lambda, kappa0, steps);
  tip.vertical = end[3];
  tip.horizontal = 1.0 - end[2];
  tip.tip_angle = end[0];
  tip.root_curvature = kappa0;
  return tip;
}

}  // namespace fibrenet::validation
