// Checks of a campaign against its base scene (or analytic function) that need the scene
// reader or an evaluator, so that bad keys are refused before a database is written.
#pragma once

#include "campaigns/campaign_file.h"

namespace fibrenet::campaigns {

// Checks the campaign against its base scene, before anything is written (the CLI calls it
// before it opens the database), so that a key the scene lacks is bad input at once rather
// than a candidate that stops the campaign half way. On a scene file: every design variable,
// set alone to its lower and to its upper bound, and every fidelity level's overrides must be
// accepted by the scene reader (key known, value in range, memory). On an analytic function:
// one evaluation at the start point without overrides gives its metrics, which must include
// every goal metric, and each fidelity override key must be one it takes. A scene's metrics
// are known only after a run (its virtual tests decide them), so a goal metric that a scene
// does not produce still stops the campaign at its first evaluation.
// Throws fibrenet::InputError naming the campaign file, the line and the key.
void CheckAgainstBaseScene(const CampaignSpec& spec);

}  // namespace fibrenet::campaigns
