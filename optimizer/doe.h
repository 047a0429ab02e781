// Design-of-experiments sweeps in the unit cube, run before or instead of optimisation.
//
// - Sobol: points 1..n of the Sobol sequence (optimizer/sobol.h; the origin, point 0, is
//   skipped because it puts every variable at its lower bound at once). Deterministic; take
//   n a power of two for the best balance. Up to SobolSequence::kMaxDimensions variables.
// - Latin hypercube: every variable's range is cut into n equal strata and each stratum is
//   sampled exactly once, at a random position inside it; strata are paired across variables
//   by independent random permutations. Reproducible from `seed`; any number of variables.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fibrenet::optimizer {

enum class DoeMethod { kSobol, kLatinHypercube };

struct DoeOptions {
  DoeMethod method = DoeMethod::kSobol;
  int points = 16;         // >= 1
  std::uint64_t seed = 1;  // Latin hypercube only
};

// The accepted method names, "sobol" and "lhs", in that order.
const std::vector<std::string>& DoeMethodNames();

// `points` points of `dimensions` coordinates in [0, 1). Throws fibrenet::InputError for
// dimensions < 1, points < 1, or too many dimensions for Sobol.
std::vector<std::vector<double>> GenerateDoe(const DoeOptions& options, int dimensions);

// The Latin hypercube itself (see above).
std::vector<std::vector<double>> LatinHypercube(int points, int dimensions, std::uint64_t seed);

}  // namespace fibrenet::optimizer
