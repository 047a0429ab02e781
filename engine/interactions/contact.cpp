#include "engine/interactions/contact.h"

#include <cmath>

#include <fmt/format.h>

namespace fibrenet {

std::string VanWykParams::Validate() const {
  if (!(std::isfinite(C) && C > 0.0)) return fmt::format("C = {} N: must be finite and > 0", C);
  if (!(std::isfinite(g) && g > 1.0)) return fmt::format("g = {}: must be finite and > 1", g);
  if (!(linear_below > 0.0 && linear_below < 1.0))
    return fmt::format("linear_below = {}: must be in (0, 1)", linear_below);
  if (!(std::isfinite(hard_stiffness) && hard_stiffness >= 0.0))
    return fmt::format("hard_stiffness = {} N/m: must be finite and >= 0", hard_stiffness);
  return {};
}

double CappedRestitution(double zeta) {
  if (zeta <= 0.0) return 1.0;
  // Overlap y(s) in units of v0 / omega_0, time s in units of 1 / omega_0: y'' = -y - 2 zeta y',
  // y(0) = 0, y'(0) = 1. The rebound velocity is -y'(s*) where y + 2 zeta y' first vanishes.
  if (zeta < 1.0) {
    const double w = std::sqrt(1.0 - zeta * zeta);
    // At s*: sin(w s*) = 2 zeta w, cos(w s*) = 2 zeta^2 - 1, and -y'(s*) = exp(-zeta s*).
    const double phase = std::atan2(2.0 * zeta * w, 2.0 * zeta * zeta - 1.0);
    return std::exp(-zeta * phase / w);
  }
  if (zeta == 1.0) return std::exp(-2.0);  // y = s exp(-s), s* = 2
  // Overdamped: y = (exp(r1 s) - exp(r2 s)) / (r1 - r2).
  const double q = std::sqrt(zeta * zeta - 1.0);
  const double r1 = -zeta + q, r2 = -zeta - q;
  const double s = std::log((1.0 + 2.0 * zeta * r2) / (1.0 + 2.0 * zeta * r1)) / (r1 - r2);
  return -(r1 * std::exp(r1 * s) - r2 * std::exp(r2 * s)) / (r1 - r2);
}

void ContactParams::Derive() {
  if (!(restitution < 1.0) || !(restitution > 0.0)) {
    zeta = 0.0;
    return;
  }
  // CappedRestitution falls monotonically to 0 as zeta grows: bisect on a bracket.
  double lo = 0.0, hi = 1.0;
  while (CappedRestitution(hi) > restitution && hi < 1e6) hi *= 2.0;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (CappedRestitution(mid) > restitution ? lo : hi) = mid;
  }
  zeta = 0.5 * (lo + hi);
}

std::string ContactParams::Validate() const {
  if (std::string m = normal.Validate(); !m.empty()) return m;
  if (!(restitution > 0.0 && restitution <= 1.0))
    return fmt::format("restitution = {}: must be in (0, 1]", restitution);
  if (!(std::isfinite(mu) && mu >= 0.0)) return fmt::format("mu = {}: must be >= 0", mu);
  if (!(std::isfinite(tangential_ratio) && tangential_ratio > 0.0))
    return fmt::format("tangential_ratio = {}: must be > 0", tangential_ratio);
  return {};
}

}  // namespace fibrenet
