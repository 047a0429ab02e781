// The design space of a campaign: the scene parameters the optimizer may change, each with
// bounds and an optional log scale or integer constraint.
//
// The optimizer works in the unit cube [0, 1]^n (one coordinate per variable, in declaration
// order); this class maps unit coordinates to designs (scene values) and back. Working in the
// unit cube puts every variable on the same footing for the derivative-free algorithms, whose
// step sizes and tolerances are then fractions of each range.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "optimizer/evaluation.h"

namespace fibrenet::optimizer {

struct Variable {
  std::string key;     // scene key path, e.g. "fibres.length_mm"
  double lower = 0.0;  // bounds in the unit the key names, lower < upper
  double upper = 1.0;
  bool log = false;             // log-uniform between the bounds (requires lower > 0)
  bool integer = false;         // only integer values (bounds must be integers)
  std::optional<double> start;  // initial value for local optimisers; centre if absent

  // Empty if the variable is well formed, else a message naming the key and accepted range.
  std::string validate() const;
};

class DesignSpace {
 public:
  DesignSpace() = default;
  // Throws fibrenet::InputError if a variable is invalid or a key appears twice.
  explicit DesignSpace(std::vector<Variable> variables);

  const std::vector<Variable>& variables() const { return variables_; }
  std::size_t size() const { return variables_.size(); }

  // Maps unit coordinates u (size(), each clamped to [0, 1]) to scene values. Linear variables
  // map u to lower + u (upper - lower); log variables map it geometrically. Integer variables
  // split [0, 1] into (upper - lower + 1) equal bins, one per integer (log integers round the
  // geometric value), so a stratified sample of u stays stratified over the integers.
  Design ToDesign(const std::vector<double>& u) const;

  // Inverse of ToDesign for values inside the bounds (integers map to the centre of their bin).
  // Throws fibrenet::InputError if a key is missing or a value lies outside its bounds.
  std::vector<double> ToUnit(const Design& design) const;

  // The unit coordinates of each variable's `start`, or 0.5 where it has none.
  std::vector<double> StartPoint() const;

 private:
  double Value(const Variable& v, double u) const;
  double Unit(const Variable& v, double value) const;
  std::vector<Variable> variables_;
};

}  // namespace fibrenet::optimizer
