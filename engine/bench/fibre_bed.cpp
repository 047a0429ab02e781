#include "engine/bench/fibre_bed.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/morton.h"

namespace fibrenet::bench {

namespace {

// A fibre as placed: centre in the plane, in-plane angle, layer.
struct PlacedFibre {
  double cx = 0.0, cy = 0.0, angle = 0.0;
  int layer = 0;
  double z = 0.0;  // height of the fibre axis [m]
};

// Random sequential placement of straight fibres in layers: a fibre is accepted when none
// of its particles comes closer than `clearance` (in the plane) to a particle of another
// fibre in the same layer; a layer that refuses a fibre `kAttempts` times is full and the
// next one opens. Deterministic for a given seed.
class LayerPlacer {
 public:
  LayerPlacer(const FibreBedSpec& s, const Cell& cell, double clearance)
      : spec_(s), cell_(cell), clearance_(clearance), rng_(s.seed) {
    n_ = std::max(1, static_cast<int>(std::floor(cell.Lx() / clearance)));
    head_.assign(static_cast<std::size_t>(n_) * n_, -1);
    if (s.deposit) all_head_.assign(static_cast<std::size_t>(n_) * n_, -1);
  }

  std::vector<PlacedFibre> Place(int fibres, int per_layer) {
    std::vector<PlacedFibre> placed;
    placed.reserve(fibres);
    int layer = 0, in_layer = 0;
    while (static_cast<int>(placed.size()) < fibres) {
      if (in_layer == per_layer) {
        NewLayer();
        layer += 1;
        in_layer = 0;
      }
      PlacedFibre f;
      bool ok = false;
      for (int attempt = 0; attempt < kAttempts && !ok; ++attempt) {
        f.cx = uniform_(rng_) * cell_.Lx();
        f.cy = uniform_(rng_) * cell_.Ly();
        f.angle = uniform_(rng_) * kPi;
        f.layer = layer;
        ok = Fits(f);
      }
      if (!ok) {  // the layer is full: open the next one and try again there
        in_layer = per_layer;
        continue;
      }
      f.z = spec_.deposit ? Deposit(f) : LayerHeight(f.layer);
      Insert(f);
      placed.push_back(f);
      ++in_layer;
    }
    return placed;
  }

  // In-plane position of particle k of a fibre, wrapped into the cell.
  Vec3 ParticleXY(const PlacedFibre& f, int k) const {
    const double s = (k - 0.5 * (spec_.particles_per_fibre - 1)) * 2.0 * spec_.radius;
    Vec3 x(f.cx + s * std::cos(f.angle), f.cy + s * std::sin(f.angle), 0.0);
    cell_.Wrap(x);
    return x;
  }

 private:
  static constexpr int kAttempts = 400;

  int GridCell(const Vec3& x) const {
    const int cx = std::min(n_ - 1, static_cast<int>((x.x() - cell_.lo.x()) / cell_.Lx() * n_));
    const int cy = std::min(n_ - 1, static_cast<int>((x.y() - cell_.lo.y()) / cell_.Ly() * n_));
    return cy * n_ + cx;
  }

  bool Fits(const PlacedFibre& f) const {
    const double limit2 = clearance_ * clearance_;
    for (int k = 0; k < spec_.particles_per_fibre; ++k) {
      const Vec3 x = ParticleXY(f, k);
      const int c = GridCell(x);
      const int cx = c % n_, cy = c / n_;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int gx = (cx + dx + n_) % n_, gy = (cy + dy + n_) % n_;
          for (int m = head_[gy * n_ + gx]; m >= 0; m = next_[m])
            if (cell_.Delta(x, xy_[m]).squaredNorm() < limit2) return false;
        }
      }
    }
    return true;
  }

  void Insert(const PlacedFibre& f) {
    for (int k = 0; k < spec_.particles_per_fibre; ++k) {
      const Vec3 x = ParticleXY(f, k);
      const int c = GridCell(x);
      xy_.push_back(x);
      next_.push_back(head_[c]);
      head_[c] = static_cast<int>(xy_.size() - 1);
      if (!spec_.deposit) continue;
      all_xyz_.push_back(Vec3(x.x(), x.y(), f.z));
      all_next_.push_back(all_head_[c]);
      all_head_[c] = static_cast<int>(all_xyz_.size() - 1);
    }
  }

  double LayerHeight(int layer) const {
    return spec_.radius + spec_.gap + layer * (2.0 * spec_.radius + spec_.gap);
  }

  // The lowest height at which the (horizontal) fibre clears every fibre placed before it
  // and the floor by the clearance: it rests on its highest support.
  double Deposit(const PlacedFibre& f) const {
    const double c2 = clearance_ * clearance_;
    double z = LayerHeight(0);
    for (int k = 0; k < spec_.particles_per_fibre; ++k) {
      const Vec3 x = ParticleXY(f, k);
      const int c = GridCell(x);
      const int cx = c % n_, cy = c / n_;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int gx = (cx + dx + n_) % n_, gy = (cy + dy + n_) % n_;
          for (int m = all_head_[gy * n_ + gx]; m >= 0; m = all_next_[m]) {
            const Vec3 below(all_xyz_[m].x(), all_xyz_[m].y(), 0.0);
            const double d2 = cell_.Delta(x, below).squaredNorm();
            if (d2 < c2) z = std::max(z, all_xyz_[m].z() + std::sqrt(c2 - d2));
          }
        }
      }
    }
    return z;
  }

  void NewLayer() {
    std::fill(head_.begin(), head_.end(), -1);
    xy_.clear();
    next_.clear();
  }

  const FibreBedSpec& spec_;
  const Cell& cell_;
  double clearance_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
  int n_ = 1;
  std::vector<int> head_, next_;  // linked cells of the particles of the current layer
  std::vector<Vec3> xy_;
  // Every particle placed so far (deposition only).
  std::vector<int> all_head_, all_next_;
  std::vector<Vec3> all_xyz_;
};

}  // namespace

std::string FibreBedSpec::Validate() const {
  auto finite_positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (particles_per_fibre < 2 || particles_per_fibre > 1000)
    return fmt::format("particles_per_fibre = {}: must be in [2, 1000]", particles_per_fibre);
  const std::int64_t min_particles = 10 * static_cast<std::int64_t>(particles_per_fibre);
  if (particles < min_particles || particles > 100'000'000)
    return fmt::format("particles = {}: must be in [{}, 100000000] (10 fibres or more)",
                       particles, min_particles);
  if (!finite_positive(radius)) return fmt::format("radius = {} m: must be > 0", radius);
  if (!finite_positive(E)) return fmt::format("E = {} Pa: must be > 0", E);
  if (!finite_positive(G)) return fmt::format("G = {} Pa: must be > 0", G);
  if (!finite_positive(coarseness))
    return fmt::format("coarseness = {} kg/m: must be > 0", coarseness);
  if (layers < 1 || layers > 10000) return fmt::format("layers = {}: must be in [1, 10000]", layers);
  if (!(coverage > 0.0 && coverage <= 0.4))
    return fmt::format("coverage = {}: must be in (0, 0.4]", coverage);
  if (!finite_positive(gap)) return fmt::format("gap = {} m: must be > 0", gap);
  if (!(std::isfinite(approach_speed) && approach_speed >= 0.0))
    return fmt::format("approach_speed = {} m/s: must be >= 0", approach_speed);
  if (!(std::isfinite(gravity) && gravity >= 0.0))
    return fmt::format("gravity = {} m/s^2: must be >= 0", gravity);
  if (!(std::isfinite(mu) && mu >= 0.0)) return fmt::format("mu = {}: must be >= 0", mu);
  if (!(restitution > 0.0 && restitution <= 1.0))
    return fmt::format("restitution = {}: must be in (0, 1]", restitution);
  if (!(safety > 0.0 && safety <= 1.0)) return fmt::format("safety = {}: must be in (0, 1]", safety);
  if (!(std::isfinite(drag_coefficient) && drag_coefficient >= 0.0))
    return fmt::format("drag_coefficient = {} N s/m: must be >= 0", drag_coefficient);
  if (!(std::isfinite(maxwell_tau) && maxwell_tau >= 0.0))
    return fmt::format("maxwell_tau = {} s: must be >= 0", maxwell_tau);
  return {};
}

FibreBedInfo BuildFibreBed(const FibreBedSpec& spec, World& w) {
  if (std::string m = spec.Validate(); !m.empty()) throw InputError("fibre bed: " + m);
  if (w.particles.size() != 0) throw InputError("fibre bed: the world must start empty");
  const int ppf = spec.particles_per_fibre;
  const double R = spec.radius, spacing = 2.0 * R;
  const int fibres = static_cast<int>(spec.particles / ppf);
  const int per_layer = (fibres + spec.layers - 1) / spec.layers;

  // Cell edge from the projected area of one layer at the requested coverage; at least
  // 1.5 fibre lengths so that a fibre never meets its own periodic image.
  const double fibre_length = ppf * spacing;
  const double side = std::max(std::sqrt(per_layer * fibre_length * spacing / spec.coverage),
                               1.5 * fibre_length);
  Cell& cell = w.cell;
  cell.lo = Vec3::Zero();
  cell.hi = Vec3(side, side, 1.0);  // z is bounded by the floor, not periodic
  cell.periodic_x = cell.periodic_y = true;

  LayerPlacer placer(spec, cell, spacing + spec.gap);
  std::vector<PlacedFibre> placed = placer.Place(fibres, per_layer);
  int layers = 0;
  double z_top = 0.0;
  for (const PlacedFibre& f : placed) {
    layers = std::max(layers, f.layer + 1);
    z_top = std::max(z_top, f.z);
  }
  cell.hi.z() = z_top + spacing;

  std::vector<int> order(placed.size());
  std::iota(order.begin(), order.end(), 0);
  if (spec.spatial_order) {
    // Tiles of half a fibre length, visited in Morton order; within a tile, by layer.
    const double tile = 0.5 * fibre_length;
    std::vector<std::uint64_t> key(placed.size());
    for (std::size_t f = 0; f < placed.size(); ++f) {
      const auto tx = static_cast<std::uint32_t>(placed[f].cx / tile);
      const auto ty = static_cast<std::uint32_t>(placed[f].cy / tile);
      key[f] = (static_cast<std::uint64_t>(MortonKey(tx, ty)) << 20) |
               static_cast<std::uint64_t>(placed[f].layer);
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key[a] < key[b]; });
  } else {
    std::mt19937_64 shuffle(spec.seed);
    std::shuffle(order.begin(), order.end(), shuffle);
  }

  Particles& p = w.particles;
  p.Reserve(static_cast<std::size_t>(fibres) * ppf);
  const double mass = spec.coarseness * spacing;
  BeamBondParams bond = BeamBondParams::FromBeam(spec.E, spec.G, R, spacing);
  bond.maxwell_tau = spec.maxwell_tau;
  const std::int32_t type = w.bonds.AddType(bond);
  const std::size_t n_bonds = static_cast<std::size_t>(fibres) * (ppf - 1);
  w.bonds.i.reserve(n_bonds);
  w.bonds.j.reserve(n_bonds);
  w.bonds.type.reserve(n_bonds);
  w.bonds.kind.reserve(n_bonds);
  w.bonds.state.reserve(n_bonds);
  w.bonds.broken.reserve(n_bonds);
  for (int id = 0; id < fibres; ++id) {
    const PlacedFibre& f = placed[order[id]];
    // A uniform compaction: every gap of height difference 2R closes at approach_speed.
    const Vec3 v(0.0, 0.0, -spec.approach_speed * (f.z + R) / spacing);
    const auto first = static_cast<std::int32_t>(p.size());
    for (int k = 0; k < ppf; ++k) {
      Vec3 x = placer.ParticleXY(f, k);
      x.z() = f.z;
      const std::size_t i = p.Add(x, R, mass, id);
      p.v[i] = v;
    }
    for (int k = 0; k + 1 < ppf; ++k) {
      const std::int32_t a = first + k, b = a + 1;
      w.bonds.Add(a, b, type, BondKind::kFibre,
                  MakeBondState(cell.Delta(p.x[a], p.x[b]), p.q[a], p.q[b], spacing));
    }
  }

  w.contact = ContactParams{};
  w.contact.mu = spec.mu;
  w.contact.restitution = spec.restitution;
  w.contact.Derive();
  w.physics = Physics{};
  w.physics.contacts = spec.contacts;
  w.physics.friction = spec.friction;
  w.physics.gravity = spec.use_gravity;
  w.physics.g = Vec3(0.0, 0.0, -spec.gravity);
  w.physics.drag = spec.drag_coefficient > 0.0;
  w.physics.drag_coefficient = spec.drag_coefficient;
  Wall floor;
  floor.z = 0.0;
  floor.side = +1;
  floor.friction = true;
  w.walls.assign(1, floor);
  w.settings = StepSettings{};
  w.settings.safety = spec.safety;

  FibreBedInfo info;
  info.particles = static_cast<std::int64_t>(p.size());
  info.bonds = static_cast<std::int64_t>(w.bonds.size());
  info.fibres = fibres;
  info.layers = layers;
  info.cell_side = side;
  return info;
}

std::int64_t CountTouchingPairs(const World& w) {
  if (!w.physics.contacts || w.neighbours.builds() == 0) return 0;
  const Particles& p = w.particles;
  const NeighbourList& nl = w.neighbours;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  std::int64_t touching = 0;
#pragma omp parallel for schedule(static) reduction(+ : touching)
  for (std::int64_t i = 0; i < n; ++i) {
    for (std::size_t k = nl.RowBegin(i); k < nl.RowEnd(i); ++k) {
      const std::int32_t j = nl.Partner(k);
      const double reach = p.radius[i] + p.radius[j];
      if (w.cell.Delta(p.x[i], p.x[j]).squaredNorm() < reach * reach) ++touching;
    }
  }
  return touching;
}

}  // namespace fibrenet::bench
