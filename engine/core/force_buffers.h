// Race-free force accumulation for the pair loops (bonds, contacts), which run in parallel
// and write both partners. The particles are split into one contiguous index range per
// thread. Each thread adds straight into the particle arrays when the particle lies in its
// own range, and queues the contribution otherwise; after the loop each thread applies the
// queues aimed at its range, from thread 0's queue up. Pair loops hand each thread the
// interactions of its own range (rows of the neighbour list; an equal share of the bonds in
// their first particle's order, see BondRange), so with particles ordered in space only pairs
// that straddle a range boundary are queued.
//
// This replaced one full force and torque copy per extra thread, summed over all particles
// every step: that cost 48 bytes per particle per thread and a pass over all of them; the
// queues cost only what crosses a boundary (docs/performance.md).
//
// Determinism: the order of the additions into a particle depends only on the thread
// count, so results are identical run to run for a given thread count; with one thread
// every addition is direct, in the order of the serial loop.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "engine/core/bonds.h"
#include "engine/core/parallel.h"
#include "engine/core/particles.h"

namespace fibrenet {

class ForceBuffers {
 public:
  // A contribution for a particle outside the writing thread's range.
  struct Queued {
    std::int32_t i;
    Vec3 force, torque;
  };

  // What one thread writes with. Add() is the only way a pair loop touches forces.
  class Writer {
   public:
    Writer(ForceBuffers& b, int range)
        : force_(b.force_->data()),
          torque_(b.torque_->data()),
          lo_(b.bounds_[range]),
          hi_(b.bounds_[range + 1]),
          buffers_(&b),
          range_(range) {}

    void Add(std::int32_t i, const Vec3& f, const Vec3& t) {
      if (i >= lo_ && i < hi_) {
        force_[i] += f;
        torque_[i] += t;
      } else {
        buffers_->Queue(range_, i).push_back({i, f, t});
      }
    }
    // Adds -f: the reaction of a pair force (a - f and a + (-f) are the same in IEEE).
    void AddReaction(std::int32_t i, const Vec3& f, const Vec3& t) {
      if (i >= lo_ && i < hi_) {
        force_[i] -= f;
        torque_[i] += t;
      } else {
        buffers_->Queue(range_, i).push_back({i, -f, t});
      }
    }

   private:
    Vec3* force_;
    Vec3* torque_;
    std::int64_t lo_, hi_;
    ForceBuffers* buffers_;
    int range_;
  };

  // Splits the particles (and the bonds, see BondRange) among the current thread count.
  // Cheap when nothing changed; call before each force evaluation.
  void Prepare(Particles& p, const Bonds& bonds) {
    force_ = &p.force;
    torque_ = &p.torque;
    const int ranges = std::max(1, ThreadCount());
    const std::size_t n = p.size();
    if (ranges != ranges_ || n != n_) {
      ranges_ = ranges;
      n_ = n;
      bounds_.resize(ranges + 1);
      for (int r = 0; r <= ranges; ++r)
        bounds_[r] = static_cast<std::int64_t>(n * static_cast<std::size_t>(r) / ranges);
      queues_.assign(static_cast<std::size_t>(ranges) * ranges, {});
      bond_key_ = {};  // the bond split follows the particle split
    }
    const std::pair<const void*, std::size_t> key{bonds.i.data(), bonds.size()};
    if (key != bond_key_) {
      bond_key_ = key;
      SplitBonds(bonds);
    }
  }

  int Ranges() const { return ranges_; }
  // Particles [first, second) of range r.
  std::pair<std::int64_t, std::int64_t> ParticleRange(int r) const {
    return {bounds_[r], bounds_[r + 1]};
  }
  // Bonds handed to range r: BondOrder()[first..second). With one range, every bond in id
  // order (the serial loop). With more, every bond in the order of its first particle (ties
  // by id), cut into equal counts: the ranges do equal work although a fibre-fibre bond's
  // first particle is its lower index, so that owning a bond by its first particle would
  // give the low range every bond that crosses to a high one. A bond whose first particle
  // lies in another range's particles (between a cut and that range's end) queues its force
  // there. Each range then walks its bonds by blocks of kFirstParticleBlock first particles
  // and, within a block, in the order of their second particle (then as before): on the
  // 10 mm sheet that took a fifth off the tensile test's steps (docs/performance.md).
  static constexpr std::int32_t kFirstParticleBlock = 256;  // about 40 kB of particle data
  std::pair<std::int64_t, std::int64_t> BondRange(int r) const {
    return {bond_bounds_[r], bond_bounds_[r + 1]};
  }
  const std::int32_t* BondOrder() const { return bond_order_.data(); }
  Writer WriterFor(int range) { return Writer(*this, range); }

  // Applies the queued contributions, each range by its owner, sources in thread order,
  // and empties the queues (keeping their memory). Call outside a parallel region.
  void Reduce() {
    bool any = false;
    for (const auto& q : queues_) any = any || !q.empty();
    if (!any) return;
    Vec3* f = force_->data();
    Vec3* t = torque_->data();
    const int ranges = ranges_;
#pragma omp parallel for schedule(static, 1)
    for (int dst = 0; dst < ranges; ++dst) {
      for (int src = 0; src < ranges; ++src) {
        std::vector<Queued>& q = queues_[static_cast<std::size_t>(src) * ranges + dst];
        for (const Queued& e : q) {
          f[e.i] += e.force;
          t[e.i] += e.torque;
        }
        q.clear();
      }
    }
  }

  std::size_t MemoryBytes() const {
    std::size_t bytes = (bounds_.capacity() + bond_bounds_.capacity()) * sizeof(std::int64_t) +
                        bond_order_.capacity() * sizeof(std::int32_t);
    for (const auto& q : queues_) bytes += q.capacity() * sizeof(Queued);
    return bytes;
  }

 private:
  std::vector<Queued>& Queue(int src, std::int32_t i) {
    // The owner of i: ranges are equal splits, so start from the proportional guess.
    int dst = static_cast<int>(static_cast<std::int64_t>(i) * ranges_ / std::max<std::int64_t>(1, n_));
    dst = std::min(std::max(dst, 0), ranges_ - 1);
    while (dst > 0 && i < bounds_[dst]) --dst;
    while (dst + 1 < ranges_ && i >= bounds_[dst + 1]) ++dst;
    return queues_[static_cast<std::size_t>(src) * ranges_ + dst];
  }

  void SplitBonds(const Bonds& bonds) {
    const std::size_t nb = bonds.size();
    bond_order_.resize(nb);
    std::iota(bond_order_.begin(), bond_order_.end(), 0);
    bond_bounds_.assign(ranges_ + 1, static_cast<std::int64_t>(nb));
    bond_bounds_[0] = 0;
    if (ranges_ == 1) return;
    std::stable_sort(bond_order_.begin(), bond_order_.end(),
                     [&](std::int32_t a, std::int32_t b) { return bonds.i[a] < bonds.i[b]; });
    for (int r = 1; r < ranges_; ++r)
      bond_bounds_[r] = static_cast<std::int64_t>(nb * static_cast<std::size_t>(r) / ranges_);
    // Within a share, block by block of first particles, the bonds in their second
    // particle's order: a fibre-fibre bond's partner lies anywhere near in space, and walked
    // in order the partners' reads and writes go forward through memory.
    for (int r = 0; r < ranges_; ++r)
      std::stable_sort(bond_order_.begin() + bond_bounds_[r],
                       bond_order_.begin() + bond_bounds_[r + 1],
                       [&](std::int32_t a, std::int32_t b) {
                         return WalkKey(bonds, a) < WalkKey(bonds, b);
                       });
  }

  // The order a share's bonds are walked in (see SplitBonds).
  static std::pair<std::int32_t, std::int32_t> WalkKey(const Bonds& bonds, std::int32_t b) {
    return {bonds.i[b] / kFirstParticleBlock, bonds.j[b]};
  }

  std::vector<Vec3>* force_ = nullptr;
  std::vector<Vec3>* torque_ = nullptr;
  int ranges_ = 0;
  std::size_t n_ = 0;
  std::vector<std::int64_t> bounds_{0, 0};
  std::vector<std::int64_t> bond_bounds_{0, 0};
  std::vector<std::int32_t> bond_order_;
  std::pair<const void*, std::size_t> bond_key_{};
  // queues_[src * ranges + dst]: written by range src's thread, applied by dst's.
  std::vector<std::vector<Queued>> queues_;
};

}  // namespace fibrenet
