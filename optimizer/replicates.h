// Replicates: independent random networks of one candidate, reduced to a mean and a standard
// error per metric.
//
// Common random numbers: replicate r of every candidate uses the same seed, ReplicateSeed(
// campaign_seed, r), so differences between candidates are not blurred by different random
// networks (variance reduction for comparisons), and a candidate's seeds are known before it
// runs (they are part of its database key).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "optimizer/evaluation.h"

namespace fibrenet::optimizer {

// Seed of replicate `replicate` (0-based) for a campaign seeded with `campaign_seed`.
std::uint64_t ReplicateSeed(std::uint64_t campaign_seed, int replicate);

// The seeds of replicates 0..count-1.
std::vector<std::uint64_t> ReplicateSeeds(std::uint64_t campaign_seed, int count);

// One metric reduced over the replicates.
struct MetricStatistics {
  double mean = 0.0;
  double std_error = 0.0;  // sample standard deviation / sqrt(n); 0 when n == 1
  int n = 0;
  std::string unit;
  std::vector<double> values;  // per replicate, in replicate order
};

// Reduces successful replicate results. Only metrics present in every replicate are kept
// (a metric missing from some replicate would make the mean incomparable). Requires at least
// one result, all ok.
std::map<std::string, MetricStatistics> ReduceReplicates(
    const std::vector<EvaluationResult>& results);

}  // namespace fibrenet::optimizer
