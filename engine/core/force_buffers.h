// Per-thread force and torque accumulators. Interaction loops run over pairs in parallel
// and write both partners; each thread adds into its own buffer (thread 0 straight into
// the particle arrays) and the buffers are summed in a fixed order afterwards, so results
// are identical run to run for a given thread count.
#pragma once

#include <vector>

#include "engine/core/particles.h"
#include "engine/core/parallel.h"

namespace fibrenet {

class ForceBuffers {
 public:
  // Sizes the buffers for the particles and the current thread count. Buffers are kept
  // zeroed by Reduce, so this only allocates when the sizes change.
  void Prepare(Particles& p) {
    force_ = &p.force;
    torque_ = &p.torque;
    const int threads = ThreadCount();
    const std::size_t extra = threads > 1 ? threads - 1 : 0;
    if (extra_force_.size() != extra) {
      extra_force_.assign(extra, {});
      extra_torque_.assign(extra, {});
    }
    for (std::size_t b = 0; b < extra; ++b) {
      if (extra_force_[b].size() == p.size()) continue;
      extra_force_[b].assign(p.size(), Vec3::Zero());
      extra_torque_[b].assign(p.size(), Vec3::Zero());
    }
  }

  Vec3* Force(int thread) { return thread == 0 ? force_->data() : extra_force_[thread - 1].data(); }
  Vec3* Torque(int thread) {
    return thread == 0 ? torque_->data() : extra_torque_[thread - 1].data();
  }

  // Adds the other threads' buffers into the particle arrays and clears them.
  void Reduce() {
    if (extra_force_.empty()) return;
    const std::int64_t n = static_cast<std::int64_t>(force_->size());
    Vec3* f = force_->data();
    Vec3* t = torque_->data();
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      for (std::size_t b = 0; b < extra_force_.size(); ++b) {
        f[i] += extra_force_[b][i];
        t[i] += extra_torque_[b][i];
        extra_force_[b][i].setZero();
        extra_torque_[b][i].setZero();
      }
    }
  }

  std::size_t MemoryBytes() const {
    std::size_t bytes = 0;
    for (const auto& b : extra_force_) bytes += 2 * b.capacity() * sizeof(Vec3);
    return bytes;
  }

 private:
  std::vector<Vec3>* force_ = nullptr;
  std::vector<Vec3>* torque_ = nullptr;
  std::vector<std::vector<Vec3>> extra_force_, extra_torque_;
};

}  // namespace fibrenet
