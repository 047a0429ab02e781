// The one narrow call through which the optimizer sees a candidate evaluation, and the plain
// values that cross it. Nothing here knows scenes, the DEM engine, NLopt, MPI or SQL.
//
// One call evaluates one replicate: a design (values of the design variables, keyed by their
// scene keys), at one fidelity level, with one random seed. The optimizer calls it once per
// replicate and reduces the replicates itself (optimizer/replicates.h).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace fibrenet::optimizer {

// A point of the design space: scene key (e.g. "pressing.target_thickness_um") -> value in the
// unit that key names. Ordered by key, so two equal designs compare and print equal.
using Design = std::map<std::string, double>;

// A fidelity level: a name stored with every candidate and numeric scene overrides that make
// the scene cheaper or finer (e.g. "fibres.particles_per_fibre" = 8). The evaluator applies
// `overrides` after the design's values.
struct Fidelity {
  std::string name = "default";
  std::map<std::string, double> overrides;
  int replicates = 1;  // independent random networks per candidate at this level, >= 1
  int top = 1;         // for every level but the first: how many of the best candidates of the
                       // previous level are re-evaluated (confirmed) at this level, >= 1
};

// A file written by an evaluation, e.g. {"snapshot", "runs/c12/pressed.h5"}.
struct ArtifactPath {
  std::string kind;
  std::string path;
};

// What one replicate evaluation returns. A failed evaluation (instability, time-out, a design
// the scene cannot build) has ok == false and a reason; its metrics are ignored.
struct EvaluationResult {
  bool ok = true;
  std::string reason;                        // why it failed; empty when ok
  std::map<std::string, double> metrics;     // metric name -> value (finite), in `units`
  std::map<std::string, std::string> units;  // metric name -> SI unit text ("1" if absent)
  std::vector<ArtifactPath> artifacts;
};

// The evaluator. Contract:
// - deterministic in (design, fidelity, seed): equal arguments give equal metrics (this is
//   what makes resume and MPI runs reproduce serial runs);
// - reports a failed candidate either by returning ok == false or by throwing
//   fibrenet::RunError (both become a failed candidate with a penalty; the campaign goes on);
// - throws fibrenet::InputError for bad input (unknown scene key, value out of range): that
//   stops the campaign with exit code 2. Any other exception also stops the campaign.
// It may be called from a worker process (MPI) but never from two threads at once.
using EvaluateFn =
    std::function<EvaluationResult(const Design&, const Fidelity&, std::uint64_t seed)>;

}  // namespace fibrenet::optimizer
