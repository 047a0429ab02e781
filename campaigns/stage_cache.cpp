#include "campaigns/stage_cache.h"

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "campaigns/campaign_file.h"
#include "campaigns/stage_snapshot.h"
#include "engine/core/error.h"

namespace fibrenet::campaigns {

namespace {

// Overrides of the tables downstream of each network stage (they do not change it).
bool DownstreamOf(const std::string& path, std::size_t stage) {
  const KeyStage fed = StageOfKey(path);
  return fed != KeyStage::kEvery && static_cast<int>(fed) > static_cast<int>(stage);
}

std::size_t Bytes(const pipeline::StageState& s) {
  // A bound: about 750 bytes a particle with neighbour rows and bonds (fibrenet bench); kept
  // states park their lists (NeighbourList::Parked), so they hold less.
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
  for (std::size_t stage = 0; stage < 3; ++stage) {  // forming, consolidation, creping
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
  for (auto key = keys.rbegin(); key != keys.rend(); ++key)
    if (const pipeline::StageState* state = FindInFolder(*key)) {
      ++hits_;
      ++folder_hits_;
      return state;
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
    Store(key, state);
    Remember(key, std::move(state));
  }
}

void StageCache::Remember(const std::string& key, pipeline::StageState state) {
  const std::size_t bytes = Bytes(state);
  if (bytes > max_bytes_) return;
  entries_.push_front({key, std::move(state), bytes});
  bytes_ += bytes;
  while (bytes_ > max_bytes_) {
    bytes_ -= entries_.back().bytes;
    entries_.pop_back();
  }
}

namespace {

std::filesystem::path SnapshotPath(const std::string& folder, const std::string& key) {
  return std::filesystem::path(folder) / (key + ".h5");
}

}  // namespace

const pipeline::StageState* StageCache::FindInFolder(const std::string& key) {
  if (folder_.empty()) return nullptr;
  const std::filesystem::path path = SnapshotPath(folder_, key);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return nullptr;
  try {
    Remember(key, ReadStageSnapshot(path.string()).state);
  } catch (const Error&) {
    // A damaged or foreign file is no network: forget it and form the network again.
    std::filesystem::remove(path, ec);
    return nullptr;
  }
  if (entries_.empty() || entries_.front().key != key) return nullptr;  // over the memory budget
  return &entries_.front().state;
}

void StageCache::Store(const std::string& key, const pipeline::StageState& state) {
  if (folder_.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  const std::filesystem::path path = SnapshotPath(folder_, key);
  if (std::filesystem::exists(path, ec)) return;
  try {
    WriteStageSnapshot(state, path.string(), {"stage cache", key, 0});
  } catch (const Error&) {
    return;  // a full disk costs the reuse, not the evaluation
  }
  TrimFolder();
}

void StageCache::TrimFolder() {
  namespace fs = std::filesystem;
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> files;
  std::uintmax_t total = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec)) {
    if (e.path().extension() != ".h5") continue;
    total += e.file_size(ec);
    files.emplace_back(e.last_write_time(ec), e.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& [time, path] : files) {
    if (total <= max_folder_bytes_) break;
    total -= fs::file_size(path, ec);
    fs::remove(path, ec);
    fs::path xdmf = path;
    fs::remove(xdmf.replace_extension(".xdmf"), ec);
  }
}

}  // namespace fibrenet::campaigns
