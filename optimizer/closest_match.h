// "Did you mean ...?" for names typed by users: campaign keys, metric names, algorithm names.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace fibrenet::optimizer {

// The entry of `known` closest to `name` by edit distance (case-insensitive), or an empty
// string when none is close enough to be a plausible typo (distance above half of the
// longer name, and at least 2), unless one abbreviates the other.
std::string ClosestMatch(std::string_view name, const std::vector<std::string>& known);

// "; did you mean 'x'?" for the closest match, or an empty string: ready to append to a message.
std::string DidYouMean(std::string_view name, const std::vector<std::string>& known);

}  // namespace fibrenet::optimizer
