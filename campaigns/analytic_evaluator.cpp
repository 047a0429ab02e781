#include "campaigns/analytic_evaluator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "engine/core/error.h"
#include "optimizer/closest_match.h"
#include "optimizer/random.h"

namespace fibrenet::campaigns {
namespace {

using optimizer::Design;
using optimizer::EvaluationResult;
using optimizer::Fidelity;

struct Settings {
  double bias = 0.0;
  double noise = 0.01;
  double fail_above = HUGE_VAL;
  double sleep_s = 0.0;
};

Settings ReadSettings(const Fidelity& fidelity) {
  static const std::vector<std::string> known = {"analytic.bias", "analytic.fail_above",
                                                 "analytic.noise", "analytic.sleep_s"};
  Settings s;
  for (const auto& [key, value] : fidelity.overrides) {
    if (key == "analytic.bias")
      s.bias = value;
    else if (key == "analytic.noise")
      s.noise = value;
    else if (key == "analytic.fail_above")
      s.fail_above = value;
    else if (key == "analytic.sleep_s")
      s.sleep_s = value;
    else {
      throw InputError(fmt::format(
          "fidelity '{}': override '{}' is not a key of the analytic "
          "test functions{}; accepted: {}",
          fidelity.name, key, optimizer::DidYouMean(key, known), fmt::join(known, ", ")));
    }
  }
  return s;
}

// A standard normal deviate from the seed (Box-Muller), identical on every platform.
double Normal(std::uint64_t seed) {
  optimizer::SplitMix64 rng(seed);
  const double u1 = 1.0 - rng.Uniform();  // in (0, 1]
  const double u2 = rng.Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

std::vector<double> Values(const Design& design) {
  std::vector<double> x;
  for (const auto& [key, value] : design) x.push_back(value);
  return x;
}

EvaluationResult Finish(const Settings& s, const std::vector<double>& x,
                        std::map<std::string, double> metrics) {
  if (s.sleep_s > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(s.sleep_s));
  double sum = 0.0;
  for (double xi : x) sum += xi;
  if (sum > s.fail_above) {
    throw RunError(
        fmt::format("analytic test failure: sum of the variables {} exceeds "
                    "analytic.fail_above = {}",
                    sum, s.fail_above));
  }
  EvaluationResult r;
  r.metrics = std::move(metrics);
  for (const auto& [name, value] : r.metrics) r.units.emplace(name, "1");
  return r;
}

EvaluationResult Quadratic(const Design& design, const Fidelity& fidelity, std::uint64_t seed) {
  const Settings s = ReadSettings(fidelity);
  const std::vector<double> x = Values(design);
  double quadratic = s.bias, sum = 0.0, product = 1.0;
  for (double xi : x) {
    quadratic += (xi - 1.0) * (xi - 1.0);
    sum += xi;
    product *= xi;
  }
  return Finish(s, x,
                {{"quadratic", quadratic},
                 {"sum", sum},
                 {"product", product},
                 {"noisy_quadratic", quadratic + s.noise * Normal(seed)}});
}

EvaluationResult SoftStrong(const Design& design, const Fidelity& fidelity, std::uint64_t seed) {
  const Settings s = ReadSettings(fidelity);
  const std::vector<double> x = Values(design);
  if (x.size() < 2) {
    throw InputError("analytic:softstrong needs at least two design variables");
  }
  const double a = x[0], b = x[1];
  return Finish(s, x,
                {{"tensile_strength", 100.0 * a / (1.0 + b) + s.bias},
                 {"softness_index", b / (1.0 + a) + s.noise * Normal(seed)},
                 {"basis_weight", 10.0 + 5.0 * a + 5.0 * b}});
}

}  // namespace

std::vector<std::string> AnalyticFunctionNames() { return {"quadratic", "softstrong"}; }

Evaluator MakeAnalyticEvaluator(const std::string& name) {
  if (name == "quadratic") return &Quadratic;
  if (name == "softstrong") return &SoftStrong;
  const std::vector<std::string> known = AnalyticFunctionNames();
  throw InputError(fmt::format("unknown analytic test function '{}'{}; accepted: {}", name,
                               optimizer::DidYouMean(name, known), fmt::join(known, ", ")));
}

}  // namespace fibrenet::campaigns
