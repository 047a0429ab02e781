// The only file of fibrenet that includes NLopt. It uses NLopt's C interface: callbacks are
// plain functions, and no C++ exception ever crosses NLopt's C frames (they are caught, NLopt
// is told to stop, and they are rethrown after nlopt_optimize returns).
#include "optimizer/nlopt_driver.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>

#include "engine/core/error.h"
#include "optimizer/closest_match.h"

namespace fibrenet::optimizer {
namespace {

struct Entry {
  AlgorithmInfo info;
  nlopt_algorithm algorithm;
};

const std::vector<Entry>& Table() {
  static const std::vector<Entry> table = {
      {{"LN_COBYLA", false, true, false, "linear approximations, native constraints (Powell)"},
       NLOPT_LN_COBYLA},
      {{"LN_BOBYQA", false, false, false, "quadratic model, bound constrained (Powell)"},
       NLOPT_LN_BOBYQA},
      {{"LN_SBPLX", false, false, false, "Nelder-Mead on subspaces (Rowan's Subplex)"},
       NLOPT_LN_SBPLX},
      {{"LN_NELDERMEAD", false, false, false, "Nelder-Mead simplex"}, NLOPT_LN_NELDERMEAD},
      {{"LN_NEWUOA_BOUND", false, false, false, "quadratic model (Powell), bounds"},
       NLOPT_LN_NEWUOA_BOUND},
      {{"LN_PRAXIS", false, false, false, "principal axis (Brent)"}, NLOPT_LN_PRAXIS},
      {{"GN_DIRECT", true, false, false, "DIviding RECTangles (Jones)"}, NLOPT_GN_DIRECT},
      {{"GN_DIRECT_L", true, false, false, "locally biased DIRECT (Gablonsky)"}, NLOPT_GN_DIRECT_L},
      {{"GN_DIRECT_L_RAND", true, false, false, "locally biased DIRECT, randomised"},
       NLOPT_GN_DIRECT_L_RAND},
      {{"GN_ORIG_DIRECT", true, true, false, "original DIRECT code, native constraints"},
       NLOPT_GN_ORIG_DIRECT},
      {{"GN_ORIG_DIRECT_L", true, true, false, "original DIRECT-L code, native constraints"},
       NLOPT_GN_ORIG_DIRECT_L},
      {{"GN_CRS2_LM", true, false, false, "controlled random search with local mutation"},
       NLOPT_GN_CRS2_LM},
      {{"GN_ISRES", true, true, false, "evolution strategy, native constraints"}, NLOPT_GN_ISRES},
      {{"GN_ESCH", true, false, false, "evolutionary algorithm (da Silva Santos)"}, NLOPT_GN_ESCH},
      {{"G_MLSL_LDS", true, false, true, "multi-level single linkage, low-discrepancy starts"},
       NLOPT_G_MLSL_LDS},
      {{"G_MLSL", true, false, true, "multi-level single linkage, random starts"}, NLOPT_G_MLSL},
      {{"AUGLAG", false, true, true, "augmented Lagrangian around a local algorithm"},
       NLOPT_AUGLAG},
  };
  return table;
}

const Entry& Lookup(const std::string& name, const char* what) {
  for (const Entry& e : Table()) {
    if (e.info.name == name) return e;
  }
  std::vector<std::string> names;
  for (const Entry& e : Table()) names.push_back(e.info.name);
  throw InputError(fmt::format("{} '{}' is not a supported NLopt algorithm; accepted: {}{}", what,
                               name, fmt::join(names, ", "), DidYouMean(name, names)));
}

// Owns an nlopt_opt.
struct OptDeleter {
  void operator()(nlopt_opt_s* opt) const { nlopt_destroy(opt); }
};
using OptPtr = std::unique_ptr<nlopt_opt_s, OptDeleter>;

// Shared by the objective and constraint callbacks of one run.
struct CallbackState {
  const ProblemFn* problem = nullptr;
  const std::function<bool()>* stop_requested = nullptr;
  nlopt_opt opt = nullptr;  // the outer optimiser, to force a stop
  std::size_t n_constraints = 0;
  bool native_constraints = false;
  double constraint_weight = 0.0;
  std::vector<double> last_u;  // point of the last evaluation (cache: NLopt asks for the
  ProblemValues last;          // objective and the constraints at one point separately)
  bool have_last = false;
  int calls = 0;
  int max_calls = 0;  // some algorithms (ORIG_DIRECT) overrun NLopt's maxeval: enforced here
  bool stopped = false;
  std::exception_ptr error;
};

// Evaluates `problem` at u unless it was the last point asked for. Returns false (after
// telling NLopt to stop) when the problem threw or the caller wants to stop.
bool EvaluateAt(CallbackState& s, unsigned n, const double* x) {
  if (s.error) return false;
  if (s.have_last && std::equal(x, x + n, s.last_u.begin())) return true;
  if (s.calls >= s.max_calls) {
    nlopt_force_stop(s.opt);
    return false;
  }
  try {
    s.last_u.assign(x, x + n);
    s.last = (*s.problem)(s.last_u);
    s.have_last = true;
    ++s.calls;
    if (s.last.constraints.size() != s.n_constraints) {
      throw Error(fmt::format("problem returned {} constraint values, expected {}",
                              s.last.constraints.size(), s.n_constraints));
    }
    if (*s.stop_requested && (*s.stop_requested)()) {
      s.stopped = true;
      nlopt_force_stop(s.opt);
    }
    return true;
  } catch (...) {
    s.error = std::current_exception();
    s.have_last = false;
    nlopt_force_stop(s.opt);
    return false;
  }
}

double Objective(unsigned n, const double* x, double* /*grad*/, void* data) {
  auto& s = *static_cast<CallbackState*>(data);
  if (!EvaluateAt(s, n, x)) return HUGE_VAL;
  if (s.native_constraints) return s.last.objective;
  double violation = 0.0;
  for (double g : s.last.constraints) violation += g > 0.0 ? g * g : 0.0;
  return s.last.objective + s.constraint_weight * violation;
}

void Constraints(unsigned m, double* result, unsigned n, const double* x, double* /*grad*/,
                 void* data) {
  auto& s = *static_cast<CallbackState*>(data);
  if (!EvaluateAt(s, n, x)) {
    for (unsigned i = 0; i < m; ++i) result[i] = HUGE_VAL;
    return;
  }
  for (unsigned i = 0; i < m; ++i) result[i] = s.last.constraints[i];
}

void Check(nlopt_result r, const std::string& what) {
  if (r < 0) throw RunError(fmt::format("NLopt refused {}: {}", what, nlopt_result_to_string(r)));
}

void SetTolerances(nlopt_opt opt, const StopCriteria& stop, const std::string& name) {
  Check(nlopt_set_xtol_rel(opt, stop.xtol_rel), name + " xtol_rel");
  Check(nlopt_set_ftol_rel(opt, stop.ftol_rel), name + " ftol_rel");
  Check(nlopt_set_ftol_abs(opt, stop.ftol_abs), name + " ftol_abs");
}

}  // namespace

const std::vector<AlgorithmInfo>& Algorithms() {
  static const std::vector<AlgorithmInfo> infos = [] {
    std::vector<AlgorithmInfo> v;
    for (const Entry& e : Table()) v.push_back(e.info);
    return v;
  }();
  return infos;
}

const AlgorithmInfo* FindAlgorithm(const std::string& name) {
  for (const AlgorithmInfo& info : Algorithms()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

std::vector<std::string> LocalAlgorithmNames() {
  std::vector<std::string> names;
  for (const Entry& e : Table()) {
    if (!e.info.global && !e.info.needs_local) names.push_back(e.info.name);
  }
  return names;
}

OptimiseResult Minimise(const AlgorithmOptions& options, const StopCriteria& stop,
                        const std::vector<double>& start, std::size_t n_constraints,
                        double constraint_weight, const ProblemFn& problem,
                        const std::function<bool()>& stop_requested) {
  const Entry& entry = Lookup(options.name, "algorithm");
  const auto n = static_cast<unsigned>(start.size());
  if (n == 0) throw InputError("the design space has no variables to optimise");
  if (stop.max_evaluations < 1) {
    throw InputError(fmt::format("max_evaluations must be >= 1; got {}", stop.max_evaluations));
  }
  OptPtr opt(nlopt_create(entry.algorithm, n));
  if (!opt) throw RunError("NLopt could not create algorithm " + options.name);

  CallbackState state;
  state.problem = &problem;
  state.stop_requested = &stop_requested;
  state.opt = opt.get();
  state.n_constraints = n_constraints;
  state.native_constraints = entry.info.constraints && n_constraints > 0;
  state.constraint_weight = constraint_weight;
  state.max_calls = stop.max_evaluations;

  Check(nlopt_set_lower_bounds1(opt.get(), 0.0), "the lower bounds");
  Check(nlopt_set_upper_bounds1(opt.get(), 1.0), "the upper bounds");
  Check(nlopt_set_min_objective(opt.get(), &Objective, &state), "the objective");
  if (state.native_constraints) {
    const std::vector<double> tolerances(n_constraints, 1e-8);
    Check(nlopt_add_inequality_mconstraint(opt.get(), static_cast<unsigned>(n_constraints),
                                           &Constraints, &state, tolerances.data()),
          "the constraints");
  }
  SetTolerances(opt.get(), stop, options.name);
  Check(nlopt_set_maxeval(opt.get(), stop.max_evaluations), "max_evaluations");
  if (options.initial_step > 0.0) {
    Check(nlopt_set_initial_step1(opt.get(), options.initial_step), "initial_step");
  }
  if (options.population > 0) {
    Check(nlopt_set_population(opt.get(), static_cast<unsigned>(options.population)), "population");
  }
  OptPtr local;
  if (entry.info.needs_local) {
    const std::string local_name = options.local.empty() ? "LN_BOBYQA" : options.local;
    const Entry& local_entry = Lookup(local_name, "local algorithm");
    if (local_entry.info.global || local_entry.info.needs_local) {
      throw InputError(fmt::format("local algorithm '{}' is not a local algorithm; accepted: {}",
                                   local_name, fmt::join(LocalAlgorithmNames(), ", ")));
    }
    local.reset(nlopt_create(local_entry.algorithm, n));
    if (!local) throw RunError("NLopt could not create algorithm " + local_name);
    SetTolerances(local.get(), stop, local_name);
    if (options.initial_step > 0.0) {
      Check(nlopt_set_initial_step1(local.get(), options.initial_step), "initial_step");
    }
    Check(nlopt_set_local_optimizer(opt.get(), local.get()), "the local algorithm");
  }

  // The stochastic algorithms draw from NLopt's generator; seeding it right before the run
  // makes the run (and so a resumed run) repeat exactly.
  nlopt_srand(static_cast<unsigned long>(options.seed));
  std::vector<double> x(start);
  for (double& xi : x) xi = std::min(1.0, std::max(0.0, xi));
  double value = HUGE_VAL;
  const nlopt_result r = nlopt_optimize(opt.get(), x.data(), &value);
  if (state.error) std::rethrow_exception(state.error);
  if (r == NLOPT_INVALID_ARGS) {
    throw RunError(
        fmt::format("NLopt refused the settings of {} for {} variables (invalid "
                    "arguments)",
                    options.name, n));
  }
  OptimiseResult result;
  result.u = x;
  result.value = value;
  result.calls = state.calls;
  // A stop forced by the evaluation budget (not by the caller) is reported as NLopt would.
  const bool budget_stop =
      r == NLOPT_FORCED_STOP && !state.stopped && state.calls >= state.max_calls;
  result.status = budget_stop ? "MAXEVAL_REACHED" : nlopt_result_to_string(r);
  result.stopped = state.stopped;
  return result;
}

}  // namespace fibrenet::optimizer
