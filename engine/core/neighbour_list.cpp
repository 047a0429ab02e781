#include "engine/core/neighbour_list.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "engine/core/parallel.h"

namespace fibrenet {

namespace {

// Linked-cell grid over the particles' bounding box (periodic in x, y as the cell says).
struct Grid {
  int nx = 1, ny = 1, nz = 1;
  Vec3 lo, size;  // origin and edge length of one grid cell

  int Index(int cx, int cy, int cz) const { return (cz * ny + cy) * nx + cx; }
  int Count() const { return nx * ny * nz; }
};

// Whether row `owner` holds the pair {owner, partner}: the parity rule of neighbour_list.h.
// The plain "lower index" rule would give the rows of the first half of the particles 3/4
// of the pairs when particles are not ordered in space (fibres placed at random).
bool RowHolds(std::int64_t owner, std::int64_t partner) {
  return ((owner + partner) & 1) == 0 ? owner < partner : owner > partner;
}

std::atomic<std::uint64_t> next_build_id{1};

int ClampCell(double t, int n) {
  const int c = static_cast<int>(std::floor(t));
  return std::min(std::max(c, 0), n - 1);
}

}  // namespace

void NeighbourList::BuildExclusions(std::size_t n, const Bonds& bonds) {
  excl_offsets_.assign(n + 1, 0);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.broken[b]) continue;
    ++excl_offsets_[bonds.i[b] + 1];
    ++excl_offsets_[bonds.j[b] + 1];
  }
  for (std::size_t k = 0; k < n; ++k) excl_offsets_[k + 1] += excl_offsets_[k];
  excl_partners_.resize(excl_offsets_[n]);
  std::vector<std::uint32_t> fill(excl_offsets_.begin(), excl_offsets_.end() - 1);
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    if (bonds.broken[b]) continue;
    excl_partners_[fill[bonds.i[b]]++] = bonds.j[b];
    excl_partners_[fill[bonds.j[b]]++] = bonds.i[b];
  }
}

int NeighbourList::BondsAtBuild(std::int32_t a, std::int32_t b) const {
  int count = 0;
  for (std::uint32_t k = excl_offsets_[a]; k < excl_offsets_[a + 1]; ++k)
    count += excl_partners_[k] == b ? 1 : 0;
  return count;
}

bool NeighbourList::AddBrokenBondPairs(std::vector<std::pair<std::int32_t, std::int32_t>> pairs) {
  const std::size_t n = offsets_.size() - 1;
  if (Stale(n) || parked_ || excl_offsets_.size() != n + 1) return false;
  for (auto& [owner, partner] : pairs) {
    if (BondsAtBuild(owner, partner) != 1) return false;
    if (!RowHolds(owner, partner)) std::swap(owner, partner);
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  // Where each pair goes in the old rows (sorted by partner); the rows keep their order.
  std::vector<std::uint32_t> at(pairs.size());
  for (std::size_t m = 0; m < pairs.size(); ++m) {
    const auto [owner, partner] = pairs[m];
    const auto first = partners_.begin() + offsets_[owner];
    const auto last = partners_.begin() + offsets_[owner + 1];
    const auto it = std::lower_bound(first, last, partner);
    if (it != last && *it == partner) return false;  // a bonded pair is never in the rows
    at[m] = static_cast<std::uint32_t>(it - partners_.begin());
  }
  // One pass that copies the entries between insertions as blocks.
  const std::size_t entries = partners_.size() + pairs.size();
  scratch_partners_.resize(entries);
  scratch_history_.resize(entries);
  std::size_t from = 0, to = 0;
  auto copy_to = [&](std::size_t end) {
    std::copy(partners_.begin() + from, partners_.begin() + end, scratch_partners_.begin() + to);
    std::copy(history_.begin() + from, history_.begin() + end, scratch_history_.begin() + to);
    to += end - from;
    from = end;
  };
  for (std::size_t m = 0; m < pairs.size(); ++m) {
    copy_to(at[m]);
    scratch_partners_[to] = pairs[m].second;
    scratch_history_[to] = Vec3::Zero();
    ++to;
  }
  copy_to(partners_.size());
  // Row i starts later by the pairs added to the rows before it.
  std::size_t added = 0;
  for (std::size_t i = 0; i <= n; ++i) {
    offsets_[i] += static_cast<std::uint32_t>(added);
    while (added < pairs.size() && static_cast<std::size_t>(pairs[added].first) == i) ++added;
  }
  partners_.swap(scratch_partners_);
  history_.swap(scratch_history_);
  owners_.resize(entries);
  for (std::size_t i = 0; i < n; ++i)
    std::fill(owners_.begin() + offsets_[i], owners_.begin() + offsets_[i + 1],
              static_cast<std::int32_t>(i));
  return true;
}

void NeighbourList::Build(const Particles& p, const Cell& cell, const Bonds& bonds, double skin) {
  const std::size_t n = p.size();
  skin_ = skin;
  BuildExclusions(n, bonds);
  double r_max = 0.0;
  double z_lo = 0.0, z_hi = 0.0;
  if (n > 0) {
    z_lo = z_hi = p.x[0].z();
    for (std::size_t i = 0; i < n; ++i) {
      r_max = std::max(r_max, p.radius[i]);
      z_lo = std::min(z_lo, p.x[i].z());
      z_hi = std::max(z_hi, p.x[i].z());
    }
  }
  const double cutoff = 2.0 * r_max + skin;

  Grid grid;
  grid.nx = std::max(1, static_cast<int>(std::floor(cell.Lx() / cutoff)));
  grid.ny = std::max(1, static_cast<int>(std::floor(cell.Ly() / cutoff)));
  grid.nz = std::max(1, std::min(static_cast<int>(std::floor((z_hi - z_lo) / cutoff)) + 1,
                                 1 << 16));
  grid.lo = Vec3(cell.lo.x(), cell.lo.y(), z_lo);
  grid.size = Vec3(cell.Lx() / grid.nx, cell.Ly() / grid.ny, cutoff);

  // Counting sort of particles into cells.
  cell_of_.resize(n);
  cell_start_.assign(grid.Count() + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    Vec3 x = p.x[i];
    cell.Wrap(x);
    const Vec3 t = (x - grid.lo).cwiseQuotient(grid.size);
    const int c = grid.Index(ClampCell(t.x(), grid.nx), ClampCell(t.y(), grid.ny),
                             ClampCell(t.z(), grid.nz));
    cell_of_[i] = c;
    ++cell_start_[c + 1];
  }
  for (int c = 0; c < grid.Count(); ++c) cell_start_[c + 1] += cell_start_[c];
  cell_members_.resize(n);
  {
    std::vector<std::int32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) cell_members_[fill[cell_of_[i]]++] = static_cast<int>(i);
  }

  // Neighbour cells of a cell, without repeats: a periodic direction with fewer than 3 cells
  // meets the same cell from both sides.
  const bool repeats = (cell.periodic_x && grid.nx < 3) || (cell.periodic_y && grid.ny < 3);
  auto neighbour_cells = [&](int c, std::array<int, 27>& out) {
    const int cx = c % grid.nx, cy = (c / grid.nx) % grid.ny, cz = c / (grid.nx * grid.ny);
    int count = 0;
    for (int dz = -1; dz <= 1; ++dz) {
      const int z = cz + dz;
      if (z < 0 || z >= grid.nz) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int y = cy + dy;
        if (y < 0 || y >= grid.ny) {
          if (!cell.periodic_y) continue;
          y = (y + grid.ny) % grid.ny;
        }
        for (int dx = -1; dx <= 1; ++dx) {
          int x = cx + dx;
          if (x < 0 || x >= grid.nx) {
            if (!cell.periodic_x) continue;
            x = (x + grid.nx) % grid.nx;
          }
          out[count++] = grid.Index(x, y, z);
        }
      }
    }
    if (!repeats) return count;
    std::sort(out.begin(), out.begin() + count);
    return static_cast<int>(std::unique(out.begin(), out.begin() + count) - out.begin());
  };

  // Appends row i's partners, sorted, to `row`.
  auto scan_row = [&](std::size_t i, std::vector<std::int32_t>& row) {
    const std::size_t start = row.size();
    std::array<int, 27> cells;
    const int count = neighbour_cells(cell_of_[i], cells);
    for (int k = 0; k < count; ++k) {
      for (int m = cell_start_[cells[k]]; m < cell_start_[cells[k] + 1]; ++m) {
        const std::int32_t j = cell_members_[m];
        if (!RowHolds(static_cast<std::int64_t>(i), j)) continue;
        const double reach = p.radius[i] + p.radius[j] + skin;
        if (cell.Delta(p.x[i], p.x[j]).squaredNorm() >= reach * reach) continue;
        if (BondsAtBuild(static_cast<std::int32_t>(i), j) > 0) continue;
        row.push_back(j);
      }
    }
    std::sort(row.begin() + static_cast<std::ptrdiff_t>(start), row.end());
  };

  // Each thread scans its static share of the rows once, into a buffer of its own; the rows
  // are then laid out from their counts and each thread copies its buffer in.
  const std::int64_t rows = static_cast<std::int64_t>(n);
  scratch_offsets_.assign(n + 1, 0);
  if (thread_rows_.size() < static_cast<std::size_t>(ThreadCount()))
    thread_rows_.resize(static_cast<std::size_t>(ThreadCount()));
  // Indices are stable while the particle count is, so the old rows still apply.
  const bool carry = offsets_.size() == n + 1 && !partners_.empty();
#pragma omp parallel
  {
    std::int64_t first, end;
    std::tie(first, end) = StaticShare(rows, ThreadId(), TeamSize());
    std::vector<std::int32_t>& found = thread_rows_[static_cast<std::size_t>(ThreadId())];
    found.clear();
    for (std::int64_t i = first; i < end; ++i) {
      const std::size_t before = found.size();
      scan_row(static_cast<std::size_t>(i), found);
      scratch_offsets_[i + 1] = static_cast<std::uint32_t>(found.size() - before);
    }
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t i = 0; i < n; ++i) scratch_offsets_[i + 1] += scratch_offsets_[i];
      scratch_partners_.resize(scratch_offsets_[n]);
      scratch_history_.assign(scratch_offsets_[n], Vec3::Zero());
      owners_.resize(scratch_offsets_[n]);
    }
    if (first < end)
      std::copy(found.begin(), found.end(), scratch_partners_.begin() + scratch_offsets_[first]);
    for (std::int64_t i = first; i < end; ++i) {
      std::fill(owners_.begin() + scratch_offsets_[i], owners_.begin() + scratch_offsets_[i + 1],
                static_cast<std::int32_t>(i));
      if (!carry) continue;
      // Carry the tangential history of pairs present before (both rows are sorted).
      std::uint32_t old = offsets_[i];
      const std::uint32_t old_end = offsets_[i + 1];
      for (std::uint32_t k = scratch_offsets_[i]; k < scratch_offsets_[i + 1]; ++k) {
        while (old < old_end && partners_[old] < scratch_partners_[k]) ++old;
        if (old < old_end && partners_[old] == scratch_partners_[k])
          scratch_history_[k] = history_[old];
      }
    }
  }
  offsets_.swap(scratch_offsets_);
  partners_.swap(scratch_partners_);
  history_.swap(scratch_history_);
  x_at_build_ = p.x;
  valid_ = true;
  ++builds_;
  build_id_ = next_build_id.fetch_add(1, std::memory_order_relaxed);
  if (parked_) RestoreParked(n);
}

void NeighbourList::RestoreParked(std::size_t particles) {
  // Pairs the new rows lack have come apart since (a cut, a removal): their history lapses,
  // as a rebuild drops it for a pair that left the list.
  if (particles == parked_particles_)
    for (const PairHistory& h : parked_history_) {
      Vec3 xi;
      if (const std::ptrdiff_t k = EntryOf(h, &xi); k >= 0) history_[k] = xi;
    }
  parked_ = false;
  parked_history_ = {};
}

NeighbourList NeighbourList::Parked() const {
  NeighbourList list;
  list.skin_ = skin_;
  list.builds_ = builds_;
  list.parked_ = true;
  list.parked_history_ = ExportHistory();
  list.parked_particles_ = parked_ ? parked_particles_ : offsets_.size() - 1;
  return list;
}

void NeighbourList::RotateHistory(const Mat3& R) {
  for (Vec3& h : history_) h = R * h;
  for (PairHistory& h : parked_history_) h.xi = R * h.xi;
}

bool NeighbourList::NeedsRebuild(const Particles& p, const Cell& cell) const {
  if (Stale(p.size())) return true;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  int moved = 0;
#pragma omp parallel for schedule(static) reduction(| : moved)
  for (std::int64_t i = 0; i < n; ++i) moved |= MovedTooFar(i, p.x[i], cell) ? 1 : 0;
  return moved != 0;
}

std::size_t NeighbourList::MemoryBytes() const {
  return offsets_.capacity() * sizeof(std::uint32_t) + partners_.capacity() * 4 +
         owners_.capacity() * 4 + history_.capacity() * sizeof(Vec3) +
         x_at_build_.capacity() * sizeof(Vec3) + excl_offsets_.capacity() * 4 +
         excl_partners_.capacity() * 4 +
         (cell_of_.capacity() + cell_start_.capacity() + cell_members_.capacity()) * 4 +
         scratch_offsets_.capacity() * 4 + scratch_partners_.capacity() * 4 +
         scratch_history_.capacity() * sizeof(Vec3) + ThreadRowsBytes() +
         parked_history_.capacity() * sizeof(PairHistory);
}

std::size_t NeighbourList::ThreadRowsBytes() const {
  std::size_t bytes = 0;
  for (const std::vector<std::int32_t>& rows : thread_rows_) bytes += rows.capacity() * 4;
  return bytes;
}

std::vector<PairHistory> NeighbourList::ExportHistory() const {
  if (parked_) return parked_history_;
  std::vector<PairHistory> out;
  for (std::size_t i = 0; i + 1 < offsets_.size(); ++i)
    for (std::size_t k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      if (history_[k].isZero(0.0)) continue;
      const std::int32_t owner = static_cast<std::int32_t>(i), partner = partners_[k];
      // Stored from the lower index's side: the history of the pair seen from j is -xi.
      if (owner < partner)
        out.push_back({owner, partner, history_[k]});
      else
        out.push_back({partner, owner, -history_[k]});
    }
  return out;
}

std::ptrdiff_t NeighbourList::EntryOf(const PairHistory& h, Vec3* xi_in_row) const {
  const bool in_row_i = RowHolds(h.i, h.j);
  const std::int32_t owner = in_row_i ? h.i : h.j, partner = in_row_i ? h.j : h.i;
  const auto first = partners_.begin() + offsets_[owner];
  const auto last = partners_.begin() + offsets_[owner + 1];
  const auto it = std::lower_bound(first, last, partner);
  if (it == last || *it != partner) return -1;
  // Seen from the other side of the pair, the tangential displacement changes sign.
  *xi_in_row = owner == h.i ? h.xi : Vec3(-h.xi);
  return it - partners_.begin();
}

void NeighbourList::ImportHistory(const std::vector<PairHistory>& history) {
  const auto outside = [&](std::int32_t i) {
    return i < 0 || static_cast<std::size_t>(i) + 1 >= offsets_.size();
  };
  for (const PairHistory& h : history) {
    if (outside(h.i) || outside(h.j) || h.i == h.j)
      throw std::invalid_argument("contact history names a particle outside the list");
    Vec3 xi;
    const std::ptrdiff_t k = EntryOf(h, &xi);
    if (k < 0) throw std::invalid_argument("contact history names a pair the neighbour list lacks");
    history_[k] = xi;
  }
}

}  // namespace fibrenet
