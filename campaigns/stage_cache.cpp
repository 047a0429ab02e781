#include "campaigns/stage_cache.h"

#include <algorithm>

#include <fmt/format.h>

#include "campaigns/campaign_file.h"

namespace fibrenet::campaigns {

namespace {

// Overrides of the tables downstream of each network stage (they do not change it).
bool DownstreamOf(const std::string& path, std::size_t stage) {
  auto in = [&](const char* table) { return path.rfind(std::string(table) + ".", 0) == 0; };
  const bool tests = in("tensile") || in("compression") || in("softness");
  return stage == 0 ? tests || in("pressing") || in("through_air") : tests;
}

std::size_t Bytes(const pipeline::StageState& s) {
  // Particles carry about 750 bytes each with their neighbour rows and bonds (fibrenet bench).
  return 1024 + 750 * s.network.world.particles.size();
}

}  // namespace

std::vector<std::string> StageKeys(const std::string& scene_text,
                                   const std::vector<Override>& overrides, std::uint64_t seed) {
  std::vector<Override> sorted = overrides;
  // Later overrides of a path win: keep the last of each, in path order.
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Override& a, const Override& b) { return a.path < b.path; });
  std::vector<std::string> keys;
  for (std::size_t stage = 0; stage < 2; ++stage) {
    std::string canonical = fmt::format("seed {}\n", seed);
    for (std::size_t k = 0; k < sorted.size(); ++k) {
      const bool last = k + 1 == sorted.size() || sorted[k + 1].path != sorted[k].path;
      if (last && !DownstreamOf(sorted[k].path, stage))
        canonical += fmt::format("{} = {:.17g}\n", sorted[k].path, sorted[k].value);
    }
    keys.push_back(fmt::format("{}-{}", stage, HashText(canonical + scene_text)));
  }
  return keys;
}

const pipeline::StageState* StageCache::Find(const std::vector<std::string>& keys) {
  for (auto key = keys.rbegin(); key != keys.rend(); ++key) {
    auto it = std::find_if(entries_.begin(), entries_.end(),
                           [&](const Entry& e) { return e.key == *key; });
    if (it != entries_.end()) {
      entries_.splice(entries_.begin(), entries_, it);
      ++hits_;
      return &entries_.front().state;
    }
  }
  ++misses_;
  return nullptr;
}

void StageCache::Keep(const std::vector<std::string>& keys, std::vector<pipeline::StageState>& kept) {
  for (pipeline::StageState& state : kept) {
    const std::size_t stage = state.stages.size() - 1;
    if (stage >= keys.size()) continue;
    const std::string& key = keys[stage];
    if (std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; }))
      continue;
    const std::size_t bytes = Bytes(state);
    if (bytes > max_bytes_) continue;
    entries_.push_front({key, std::move(state), bytes});
    bytes_ += bytes;
    while (bytes_ > max_bytes_) {
      bytes_ -= entries_.back().bytes;
      entries_.pop_back();
    }
  }
}

}  // namespace fibrenet::campaigns
