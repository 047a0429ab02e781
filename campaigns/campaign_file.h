// The campaign file: a TOML document that declares an inverse-design campaign (docs/campaigns.md
// is the reference). Reading it checks everything that can be checked without running the
// scene: types, ranges, algorithm names, unknown keys (rejected with a close-match suggestion).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "optimizer/design_space.h"
#include "optimizer/doe.h"
#include "optimizer/evaluation.h"
#include "optimizer/goals.h"
#include "optimizer/nlopt_driver.h"

namespace fibrenet::campaigns {

// Base scenes of this form are built-in analytic test functions (campaigns/analytic_evaluator.h),
// not files.
inline constexpr std::string_view kAnalyticPrefix = "analytic:";

// Largest counts a campaign file may ask for: far beyond any practical campaign (each
// evaluation is a pipeline run and a database row), small enough that the sweep's points,
// the seeds and NLopt's population fit in memory. max_evaluations, doe.points and top share
// the first.
inline constexpr int kMaxEvaluations = 1'000'000;
inline constexpr int kMaxReplicates = 1000;
inline constexpr int kMaxPopulation = 100'000;

struct CampaignSpec {
  std::string path;        // the file as given ("" when parsed from text)
  std::string text;        // its content, stored in the results database
  std::string spec_hash;   // hash of everything but [budget] (and of the base scene file), so
                           // that a resumed campaign is known to be the same campaign
  std::string name;        // unique within a database
  std::string base_scene;  // path (made absolute from the campaign file's folder) or analytic:NAME
  std::uint64_t seed = 1;  // replicate seeds and stochastic algorithms derive from it

  optimizer::DesignSpace space;
  optimizer::Goals goals;
  std::optional<double> failure_penalty;  // fixed penalty for failed candidates, if set

  std::optional<optimizer::AlgorithmOptions> algorithm;  // absent: DOE only
  optimizer::StopCriteria stop;
  double max_wall_s = 0.0;  // wall-time budget of one invocation [s]; 0 = unlimited

  std::vector<optimizer::Fidelity> fidelities;  // at least one: [0] explores, later confirm
  std::optional<optimizer::DoeOptions> doe;     // absent: no sweep
};

// Reads and checks the campaign file at `path`. Throws fibrenet::InputError naming the file,
// the key and the accepted range (a missing file, TOML syntax, a wrong type or value, an
// unknown key).
CampaignSpec LoadCampaignFile(const std::string& path);

// How much of the outside world a parse checks.
enum class ParseMode {
  kFull,    // the base scene file must exist; it is part of spec_hash
  kStored,  // a campaign file stored in a results database, read back to show its goals: the
            // base scene is neither checked nor hashed (spec_hash is then left empty)
};

// The same from text; `source` names it in messages, relative scene paths are resolved against
// `base_dir`.
CampaignSpec ParseCampaign(std::string_view text, const std::string& source,
                           const std::string& base_dir, ParseMode mode = ParseMode::kFull);

// 16 hex digits of the 64-bit FNV-1a hash of `text`: a stable fingerprint (not cryptographic).
std::string HashText(std::string_view text);

}  // namespace fibrenet::campaigns
