// How a campaign evaluates a candidate: the adapter interface between the campaign runner and
// whatever computes metrics (the DEM scene pipeline, or an analytic test function).
//
// The runner receives an Evaluator by injection and never knows which one it got, so the real
// scene evaluator plugs in through MakeEvaluator alone. The contract (determinism, failures,
// errors) is the one of optimizer::EvaluateFn, optimizer/evaluation.h.
#pragma once

#include <string>
#include <vector>

#include "optimizer/evaluation.h"

namespace fibrenet::campaigns {

// EvaluationResult evaluate(const Design& design, const Fidelity& fidelity, uint64_t seed):
// one replicate of one candidate.
using Evaluator = optimizer::EvaluateFn;

// The evaluator of a campaign's base scene: "analytic:NAME" gives the built-in test function
// NAME (campaigns/analytic_evaluator.h), anything else is a scene file evaluated by the DEM
// pipeline (campaigns/scene_evaluator.h). Throws fibrenet::InputError if it cannot be built.
// `goal_metrics`: the metrics the goals read; a scene evaluation fails when one of them is
// not finite, and leaves out any other metric that is not (an undefined diagnostic).
// `stage_folder`: where a scene evaluator's stage cache keeps its networks on disk ("" keeps
// them in memory only; campaigns/stage_cache.h).
Evaluator MakeEvaluator(const std::string& base_scene,
                        const std::vector<std::string>& goal_metrics = {},
                        const std::string& stage_folder = "");

}  // namespace fibrenet::campaigns
