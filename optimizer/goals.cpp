#include "optimizer/goals.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::optimizer {
namespace {

double DefaultScale(std::optional<double> scale, double reference) {
  if (scale) return *scale;
  return reference != 0.0 ? std::abs(reference) : 1.0;
}

std::string CheckScale(const std::string& owner, std::optional<double> scale) {
  if (scale && !(std::isfinite(*scale) && *scale > 0.0)) {
    return fmt::format("{}: scale must be finite and > 0; got {}", owner, *scale);
  }
  return {};
}

}  // namespace

Goals::Goals(Objective objective, std::vector<Constraint> constraints, double constraint_weight)
    : objective_(std::move(objective)),
      constraints_(std::move(constraints)),
      constraint_weight_(constraint_weight) {}

std::string Goals::validate() const {
  switch (objective_.kind) {
    case ObjectiveKind::kMinimise:
    case ObjectiveKind::kMaximise:
      if (objective_.metric.empty()) return "objective: the metric name must not be empty";
      break;
    case ObjectiveKind::kTargets:
      if (objective_.targets.empty()) return "objective: targets needs at least one metric";
      for (const Target& t : objective_.targets) {
        const std::string owner = "target '" + t.metric + "'";
        if (!std::isfinite(t.value)) return owner + ": value must be finite";
        if (!(std::isfinite(t.weight) && t.weight > 0.0)) {
          return fmt::format("{}: weight must be finite and > 0; got {}", owner, t.weight);
        }
        if (std::string m = CheckScale(owner, t.scale); !m.empty()) return m;
      }
      break;
  }
  for (const Constraint& c : constraints_) {
    const std::string owner = "constraint '" + c.metric + "'";
    if (!c.min && !c.max) return owner + ": needs min, max or both";
    if ((c.min && !std::isfinite(*c.min)) || (c.max && !std::isfinite(*c.max))) {
      return owner + ": bounds must be finite";
    }
    if (c.min && c.max && !(*c.min <= *c.max)) {
      return fmt::format("{}: min ({}) must not exceed max ({})", owner, *c.min, *c.max);
    }
    if (std::string m = CheckScale(owner, c.scale); !m.empty()) return m;
  }
  if (!(std::isfinite(constraint_weight_) && constraint_weight_ >= 0.0)) {
    return fmt::format("constraint_weight must be finite and >= 0; got {}", constraint_weight_);
  }
  return {};
}

std::vector<std::string> Goals::Metrics() const {
  std::set<std::string> names;
  if (objective_.kind == ObjectiveKind::kTargets) {
    for (const Target& t : objective_.targets) names.insert(t.metric);
  } else {
    names.insert(objective_.metric);
  }
  for (const Constraint& c : constraints_) names.insert(c.metric);
  return {names.begin(), names.end()};
}

std::vector<std::string> Goals::ConstraintLabels() const {
  std::vector<std::string> labels;
  for (const Constraint& c : constraints_) {
    if (c.min) labels.push_back(fmt::format("{} >= {}", c.metric, *c.min));
    if (c.max) labels.push_back(fmt::format("{} <= {}", c.metric, *c.max));
  }
  return labels;
}

GoalValues Goals::Evaluate(const std::map<std::string, double>& metrics) const {
  auto get = [&](const std::string& name) {
    const auto it = metrics.find(name);
    if (it != metrics.end()) return it->second;
    std::vector<std::string> known;
    for (const auto& [key, value] : metrics) known.push_back(key);
    throw InputError(fmt::format("goal metric '{}' is not among the metrics of the scene ({}){}",
                                 name, fmt::join(known, ", "), DidYouMean(name, known)));
  };
  GoalValues values;
  switch (objective_.kind) {
    case ObjectiveKind::kMinimise:
      values.objective = get(objective_.metric);
      break;
    case ObjectiveKind::kMaximise:
      values.objective = -get(objective_.metric);
      break;
    case ObjectiveKind::kTargets: {
      double sum = 0.0;
      for (const Target& t : objective_.targets) {
        const double r = (get(t.metric) - t.value) / DefaultScale(t.scale, t.value);
        sum += t.weight * r * r;
      }
      values.objective = std::sqrt(sum);
      break;
    }
  }
  for (const Constraint& c : constraints_) {
    const double m = get(c.metric);
    if (c.min) values.constraints.push_back((*c.min - m) / DefaultScale(c.scale, *c.min));
    if (c.max) values.constraints.push_back((m - *c.max) / DefaultScale(c.scale, *c.max));
  }
  for (double g : values.constraints) {
    if (g > 0.0) values.violation += g * g;
    if (g > kFeasibilityTolerance) values.feasible = false;
  }
  return values;
}

double Goals::Merit(const GoalValues& values) const {
  return values.objective + constraint_weight_ * values.violation;
}

void FailurePenalty::Observe(double value) {
  if (!std::isfinite(value)) return;
  best_ = best_ ? std::min(*best_, value) : value;
  worst_ = worst_ ? std::max(*worst_, value) : value;
}

double FailurePenalty::Value() const {
  if (fixed_) return *fixed_;
  if (!worst_) return kNoHistory;
  return *worst_ + std::max(1.0, *worst_ - *best_);
}

}  // namespace fibrenet::optimizer
