// The NLopt driver: the one place of fibrenet that talks to NLopt (nlopt_driver.cpp).
//
// The problem is posed in the unit cube [0, 1]^n (optimizer/design_space.h maps it to scene
// values). The driver minimises an objective under inequality constraints g <= 0: algorithms
// with native constraint support (COBYLA, ISRES, ORIG_DIRECT, AUGLAG) receive the constraints;
// all others minimise the merit objective + w sum max(0, g)^2 (optimizer/goals.h).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fibrenet::optimizer {

// What the campaign file may name as [algorithm] name (or local).
struct AlgorithmInfo {
  std::string name;          // NLopt's name, e.g. "LN_COBYLA"
  bool global = false;       // searches the whole box (G*) rather than around a start (LN_*)
  bool constraints = false;  // handles inequality constraints natively
  bool needs_local = false;  // needs a local algorithm (AUGLAG, MLSL)
  std::string summary;       // one line for docs and error messages
};

// Every algorithm the driver accepts, in the order the docs list them.
const std::vector<AlgorithmInfo>& Algorithms();

// The entry called `name`, or nullptr.
const AlgorithmInfo* FindAlgorithm(const std::string& name);

// Names of the derivative-free local algorithms that may serve as `local`.
std::vector<std::string> LocalAlgorithmNames();

struct AlgorithmOptions {
  std::string name = "LN_BOBYQA";
  std::string local;          // for AUGLAG and G_MLSL*: empty picks LN_BOBYQA
  double initial_step = 0.1;  // first step of local algorithms, as a fraction of each range
  int population = 0;         // CRS2, ISRES, ESCH, MLSL; 0 leaves NLopt's default
  std::uint64_t seed = 1;     // for the stochastic algorithms (CRS2, ISRES, ESCH, MLSL, _RAND)
};

struct StopCriteria {
  int max_evaluations = 100;  // calls of the objective, >= 1 (never exceeded)
  double xtol_rel = 1e-4;     // relative step size in the unit cube; 0 disables
  double ftol_rel = 1e-6;     // relative change of the objective; 0 disables
  double ftol_abs = 0.0;      // absolute change of the objective; 0 disables
};

// The objective and the constraint values at one point of the unit cube.
struct ProblemValues {
  double objective = 0.0;
  std::vector<double> constraints;  // as many as the problem declares; feasible when <= 0
};

using ProblemFn = std::function<ProblemValues(const std::vector<double>& u)>;

struct OptimiseResult {
  std::vector<double> u;  // NLopt's best point (by the value it minimised)
  double value = 0.0;     // that value (objective, or merit without native constraints)
  int calls = 0;          // calls of `problem`
  std::string status;     // NLopt's result, e.g. "MAXEVAL_REACHED", "FORCED_STOP"
  bool stopped = false;   // ended because `stop_requested` said so
};

// Minimises from `start` (in [0, 1]^n). `problem` is called once per new point; an exception
// it throws stops NLopt and is rethrown here. `stop_requested` is asked after each call.
// `n_constraints` constraint values come with every ProblemValues. Deterministic for a given
// options.seed and problem. Throws fibrenet::InputError for an unknown algorithm or local
// algorithm, and fibrenet::RunError if NLopt refuses the settings.
OptimiseResult Minimise(const AlgorithmOptions& options, const StopCriteria& stop,
                        const std::vector<double>& start, std::size_t n_constraints,
                        double constraint_weight, const ProblemFn& problem,
                        const std::function<bool()>& stop_requested);

}  // namespace fibrenet::optimizer
