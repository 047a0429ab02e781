#include "optimizer/design_space.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "engine/core/error.h"

namespace fibrenet::optimizer {

std::string Variable::validate() const {
  if (key.empty()) return "variable key must not be empty";
  if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower < upper)) {
    return fmt::format("variable '{}': bounds must be finite with lower < upper; got [{}, {}]", key,
                       lower, upper);
  }
  if (log && !(lower > 0.0)) {
    return fmt::format("variable '{}': log scale needs lower > 0; got lower = {}", key, lower);
  }
  if (integer && (lower != std::round(lower) || upper != std::round(upper))) {
    return fmt::format("variable '{}': integer variable needs integer bounds; got [{}, {}]", key,
                       lower, upper);
  }
  if (start && !(*start >= lower && *start <= upper)) {
    return fmt::format("variable '{}': start must lie in [{}, {}]; got {}", key, lower, upper,
                       *start);
  }
  return {};
}

DesignSpace::DesignSpace(std::vector<Variable> variables) : variables_(std::move(variables)) {
  std::set<std::string> seen;
  for (const Variable& v : variables_) {
    if (std::string message = v.validate(); !message.empty()) throw InputError(message);
    if (!seen.insert(v.key).second) {
      throw InputError(fmt::format("variable '{}' is declared twice", v.key));
    }
  }
}

double DesignSpace::Value(const Variable& v, double u) const {
  u = std::clamp(u, 0.0, 1.0);
  if (v.integer && !v.log) {
    const double n = v.upper - v.lower + 1.0;
    return std::min(v.upper, v.lower + std::floor(u * n));
  }
  double value = v.log ? std::exp(std::log(v.lower) + u * (std::log(v.upper) - std::log(v.lower)))
                       : v.lower + u * (v.upper - v.lower);
  if (v.integer) value = std::round(value);
  // Guard the ends against rounding in exp/log so that values never leave the bounds.
  return std::clamp(value, v.lower, v.upper);
}

double DesignSpace::Unit(const Variable& v, double value) const {
  if (!(value >= v.lower && value <= v.upper)) {
    throw InputError(fmt::format("variable '{}': value {} lies outside its bounds [{}, {}]", v.key,
                                 value, v.lower, v.upper));
  }
  if (v.integer && !v.log) {
    const double n = v.upper - v.lower + 1.0;
    return (std::round(value) - v.lower + 0.5) / n;
  }
  if (v.log) return (std::log(value) - std::log(v.lower)) / (std::log(v.upper) - std::log(v.lower));
  return (value - v.lower) / (v.upper - v.lower);
}

Design DesignSpace::ToDesign(const std::vector<double>& u) const {
  if (u.size() != variables_.size()) {
    throw Error(fmt::format("design space has {} variables, got {} coordinates", variables_.size(),
                            u.size()));
  }
  Design design;
  for (std::size_t i = 0; i < variables_.size(); ++i) {
    design[variables_[i].key] = Value(variables_[i], u[i]);
  }
  return design;
}

std::vector<double> DesignSpace::ToUnit(const Design& design) const {
  std::vector<double> u;
  u.reserve(variables_.size());
  for (const Variable& v : variables_) {
    const auto it = design.find(v.key);
    if (it == design.end()) throw InputError(fmt::format("design lacks variable '{}'", v.key));
    u.push_back(Unit(v, it->second));
  }
  return u;
}

std::vector<double> DesignSpace::StartPoint() const {
  std::vector<double> u;
  u.reserve(variables_.size());
  for (const Variable& v : variables_) u.push_back(v.start ? Unit(v, *v.start) : 0.5);
  return u;
}

}  // namespace fibrenet::optimizer
