#include "optimizer/replicates.h"

#include <cassert>
#include <cmath>

#include "optimizer/random.h"

namespace fibrenet::optimizer {

std::uint64_t ReplicateSeed(std::uint64_t campaign_seed, int replicate) {
  // Kept below 2^63 so that the seed survives a signed 64-bit column or a JSON integer.
  return DeriveSeed(campaign_seed, static_cast<std::uint64_t>(replicate)) >> 1;
}

std::vector<std::uint64_t> ReplicateSeeds(std::uint64_t campaign_seed, int count) {
  std::vector<std::uint64_t> seeds;
  for (int r = 0; r < count; ++r) seeds.push_back(ReplicateSeed(campaign_seed, r));
  return seeds;
}

std::map<std::string, MetricStatistics> ReduceReplicates(
    const std::vector<EvaluationResult>& results) {
  assert(!results.empty());
  std::map<std::string, MetricStatistics> stats;
  for (const auto& [name, value] : results.front().metrics) {
    MetricStatistics s;
    bool everywhere = true;
    for (const EvaluationResult& r : results) {
      assert(r.ok);
      const auto it = r.metrics.find(name);
      if (it == r.metrics.end()) {
        everywhere = false;
        break;
      }
      s.values.push_back(it->second);
    }
    if (!everywhere) continue;
    s.n = static_cast<int>(s.values.size());
    // Summed as offsets from the first replicate, so that equal replicates (a metric the seed
    // does not affect) give exactly their value and a standard error of exactly zero.
    double offsets = 0.0;
    for (double v : s.values) offsets += v - s.values.front();
    s.mean = s.values.front() + offsets / s.n;
    if (s.n > 1) {
      double squares = 0.0;
      for (double v : s.values) squares += (v - s.mean) * (v - s.mean);
      s.std_error = std::sqrt(squares / (s.n - 1)) / std::sqrt(static_cast<double>(s.n));
    }
    const auto unit = results.front().units.find(name);
    s.unit = unit != results.front().units.end() ? unit->second : "1";
    stats.emplace(name, std::move(s));
  }
  return stats;
}

}  // namespace fibrenet::optimizer
