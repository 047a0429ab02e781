// Diagnostics used when a run fails: which interaction of a particle is to blame.
#pragma once

#include <string>

#include "engine/core/world.h"

namespace fibrenet {

// Evaluates every interaction of `particle` (without changing any history) and describes
// the one with a non-finite or the largest force, e.g. "bond 12 (3-4): |F| = 1.2e-2 N".
std::string DescribeLargestInteraction(const World& w, std::size_t particle);

}  // namespace fibrenet
