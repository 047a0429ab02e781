// Verlet neighbour list built with linked cells. Each unordered pair within
// R_i + R_j + skin is stored once (half list), in compressed rows sorted by partner:
// partners[offsets[i] .. offsets[i+1]). The pair {a < b} lies in row a when a + b is even and
// in row b when it is odd, so that rows hold about equal shares of the pairs whatever the
// particle order (threads split the rows by particle range). Bonded pairs are excluded. The list is
// rebuilt when some particle has moved more than half the skin since the last build, so
// no contact can be missed; the cost of a build is linear in the particle count.
// Each entry carries the tangential history of its contact, carried over across rebuilds.
// A parked list (Parked) holds that history alone, without rows, for a world kept aside (a
// stage's network, an impact frame): the rows are a cache the next build makes again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/core/bonds.h"
#include "engine/core/cell.h"
#include "engine/core/particles.h"

namespace fibrenet {

// The tangential history of one touching pair, for snapshots.
struct PairHistory {
  std::int32_t i = 0, j = 0;  // i < j
  Vec3 xi = Vec3::Zero();      // as seen from i (from j it is -xi)
};

class NeighbourList {
 public:
  // skin: extra distance beyond contact [m], > 0.
  void Build(const Particles& p, const Cell& cell, const Bonds& bonds, double skin);
  bool NeedsRebuild(const Particles& p, const Cell& cell) const;
  // The two halves of NeedsRebuild, for a caller that checks the displacements inside a pass
  // over the particles of its own: whether the list needs a build whatever the positions
  // (never built, invalidated, or another particle count), and whether particle i, now at x,
  // has moved more than half the skin since the last build.
  bool Stale(std::size_t particles) const { return !valid_ || x_at_build_.size() != particles; }
  bool MovedTooFar(std::size_t i, const Vec3& x, const Cell& cell) const {
    return cell.Delta(x_at_build_[i], x).squaredNorm() > 0.25 * skin_ * skin_;
  }
  // Forces a rebuild at the next check (after bonds break or particles are added).
  void Invalidate() { valid_ = false; }
  // Adds pairs {i, j} whose bond has just broken, with no history, instead of a build: every
  // other pair that can touch before the next build is already in the rows, since the skin
  // still bounds the motion since the last one. The forces are those a build would give, bit
  // for bit: a build would add these pairs and differ otherwise only by pairs apart, which add
  // nothing. Returns false, and changes nothing, where it cannot stand for a build: a list
  // never built or invalidated, or a pair that another bond joined at the last build.
  bool AddBrokenBondPairs(std::vector<std::pair<std::int32_t, std::int32_t>> pairs);

  std::size_t RowBegin(std::size_t i) const { return offsets_[i]; }
  std::size_t RowEnd(std::size_t i) const { return offsets_[i + 1]; }
  std::size_t size() const { return partners_.size(); }
  std::int32_t Partner(std::size_t k) const { return partners_[k]; }
  // The row that holds entry k, so that a loop can walk the entries without the rows.
  std::int32_t Owner(std::size_t k) const { return owners_[k]; }
  Vec3& History(std::size_t k) { return history_[k]; }
  const Vec3& History(std::size_t k) const { return history_[k]; }
  const std::vector<std::int32_t>& partners() const { return partners_; }
  std::size_t builds() const { return builds_; }
  // An id no other build in this process has had (0: no rows). Every particle lies within
  // half the skin of where it lay at the build with this id: what a world's walls rely on to
  // check only the particles near them (WallReach).
  std::uint64_t build_id() const { return build_id_; }
  bool parked() const { return parked_; }
  double skin() const { return skin_; }
  std::size_t MemoryBytes() const;

  // Histories of all pairs with a non-zero tangential history, in row order (a parked list's
  // as it was parked).
  std::vector<PairHistory> ExportHistory() const;
  // Restores histories into a freshly built list; a pair that the list lacks is an error
  // (std::invalid_argument), since a touching pair is always within the list's reach.
  void ImportHistory(const std::vector<PairHistory>& history);
  // Rotates every stored history (a rigid rotation of the world), parked or in rows.
  void RotateHistory(const Mat3& R);
  // A list without rows that keeps this one's contact history, skin and build count: its next
  // build restores the history of the pairs it finds, if the particle count is unchanged.
  NeighbourList Parked() const;

 private:
  void BuildExclusions(std::size_t n, const Bonds& bonds);
  void RestoreParked(std::size_t particles);
  // The entry of pair h (-1 if the rows lack it), and h's history as its row stores it.
  std::ptrdiff_t EntryOf(const PairHistory& h, Vec3* xi_in_row) const;
  // Unbroken bonds that joined a and b at the last build: a pair with any is not in the rows.
  int BondsAtBuild(std::int32_t a, std::int32_t b) const;
  std::size_t ThreadRowsBytes() const;

  std::vector<std::uint32_t> offsets_{0};
  std::vector<std::int32_t> partners_;
  std::vector<std::int32_t> owners_;
  std::vector<Vec3> history_;
  std::vector<Vec3> x_at_build_;
  // Bonded partners of each particle, compressed rows.
  std::vector<std::uint32_t> excl_offsets_;
  std::vector<std::int32_t> excl_partners_;
  // Scratch reused between builds: cell of each particle and particles sorted by cell.
  std::vector<std::int32_t> cell_of_, cell_start_, cell_members_;
  std::vector<std::uint32_t> scratch_offsets_;
  std::vector<std::int32_t> scratch_partners_;
  std::vector<Vec3> scratch_history_;
  std::vector<std::vector<std::int32_t>> thread_rows_;  // each thread's rows during a build
  double skin_ = 0.0;
  bool valid_ = false;
  std::size_t builds_ = 0;
  std::uint64_t build_id_ = 0;
  // A parked list's history, for the particle count it was parked with.
  bool parked_ = false;
  std::vector<PairHistory> parked_history_;
  std::size_t parked_particles_ = 0;
};

}  // namespace fibrenet
