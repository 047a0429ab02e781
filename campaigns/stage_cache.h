// The stage cache of a campaign: networks kept after forming and after pressing, so that a
// candidate that differs from an earlier one only in settings of later stages (pressing,
// the virtual tests) starts from the kept network instead of forming it again.
//
// A stage's key is a hash of everything upstream of the stage's end: the scene text, the
// seed and every override except those of later stages. Two runs with equal keys compute the
// same network bit for bit (same thread count), so reuse changes no result.
//
// The cache lives in the evaluating process (one per MPI rank) and holds the most recently
// used networks up to a byte budget. With a folder it also keeps each network there as a stage
// snapshot (campaigns/stage_snapshot.h) named by its key, so that a resumed campaign, a later
// campaign on the same scene, or another MPI rank on a shared file system starts from it too;
// the folder is trimmed to a byte budget, oldest files first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "campaigns/scene.h"
#include "engine/pipeline/pipeline.h"

namespace fibrenet::campaigns {

// Keys of the network stages, in pipeline order: [0] after forming, [1] after consolidation
// (pressing or through-air drying), [2] after creping.
std::vector<std::string> StageKeys(const std::string& scene_text, const std::vector<Override>& overrides,
                                   std::uint64_t seed);

class StageCache {
 public:
  explicit StageCache(std::size_t max_bytes = std::size_t{1} << 30, std::string folder = "",
                      std::uintmax_t max_folder_bytes = std::uintmax_t{4} << 30)
      : max_bytes_(max_bytes), folder_(std::move(folder)), max_folder_bytes_(max_folder_bytes) {}

  // The latest stage state whose key is in `keys` (checked from the last stage back), or
  // nullptr. The pointer stays valid until the next Keep.
  const pipeline::StageState* Find(const std::vector<std::string>& keys);
  // Keeps kept[k] under keys[k].
  void Keep(const std::vector<std::string>& keys, std::vector<pipeline::StageState>& kept);

  std::int64_t hits() const { return hits_; }  // from memory or the folder
  std::int64_t folder_hits() const { return folder_hits_; }
  std::int64_t misses() const { return misses_; }

 private:
  struct Entry {
    std::string key;
    pipeline::StageState state;
    std::size_t bytes = 0;
  };
  const pipeline::StageState* FindInFolder(const std::string& key);
  void Remember(const std::string& key, pipeline::StageState state);
  void Store(const std::string& key, const pipeline::StageState& state);
  void TrimFolder();

  std::list<Entry> entries_;  // most recently used first
  std::size_t bytes_ = 0, max_bytes_;
  std::string folder_;
  std::uintmax_t max_folder_bytes_;
  std::int64_t hits_ = 0, folder_hits_ = 0, misses_ = 0;
};

}  // namespace fibrenet::campaigns
