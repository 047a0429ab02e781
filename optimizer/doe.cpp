#include "optimizer/doe.h"

#include <fmt/format.h>

#include <numeric>

#include "engine/core/error.h"
#include "optimizer/random.h"
#include "optimizer/sobol.h"

namespace fibrenet::optimizer {

const std::vector<std::string>& DoeMethodNames() {
  static const std::vector<std::string> names = {"sobol", "lhs"};
  return names;
}

std::vector<std::vector<double>> LatinHypercube(int points, int dimensions, std::uint64_t seed) {
  if (points < 1 || dimensions < 1) {
    throw InputError(
        fmt::format("Latin hypercube: needs points >= 1 and dimensions >= 1; got {} "
                    "points, {} dimensions",
                    points, dimensions));
  }
  SplitMix64 rng(seed);
  std::vector<std::vector<double>> result(points, std::vector<double>(dimensions));
  std::vector<int> strata(points);
  for (int d = 0; d < dimensions; ++d) {
    std::iota(strata.begin(), strata.end(), 0);
    // Fisher-Yates shuffle with the portable generator.
    for (int i = points - 1; i > 0; --i) {
      const auto j = static_cast<int>(rng.Below(static_cast<std::uint64_t>(i) + 1));
      std::swap(strata[i], strata[j]);
    }
    for (int i = 0; i < points; ++i) {
      result[i][d] = (strata[i] + rng.Uniform()) / points;
    }
  }
  return result;
}

std::vector<std::vector<double>> GenerateDoe(const DoeOptions& options, int dimensions) {
  if (options.points < 1) {
    throw InputError(fmt::format("doe.points must be >= 1; got {}", options.points));
  }
  if (options.method == DoeMethod::kLatinHypercube) {
    return LatinHypercube(options.points, dimensions, options.seed);
  }
  SobolSequence sobol(dimensions);
  sobol.Skip(1);
  std::vector<std::vector<double>> result;
  result.reserve(options.points);
  for (int i = 0; i < options.points; ++i) result.push_back(sobol.Next());
  return result;
}

}  // namespace fibrenet::optimizer
