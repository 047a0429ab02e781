// Built-in analytic test functions, used as the base scene "analytic:NAME" of a campaign.
// They stand in for the DEM pipeline in tests, demos and the MPI check: cheap, deterministic
// in (design, fidelity, seed), with smooth metrics of the design variables.
//
// x_1..x_n are the design values in the order of their keys (sorted). Every metric has unit "1".
//
//   analytic:quadratic
//     quadratic       = sum_i (x_i - 1)^2 + bias
//     sum             = sum_i x_i
//     product         = prod_i x_i
//     noisy_quadratic = quadratic + noise * N(0, 1), the normal deviate drawn from the seed
//   analytic:softstrong  (a toy tissue trade-off of two variables a = x_1, b = x_2; needs n >= 2)
//     tensile_strength = 100 a / (1 + b) + bias
//     softness_index   = b / (1 + a) + noise * N(0, 1)
//     basis_weight     = 10 + 5 a + 5 b
//
// Fidelity overrides accepted (anything else is an InputError, as an unknown scene key is):
//   analytic.bias        added as shown above (a coarse level's systematic error), default 0
//   analytic.noise       standard deviation of the noise terms, default 0.01
//   analytic.fail_above  the evaluation fails (RunError) when sum_i x_i exceeds it
//   analytic.sleep_s     sleep this long per evaluation [s] (to test time limits and kills)
#pragma once

#include <string>
#include <vector>

#include "campaigns/evaluator.h"

namespace fibrenet::campaigns {

// "quadratic", "softstrong".
std::vector<std::string> AnalyticFunctionNames();

// Throws fibrenet::InputError for an unknown name.
Evaluator MakeAnalyticEvaluator(const std::string& name);

}  // namespace fibrenet::campaigns
