// Goals of a campaign: constraints on metrics and one objective, turned into the numbers an
// optimiser needs (an objective where lower is better and normalised constraint values).
//
// Conventions, documented for users in docs/campaigns.md:
// - Objective (lower is better): minimise m -> m; maximise m -> -m; distance to targets ->
//   sqrt(sum_i w_i ((m_i - t_i) / s_i)^2) with scale s_i = |t_i| by default (relative error).
// - Constraint values g (feasible when g <= 0), normalised by a scale s (|bound| by default,
//   1 for a zero bound): `min = b` gives g = (b - m) / s, `max = b` gives g = (m - b) / s.
// - Merit, for algorithms without native constraints: objective + w sum_i max(0, g_i)^2 with
//   the campaign's constraint weight w.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fibrenet::optimizer {

// A bound on one metric: min, max, or both (a band).
struct Constraint {
  std::string metric;
  std::optional<double> min;
  std::optional<double> max;
  std::optional<double> scale;  // normalisation of the violation, > 0; default |bound|
};

// One term of a distance-to-targets objective.
struct Target {
  std::string metric;
  double value = 0.0;
  double weight = 1.0;          // > 0
  std::optional<double> scale;  // > 0; default |value| (or 1 for a zero target)
};

enum class ObjectiveKind { kMinimise, kMaximise, kTargets };

struct Objective {
  ObjectiveKind kind = ObjectiveKind::kMinimise;
  std::string metric;           // for kMinimise and kMaximise
  std::vector<Target> targets;  // for kTargets
};

// The goals evaluated at one set of metrics.
struct GoalValues {
  double objective = 0.0;           // lower is better
  std::vector<double> constraints;  // normalised, feasible when <= 0; see ConstraintLabels()
  double violation = 0.0;           // sum of max(0, g)^2
  bool feasible = true;             // every g <= kFeasibilityTolerance
};

class Goals {
 public:
  // Normalised constraint values up to this count as met (absorbs round-off at the bound).
  static constexpr double kFeasibilityTolerance = 1e-9;

  Goals() = default;
  Goals(Objective objective, std::vector<Constraint> constraints, double constraint_weight);

  // Empty if well formed, else a message naming the offending goal and the accepted range.
  std::string validate() const;

  const Objective& objective() const { return objective_; }
  const std::vector<Constraint>& constraints() const { return constraints_; }
  double constraint_weight() const { return constraint_weight_; }

  // Every metric the goals read, sorted, without repeats.
  std::vector<std::string> Metrics() const;

  // One label per constraint value, in the order of GoalValues::constraints, e.g.
  // "softness_index >= 0.7".
  std::vector<std::string> ConstraintLabels() const;
  std::size_t NumConstraintValues() const { return ConstraintLabels().size(); }

  // Throws fibrenet::InputError if a metric the goals need is missing from `metrics`, naming
  // it, the metrics that are there and the closest one.
  GoalValues Evaluate(const std::map<std::string, double>& metrics) const;

  // objective + constraint_weight * violation.
  double Merit(const GoalValues& values) const;

 private:
  Objective objective_;
  std::vector<Constraint> constraints_;
  double constraint_weight_ = 1e3;
};

// The penalty handed to the optimiser for a failed candidate (documented in docs/campaigns.md):
// a fixed value if the campaign sets one, else worst + max(1, worst - best) over the values of
// the finished candidates seen so far (in evaluation order), or kNoHistory before any finished.
// Failed candidates also get kConstraintValue for every constraint value (violated, by the
// constraint's whole scale). Because it depends only on the history in evaluation order, a
// resumed campaign replays the same penalties.
class FailurePenalty {
 public:
  static constexpr double kNoHistory = 1e3;
  static constexpr double kConstraintValue = 1.0;

  explicit FailurePenalty(std::optional<double> fixed = std::nullopt) : fixed_(fixed) {}

  // A value handed to the optimiser for a finished (not failed) candidate.
  void Observe(double value);
  double Value() const;

 private:
  std::optional<double> fixed_;
  std::optional<double> best_;
  std::optional<double> worst_;
};

}  // namespace fibrenet::optimizer
