#include "engine/interactions/contact.h"

#include <cmath>

#include <fmt/format.h>

namespace fibrenet {

std::string VanWykParams::Validate() const {
  if (!(std::isfinite(C) && C > 0.0)) return fmt::format("C = {} N: must be finite and > 0", C);
  if (!(std::isfinite(g) && g > 1.0)) return fmt::format("g = {}: must be finite and > 1", g);
  if (!(linear_below > 0.0 && linear_below < 1.0))
    return fmt::format("linear_below = {}: must be in (0, 1)", linear_below);
  return {};
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
