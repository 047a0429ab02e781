#include "campaigns/campaign_file.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "campaigns/analytic_evaluator.h"
#include "campaigns/campaign_toml.h"
#include "engine/core/error.h"
#include "optimizer/closest_match.h"
#include "optimizer/sobol.h"

namespace fibrenet::campaigns {
namespace {

namespace fs = std::filesystem;
using optimizer::Constraint;
using optimizer::ObjectiveKind;
using optimizer::Target;

std::string ReadFile(const std::string& path, const std::string& what) {
  // An ifstream opens a folder without complaint and reads nothing from it.
  std::error_code ec;  // a name the system refuses (too long, say) is not a folder
  if (fs::is_directory(path, ec)) {
    throw InputError(fmt::format("{}: cannot read {}: it is a folder; accepted: a TOML file", path,
                                 what));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(fmt::format("{}: cannot read {} ({})", path, what,
                                 fs::exists(path, ec) ? "permission denied"
                                 : ec                 ? ec.message()
                                                      : "no such file"));
  }
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

optimizer::Variable ReadVariable(const toml::table& table, const std::string& file,
                                 const std::string& path) {
  CampaignTable r(table, file, path);
  r.Accept({"key", "lower", "upper", "log", "integer", "start"});
  optimizer::Variable v;
  v.key = r.RequireString("key", "a numeric scene key such as \"fibres.length_mm\"");
  if (v.key.empty()) r.Fail("key", "must not be empty");
  v.lower = r.RequireNumber("lower", "a finite number below upper");
  v.upper = r.RequireNumber("upper", "a finite number above lower");
  v.log = r.Bool("log").value_or(false);
  v.integer = r.Bool("integer").value_or(false);
  v.start = r.Number("start");
  r.Finish();
  if (std::string message = v.validate(); !message.empty()) r.Fail("", message);
  return v;
}

optimizer::DesignSpace ReadVariables(CampaignTable& top) {
  const toml::array* array = top.Array("variables");
  if (!array || array->empty()) {
    top.Fail("variables", "at least one [[variables]] table is required (key, lower, upper)");
  }
  std::vector<optimizer::Variable> variables;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string path = fmt::format("variables[{}]", i);
    const toml::table* table = array->get(i)->as_table();
    if (!table) {
      throw InputError(Located(top.file(), LineOf(*array->get(i)), path,
                               "must be a table with key, lower, upper"));
    }
    variables.push_back(ReadVariable(*table, top.file(), path));
    if (!seen.insert(variables.back().key).second) {
      throw InputError(Located(top.file(), LineOf(*table), path + ".key",
                               "'" + variables.back().key + "' is declared twice"));
    }
  }
  return optimizer::DesignSpace(std::move(variables));
}

std::optional<double> PositiveScale(CampaignTable& r) {
  if (!r.Has("scale")) return std::nullopt;
  return r.NumberAtLeast("scale", 1.0, 0.0, false);
}

std::vector<Constraint> ReadConstraints(const toml::table& table, const std::string& file,
                                        const std::string& path) {
  std::vector<Constraint> constraints;
  for (const auto& [key, node] : table) {
    const std::string metric(key.str());
    const std::string metric_path = path + "." + metric;
    const toml::table* bounds = node.as_table();
    if (!bounds) {
      throw InputError(Located(file, LineOf(node), metric_path,
                               "must be a table such as { min = 0.7 }, { max = 300 } or both"));
    }
    CampaignTable r(*bounds, file, metric_path);
    r.Accept({"min", "max", "scale"});
    Constraint c;
    c.metric = metric;
    c.min = r.Number("min");
    c.max = r.Number("max");
    c.scale = PositiveScale(r);
    r.Finish();
    if (!c.min && !c.max) r.Fail("", "needs min, max or both");
    constraints.push_back(c);
  }
  return constraints;
}

std::vector<Target> ReadTargets(const toml::table& table, const std::string& file,
                                const std::string& path) {
  std::vector<Target> targets;
  for (const auto& [key, node] : table) {
    Target t;
    t.metric = std::string(key.str());
    const std::string metric_path = path + "." + t.metric;
    if (const auto* i = node.as_integer()) {
      t.value = static_cast<double>(i->get());
    } else if (const auto* f = node.as_floating_point()) {
      t.value = f->get();
    } else if (const toml::table* spec = node.as_table()) {
      CampaignTable r(*spec, file, metric_path);
      r.Accept({"value", "weight", "scale"});
      t.value = r.RequireNumber("value", "the target value of the metric");
      t.weight = r.NumberAtLeast("weight", 1.0, 0.0, false);
      t.scale = PositiveScale(r);
      r.Finish();
    } else {
      throw InputError(Located(file, LineOf(node), metric_path,
                               "must be a number or a table { value, weight, scale }"));
    }
    targets.push_back(t);
  }
  if (targets.empty()) {
    throw InputError(Located(file, LineOf(table), path, "needs at least one metric"));
  }
  return targets;
}

void ReadGoals(CampaignTable& top, CampaignSpec& spec) {
  const toml::table* table = top.Table("goals");
  if (!table) top.Fail("goals", "a [goals] table is required (minimise, maximise or targets)");
  CampaignTable r(*table, top.file(), "goals");
  r.Accept(
      {"minimise", "maximise", "targets", "constraints", "constraint_weight", "failure_penalty"});
  optimizer::Objective objective;
  int n_objectives = 0;
  if (auto m = r.String("minimise")) {
    objective.kind = ObjectiveKind::kMinimise;
    objective.metric = *m;
    ++n_objectives;
  }
  if (auto m = r.String("maximise")) {
    objective.kind = ObjectiveKind::kMaximise;
    objective.metric = *m;
    ++n_objectives;
  }
  if (const toml::table* targets = r.Table("targets")) {
    objective.kind = ObjectiveKind::kTargets;
    objective.targets = ReadTargets(*targets, top.file(), "goals.targets");
    ++n_objectives;
  }
  if (n_objectives != 1) {
    r.Fail("", fmt::format("needs exactly one objective: minimise = \"METRIC\", maximise = "
                           "\"METRIC\" or a [goals.targets] table; got {}",
                           n_objectives));
  }
  if (objective.kind != ObjectiveKind::kTargets && objective.metric.empty()) {
    r.Fail(objective.kind == ObjectiveKind::kMinimise ? "minimise" : "maximise",
           "must name a metric");
  }
  std::vector<Constraint> constraints;
  if (const toml::table* c = r.Table("constraints")) {
    constraints = ReadConstraints(*c, top.file(), "goals.constraints");
  }
  const double weight = r.NumberAtLeast("constraint_weight", 1e3, 0.0, true);
  if (r.Has("failure_penalty")) {
    spec.failure_penalty = r.RequireNumber("failure_penalty", "a finite number");
    if (!std::isfinite(*spec.failure_penalty)) r.Fail("failure_penalty", "must be finite");
  }
  r.Finish();
  spec.goals = optimizer::Goals(std::move(objective), std::move(constraints), weight);
  if (std::string message = spec.goals.validate(); !message.empty()) r.Fail("", message);
}

void ReadAlgorithm(CampaignTable& top, CampaignSpec& spec) {
  const toml::table* table = top.Table("algorithm");
  if (!table) return;
  CampaignTable r(*table, top.file(), "algorithm");
  r.Accept({"name", "local", "initial_step", "population", "seed"});
  optimizer::AlgorithmOptions a;
  std::vector<std::string> names;
  for (const auto& info : optimizer::Algorithms()) names.push_back(info.name);
  a.name = r.RequireString("name", fmt::format("{}", fmt::join(names, ", ")));
  const optimizer::AlgorithmInfo* info = optimizer::FindAlgorithm(a.name);
  if (!info) {
    r.Fail("name", fmt::format("unknown algorithm '{}'{}; accepted: {}", a.name,
                               optimizer::DidYouMean(a.name, names), fmt::join(names, ", ")));
  }
  if (auto local = r.String("local")) {
    const std::vector<std::string> locals = optimizer::LocalAlgorithmNames();
    if (!info->needs_local) {
      r.Fail("local",
             fmt::format("only AUGLAG and G_MLSL* take a local algorithm, not {}", a.name));
    }
    if (std::find(locals.begin(), locals.end(), *local) == locals.end()) {
      r.Fail("local", fmt::format("unknown local algorithm '{}'{}; accepted: {}", *local,
                                  optimizer::DidYouMean(*local, locals), fmt::join(locals, ", ")));
    }
    a.local = *local;
  }
  a.initial_step = r.NumberAtLeast("initial_step", 0.1, 0.0, false);
  if (a.initial_step > 1.0) {
    r.Fail("initial_step", fmt::format("must lie in (0, 1] (a fraction of each variable's "
                                       "range); got {}",
                                       a.initial_step));
  }
  a.population = r.Count("population", 0, 0, kMaxPopulation);
  a.seed =
      static_cast<std::uint64_t>(r.IntegerAtLeast("seed", static_cast<std::int64_t>(spec.seed), 0));
  r.Finish();
  const bool two_or_more = spec.space.size() >= 2;
  if (!two_or_more &&
      (a.name == "LN_BOBYQA" || a.name == "LN_NEWUOA_BOUND" || a.local == "LN_BOBYQA" ||
       a.local == "LN_NEWUOA_BOUND" || (info->needs_local && a.local.empty()))) {
    r.Fail("name",
           "Powell's quadratic-model methods (LN_BOBYQA, LN_NEWUOA_BOUND) need at least "
           "two variables; choose LN_COBYLA, LN_SBPLX or LN_NELDERMEAD");
  }
  spec.algorithm = a;
}

void ReadBudget(CampaignTable& top, CampaignSpec& spec) {
  const toml::table* table = top.Table("budget");
  toml::table empty;
  CampaignTable r(table ? *table : empty, top.file(), "budget");
  r.Accept({"max_evaluations", "max_wall_s", "xtol_rel", "ftol_rel", "ftol_abs"});
  spec.stop.max_evaluations = r.Count("max_evaluations", 100, 1, kMaxEvaluations);
  spec.max_wall_s = r.Has("max_wall_s") ? r.NumberAtLeast("max_wall_s", 0.0, 0.0, false) : 0.0;
  spec.stop.xtol_rel = r.NumberAtLeast("xtol_rel", 1e-4, 0.0, true);
  spec.stop.ftol_rel = r.NumberAtLeast("ftol_rel", 1e-6, 0.0, true);
  spec.stop.ftol_abs = r.NumberAtLeast("ftol_abs", 0.0, 0.0, true);
  r.Finish();
}

// Flattens nested tables into dotted keys: [fidelity.overrides] fibres.count = 8 and
// "fibres.count" = 8 mean the same.
void FlattenOverrides(const toml::table& table, const std::string& prefix, const std::string& file,
                      const std::string& path, std::map<std::string, double>& out) {
  for (const auto& [key, node] : table) {
    const std::string name =
        prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
    if (const toml::table* nested = node.as_table()) {
      FlattenOverrides(*nested, name, file, path, out);
    } else if (const auto* i = node.as_integer()) {
      out[name] = static_cast<double>(i->get());
    } else if (const auto* f = node.as_floating_point()) {
      out[name] = f->get();
    } else {
      throw InputError(Located(file, LineOf(node), path + "." + name,
                               "must be a number (a numeric scene override)"));
    }
  }
}

void ReadFidelities(CampaignTable& top, CampaignSpec& spec, int replicates) {
  const toml::array* array = top.Array("fidelity");
  if (!array) {
    optimizer::Fidelity f;
    f.replicates = replicates;
    spec.fidelities.push_back(f);
    return;
  }
  if (array->empty()) top.Fail("fidelity", "needs at least one [[fidelity]] level when present");
  std::set<std::string> names;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string path = fmt::format("fidelity[{}]", i);
    const toml::table* table = array->get(i)->as_table();
    if (!table) {
      throw InputError(Located(top.file(), LineOf(*array->get(i)), path, "must be a table"));
    }
    CampaignTable r(*table, top.file(), path);
    r.Accept({"name", "replicates", "top", "overrides"});
    optimizer::Fidelity f;
    f.name = r.RequireString("name", "a unique name such as \"coarse\"");
    if (f.name.empty()) r.Fail("name", "must not be empty");
    if (!names.insert(f.name).second) r.Fail("name", "'" + f.name + "' is used twice");
    f.replicates = r.Count("replicates", replicates, 1, kMaxReplicates);
    if (r.Has("top") && i == 0) {
      r.Fail("top", "the first level explores; top applies to later (confirming) levels");
    }
    f.top = r.Count("top", 1, 1, kMaxEvaluations);
    if (const toml::table* overrides = r.Table("overrides")) {
      FlattenOverrides(*overrides, "", top.file(), path + ".overrides", f.overrides);
    }
    r.Finish();
    for (const auto& v : spec.space.variables()) {
      if (f.overrides.count(v.key)) {
        r.Fail("overrides", "'" + v.key + "' is a design variable and cannot be overridden");
      }
    }
    spec.fidelities.push_back(f);
  }
}

void ReadDoe(CampaignTable& top, CampaignSpec& spec) {
  const toml::table* table = top.Table("doe");
  if (!table) return;
  CampaignTable r(*table, top.file(), "doe");
  r.Accept({"method", "points", "seed"});
  optimizer::DoeOptions doe;
  const std::string method = r.String("method").value_or("sobol");
  const auto& methods = optimizer::DoeMethodNames();
  if (method == "sobol") {
    doe.method = optimizer::DoeMethod::kSobol;
  } else if (method == "lhs") {
    doe.method = optimizer::DoeMethod::kLatinHypercube;
  } else {
    r.Fail("method", fmt::format("unknown method '{}'{}; accepted: {}", method,
                                 optimizer::DidYouMean(method, methods), fmt::join(methods, ", ")));
  }
  doe.points = r.Count("points", 16, 1, kMaxEvaluations);
  doe.seed =
      static_cast<std::uint64_t>(r.IntegerAtLeast("seed", static_cast<std::int64_t>(spec.seed), 0));
  r.Finish();
  if (doe.method == optimizer::DoeMethod::kSobol &&
      spec.space.size() > static_cast<std::size_t>(optimizer::SobolSequence::kMaxDimensions)) {
    r.Fail("method", fmt::format("sobol supports up to {} variables, the campaign has {}; use "
                                 "\"lhs\"",
                                 optimizer::SobolSequence::kMaxDimensions, spec.space.size()));
  }
  spec.doe = doe;
}

std::string ResolveScene(CampaignTable& top, const std::string& base_dir, ParseMode mode) {
  const std::string scene =
      top.RequireString("base_scene", "a scene file path or analytic:NAME (a test function)");
  if (scene.rfind(kAnalyticPrefix, 0) == 0) {
    const std::string name = scene.substr(kAnalyticPrefix.size());
    const std::vector<std::string> known = AnalyticFunctionNames();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      top.Fail("base_scene",
               fmt::format("unknown analytic test function '{}'{}; accepted: {}", name,
                           optimizer::DidYouMean(name, known), fmt::join(known, ", ")));
    }
    return scene;
  }
  if (scene.empty()) top.Fail("base_scene", "must not be empty");
  fs::path p(scene);
  if (p.is_relative()) p = fs::path(base_dir) / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (mode == ParseMode::kFull && !fs::is_regular_file(p, ec)) {
    // A name the system refuses outright (too long, say) gets the system's words.
    const bool refused = ec && ec != std::errc::no_such_file_or_directory;
    top.Fail("base_scene",
             fmt::format("scene file '{}' {}", p.string(),
                         refused ? "cannot be read: " + ec.message() : "does not exist"));
  }
  return p.string();
}

}  // namespace

std::string HashText(std::string_view text) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001B3ULL;
  }
  return fmt::format("{:016x}", h);
}

CampaignSpec ParseCampaign(std::string_view text, const std::string& source,
                           const std::string& base_dir, ParseMode mode) {
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError(Located(source, static_cast<int>(e.source().begin.line), "",
                             "TOML syntax error: " + std::string(e.description())));
  }
  if (root.empty()) {
    throw InputError(fmt::format("{}: the file is empty; accepted: a campaign with base_scene, "
                                 "[[variables]], [goals] and [algorithm] or [doe] "
                                 "(docs/campaigns.md)",
                                 source));
  }
  CampaignSpec spec;
  spec.text = std::string(text);
  CampaignTable top(root, source, "");
  top.Accept({"name", "base_scene", "seed", "replicates", "variables", "goals", "algorithm",
              "budget", "fidelity", "doe"});
  spec.name = top.String("name").value_or(fs::path(source).stem().string());
  if (spec.name.empty()) top.Fail("name", "must not be empty");
  spec.base_scene = ResolveScene(top, base_dir, mode);
  spec.seed = static_cast<std::uint64_t>(top.IntegerAtLeast("seed", 1, 0));
  const int replicates = top.Count("replicates", 1, 1, kMaxReplicates);
  spec.space = ReadVariables(top);
  ReadGoals(top, spec);
  ReadAlgorithm(top, spec);
  ReadBudget(top, spec);
  ReadFidelities(top, spec, replicates);
  ReadDoe(top, spec);
  top.Finish();
  if (!spec.algorithm && !spec.doe) {
    top.Fail("", "a campaign needs an [algorithm] table, a [doe] table, or both");
  }

  if (mode == ParseMode::kStored) return spec;

  // The identity of the campaign for resuming: everything but the budget (which may grow to
  // extend a campaign), plus the content of the base scene file.
  toml::table identity = root;
  identity.erase("budget");
  std::ostringstream canonical;
  canonical << identity;
  if (spec.base_scene.rfind(kAnalyticPrefix, 0) != 0) {
    canonical << "\nscene " << HashText(ReadFile(spec.base_scene, "base scene"));
  }
  spec.spec_hash = HashText(canonical.str());
  return spec;
}

CampaignSpec LoadCampaignFile(const std::string& path) {
  const std::string text = ReadFile(path, "campaign file");
  const std::string base_dir = fs::absolute(fs::path(path)).parent_path().string();
  CampaignSpec spec = ParseCampaign(text, path, base_dir);
  spec.path = path;
  return spec;
}

}  // namespace fibrenet::campaigns
