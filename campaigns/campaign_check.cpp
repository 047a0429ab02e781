#include "campaigns/campaign_check.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "campaigns/campaign_toml.h"
#include "campaigns/evaluator.h"
#include "campaigns/scene.h"
#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::campaigns {
namespace {

using optimizer::ObjectiveKind;
using optimizer::Target;

// The source line of `path` (e.g. "variables[1]") in the campaign's text, 0 if not found.
int LineOfPath(const CampaignSpec& spec, const std::string& path) {
  try {
    const toml::table root = toml::parse(spec.text);
    const toml::node_view<const toml::node> node = toml::at_path(root, path);
    return node ? LineOf(*node.node()) : 0;
  } catch (const toml::parse_error&) {
    return 0;
  }
}

std::string FileOf(const CampaignSpec& spec) { return spec.path.empty() ? "campaign" : spec.path; }

// The dotted key of the campaign file that names goal metric `metric`.
std::string GoalKey(const optimizer::Goals& goals, const std::string& metric) {
  const optimizer::Objective& o = goals.objective();
  if (o.kind == ObjectiveKind::kMinimise && o.metric == metric) return "goals.minimise";
  if (o.kind == ObjectiveKind::kMaximise && o.metric == metric) return "goals.maximise";
  for (const Target& t : o.targets)
    if (t.metric == metric) return "goals.targets." + metric;
  return "goals.constraints." + metric;
}

// The scene's message when it refuses `key` = `value`, or "" when it accepts it.
std::string SceneRefusal(const std::string& text, const std::string& scene, const std::string& key,
                         double value) {
  try {
    ParseScene(text, scene, {{key, value}});
    return "";
  } catch (const InputError& e) {
    return e.what();
  }
}

void CheckSceneKeys(const CampaignSpec& spec) {
  std::string text;
  try {
    text = ReadSceneText(spec.base_scene);
    ParseScene(text, spec.base_scene);
  } catch (const InputError& e) {
    throw InputError(Located(FileOf(spec), LineOfPath(spec, "base_scene"), "base_scene", e.what()));
  }
  const auto& variables = spec.space.variables();
  for (std::size_t i = 0; i < variables.size(); ++i) {
    const optimizer::Variable& v = variables[i];
    const std::string at_lower = SceneRefusal(text, spec.base_scene, v.key, v.lower);
    const std::string at_upper = SceneRefusal(text, spec.base_scene, v.key, v.upper);
    if (at_lower.empty() && at_upper.empty()) continue;
    // Refused at both bounds: the key itself (or both bounds) is wrong; else the one bound.
    const char* field = at_upper.empty() ? "lower" : at_lower.empty() ? "upper" : "key";
    const std::string path = fmt::format("variables[{}].{}", i, field);
    const std::string what =
        at_upper.empty()   ? fmt::format("{} = {:g} is refused by the base scene: {}", v.key,
                                         v.lower, at_lower)
        : at_lower.empty() ? fmt::format("{} = {:g} is refused by the base scene: {}", v.key,
                                         v.upper, at_upper)
                           : fmt::format("'{}' is refused by the base scene (at lower = {:g} and "
                                         "upper = {:g}): {}",
                                         v.key, v.lower, v.upper, at_lower);
    throw InputError(Located(FileOf(spec), LineOfPath(spec, path), path, what));
  }
  for (std::size_t i = 0; i < spec.fidelities.size(); ++i) {
    std::vector<Override> overrides;
    for (const auto& [key, value] : spec.fidelities[i].overrides) overrides.push_back({key, value});
    try {
      ParseScene(text, spec.base_scene, overrides);
    } catch (const InputError& e) {
      const std::string path = fmt::format("fidelity[{}].overrides", i);
      throw InputError(Located(FileOf(spec), LineOfPath(spec, fmt::format("fidelity[{}]", i)),
                               path, fmt::format("refused by the base scene: {}", e.what())));
    }
  }
}

void CheckAnalyticFunction(const CampaignSpec& spec) {
  const Evaluator evaluate = MakeEvaluator(spec.base_scene);
  const optimizer::Design start = spec.space.ToDesign(spec.space.StartPoint());
  optimizer::EvaluationResult probe;
  try {
    probe = evaluate(start, optimizer::Fidelity{}, spec.seed);
  } catch (const InputError& e) {
    throw InputError(Located(FileOf(spec), LineOfPath(spec, "base_scene"), "base_scene", e.what()));
  }
  std::vector<std::string> produced;
  for (const auto& [name, value] : probe.metrics) produced.push_back(name);
  for (const std::string& metric : spec.goals.Metrics()) {
    if (probe.metrics.count(metric)) continue;
    const std::string key = GoalKey(spec.goals, metric);
    throw InputError(Located(FileOf(spec), LineOfPath(spec, key), key,
                             fmt::format("metric '{}' is not produced by {}{}; accepted: {}",
                                         metric, spec.base_scene,
                                         optimizer::DidYouMean(metric, produced),
                                         fmt::join(produced, ", "))));
  }
  // Each override alone, at 0: that checks its key without waiting (analytic.sleep_s) or
  // needing a meaningful value; a failed evaluation (RunError) is no bad input.
  for (std::size_t i = 0; i < spec.fidelities.size(); ++i) {
    for (const auto& [key, value] : spec.fidelities[i].overrides) {
      optimizer::Fidelity alone;
      alone.name = spec.fidelities[i].name;
      alone.overrides[key] = 0.0;
      try {
        evaluate(start, alone, spec.seed);
      } catch (const InputError& e) {
        const std::string path = fmt::format("fidelity[{}].overrides", i);
        throw InputError(Located(FileOf(spec), LineOfPath(spec, fmt::format("fidelity[{}]", i)),
                                 path, e.what()));
      } catch (const RunError&) {
      }
    }
  }
}

}  // namespace

void CheckAgainstBaseScene(const CampaignSpec& spec) {
  if (spec.base_scene.rfind(kAnalyticPrefix, 0) == 0) {
    CheckAnalyticFunction(spec);
  } else {
    CheckSceneKeys(spec);
  }
}

}  // namespace fibrenet::campaigns
