#include "engine/pipeline/test_rig.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/parallel.h"
#include "engine/core/time_step.h"

namespace fibrenet::pipeline {

std::string MaterialSwitches::Validate() const {
  if (!(maxwell_tau >= 0.0 && maxwell_tau <= 1e6))
    return fmt::format("maxwell_tau = {} s: must lie in [0, 1e6] (0 = keep the network's)",
                       maxwell_tau);
  return {};
}

std::string QuasiStaticSettings::Validate() const {
  if (!(mass_scale == 0.0 || (mass_scale >= 1.0 && mass_scale <= 1e15)))
    return fmt::format("mass_scale = {}: must be 0 (automatic) or lie in [1, 1e15]", mass_scale);
  if (!(loading_steps >= 100.0 && loading_steps <= 1e8))
    return fmt::format("loading_steps = {}: must lie in [100, 1e8]", loading_steps);
  if (!(bond_damping_ratio >= 0.0 && bond_damping_ratio <= 1.0))
    return fmt::format("bond_damping_ratio = {}: must lie in [0, 1]", bond_damping_ratio);
  if (!(drag_time_fraction >= 0.0 && drag_time_fraction <= 10.0))
    return fmt::format("drag_time_fraction = {}: must lie in [0, 10] (0 = off)", drag_time_fraction);
  if (!(local_damping >= 0.0 && local_damping < 1.0))
    return fmt::format("local_damping = {}: must lie in [0, 1) (0 = off)", local_damping);
  if (!(kinetic_work_tolerance > 0.0 && kinetic_work_tolerance <= 1.0))
    return fmt::format("kinetic_work_tolerance = {}: must lie in (0, 1]", kinetic_work_tolerance);
  if (!(time_step_safety > 0.0 && time_step_safety <= 1.0))
    return fmt::format("time_step_safety = {}: must lie in (0, 1]", time_step_safety);
  return {};
}

std::string ValidateLoading(int samples, std::int64_t max_steps, const MaterialSwitches& s,
                            const QuasiStaticSettings& q) {
  if (samples < 10 || samples > 100000)
    return fmt::format("samples = {}: must lie in [10, 100000]", samples);
  if (max_steps < 1) return fmt::format("max_steps = {}: must be >= 1", max_steps);
  if (std::string why = s.Validate(); !why.empty()) return why;
  return q.Validate();
}

void ApplyTestPhysics(Network& net, const MaterialSwitches& s) {
  World& w = net.world;
  w.physics.gravity = false;
  w.physics.drag = false;
  w.physics.applied_loads = false;
  w.walls.clear();
  if (s.friction) w.physics.friction = *s.friction && w.contact.mu > 0.0;
  std::set<std::int32_t> fibre_types;
  for (const FibreRecord& f : net.fibres) fibre_types.insert(f.bond_type);
  for (std::size_t t = 0; t < w.bonds.types.size(); ++t) {
    BeamBondParams& p = w.bonds.types[t];
    if (!s.bond_failure) p.failure = BondFailure::kNone;
    if (!s.viscoelastic)
      p.maxwell_tau = 0.0;
    else if (s.maxwell_tau > 0.0 && fibre_types.count(static_cast<std::int32_t>(t)))
      p.maxwell_tau = s.maxwell_tau;
  }
}

void AddBondDamping(World& w, double ratio) {
  const Particles& p = w.particles;
  if (ratio <= 0.0 || p.size() == 0) return;
  double m = 0.0, inertia = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    m += p.mass[i];
    inertia += p.inertia[i];
  }
  m /= static_cast<double>(p.size());
  inertia /= static_cast<double>(p.size());
  // The types are sized for two particles of mean mass on a spring k: reduced mass m/2,
  // critical damping 2 sqrt(k m/2).
  for (BeamBondParams& t : w.bonds.types) {
    t.damping_n = std::max(t.damping_n, 2.0 * ratio * std::sqrt(0.5 * m * t.k_n));
    t.damping_s = std::max(t.damping_s, 2.0 * ratio * std::sqrt(0.5 * m * t.k_s));
    t.damping_rot =
        std::max(t.damping_rot, 2.0 * ratio * std::sqrt(0.5 * inertia * std::max(t.k_b, t.k_t)));
  }
  // Each bond for its own pair: critical damping goes as the square root of the reduced mass
  // 1 / (1/m_i + 1/m_j), a pinned end counting as infinitely heavy. Sized on the mean pair
  // alone, a light fibre's bonds were damped at several times `ratio`, and the explicit step
  // that holds for its stiffness and mass went unstable under that damping.
  const auto factor = [](double inverse_i, double inverse_j, double mean) {
    const double inverse = inverse_i + inverse_j;
    return inverse > 0.0 ? static_cast<float>(std::sqrt(2.0 / (inverse * mean))) : 1.0f;
  };
  Bonds& bonds = w.bonds;
  bonds.damping_factors.resize(bonds.size());
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const std::int32_t i = bonds.i[b], j = bonds.j[b];
    bonds.damping_factors[b] = {factor(p.inv_mass[i], p.inv_mass[j], m),
                                factor(p.inv_inertia[i], p.inv_inertia[j], inertia)};
  }
}

void ApplyQuasiStaticDamping(World& w, const QuasiStaticSettings& s) {
  AddBondDamping(w, s.bond_damping_ratio);
  w.physics.local_damping = s.local_damping;
}

double ChooseMassScale(World& w, const QuasiStaticSettings& s, double loading_time) {
  w.settings.safety = s.time_step_safety;
  w.settings.dt = 0.0;
  double M = s.mass_scale;
  if (M < 1.0) {
    const double dt1 = s.time_step_safety * CriticalTimeStep(w).dt_crit;
    const double wanted_dt = loading_time / s.loading_steps;
    M = std::clamp(std::pow(wanted_dt / dt1, 2.0), 1.0, 1e15);
  }
  if (M != 1.0) ScaleMasses(w, M);
  return M;
}

void QuarterTurn(Network& net) {
  World& w = net.world;
  Cell& c = w.cell;
  const Vec3 lo = c.lo, hi = c.hi;
  Mat3 R;
  R << 0.0, 1.0, 0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 1.0;
  // (x, y) -> (lo.x + y - lo.y, lo.y + hi.x - x): the turned cell starts where this one did.
  TransformRigidly(w, R, Vec3(lo.x() - lo.y(), lo.y() + hi.x(), 0.0));
  c.hi = Vec3(lo.x() + c.Ly(), lo.y() + (hi.x() - lo.x()), hi.z());
  std::swap(c.periodic_x, c.periodic_y);
  for (Vec3& x : w.particles.x) c.Wrap(x);
}

std::size_t CutAlongX(Network& net, double margin) {
  World& w = net.world;
  const double Lx = w.cell.Lx();
  std::size_t cut = 0;
  if (w.cell.periodic_x) {
    for (std::size_t b = 0; b < w.bonds.size(); ++b) {
      if (w.bonds.broken[b]) continue;
      const double dx = w.particles.x[w.bonds.j[b]].x() - w.particles.x[w.bonds.i[b]].x();
      if (std::abs(dx) > 0.5 * Lx) {
        w.bonds.broken[b] = 1;
        ++cut;
      }
    }
  }
  w.cell.periodic_x = false;
  w.cell.lo.x() -= margin;
  w.cell.hi.x() += margin;
  w.neighbours.Invalidate();
  return cut;
}

StripEnds FindStripEnds(const World& w) {
  const Particles& p = w.particles;
  StripEnds ends{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                 w.cell.Lx()};
  double r_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ends.lo = std::min(ends.lo, p.x[i].x());
    ends.hi = std::max(ends.hi, p.x[i].x());
    r_max = std::max(r_max, p.radius[i]);
  }
  if (p.size() == 0 || w.cell.periodic_x) return ends;
  ends.length = ends.hi - ends.lo;
  const double bin = 4.0 * r_max;
  const int bins = static_cast<int>(std::ceil(ends.length / bin));
  if (bins < 4) return ends;
  const double origin = ends.lo;
  auto bin_of = [&](std::size_t i) {
    return std::min(bins - 1, static_cast<int>((p.x[i].x() - origin) / bin));
  };
  std::vector<double> mass(static_cast<std::size_t>(bins), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) mass[bin_of(i)] += p.mass[i];
  std::vector<double> sorted = mass;
  std::nth_element(sorted.begin(), sorted.begin() + bins / 2, sorted.end());
  const double threshold = 0.5 * sorted[bins / 2];
  int first = 0, last = bins - 1;
  while (mass[first] < threshold) ++first;
  while (mass[last] < threshold) --last;
  // The ends are the outermost particle centres in the bins from the first whole one to the
  // last: a bin's edge would add up to a bin where a tail runs on beyond the strip.
  ends.lo = std::numeric_limits<double>::infinity();
  ends.hi = -ends.lo;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int b = bin_of(i);
    if (b < first || b > last) continue;
    ends.lo = std::min(ends.lo, p.x[i].x());
    ends.hi = std::max(ends.hi, p.x[i].x());
  }
  ends.length = ends.hi - ends.lo;
  return ends;
}

double SheetArea(const World& w) {
  const Particles& p = w.particles;
  if (w.cell.periodic_x || p.size() == 0) return w.cell.Lx() * w.cell.Ly();
  // The ends are particle centres: the strip's footprint reaches a radius beyond each.
  double diameter = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) diameter += 2.0 * p.radius[i];
  diameter /= static_cast<double>(p.size());
  return (FindStripEnds(w).length + diameter) * w.cell.Ly();
}

double GripLength(const StripEnds& ends, double grip_length, const std::string& key) {
  const double grip = grip_length > 0.0 ? grip_length : 0.1 * ends.length;
  if (!(2.0 * grip < 0.8 * ends.length))
    throw InputError(fmt::format("{} = {} m: the grips must leave at least 20% of the {} m strip "
                                 "free", key, grip, ends.length));
  return grip;
}

Grips MakeGrips(const World& w, const StripEnds& ends, double grip_length) {
  const Particles& p = w.particles;
  Grips g;
  if (p.size() == 0) return g;
  const double cut_left = ends.lo + grip_length, cut_right = ends.hi - grip_length;
  g.x_left = -std::numeric_limits<double>::infinity();
  g.x_right = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.x[i].x();
    if (x < cut_left) {
      g.left.push_back(static_cast<std::int32_t>(i));
      g.x_left = std::max(g.x_left, x);
    }
    if (x > cut_right) {
      g.right.push_back(static_cast<std::int32_t>(i));
      g.x_right = std::min(g.x_right, x);
    }
  }
  g.span = g.x_right - g.x_left;
  return g;
}

void DriveGrips(World& w, const Grips& g, double V, int sign, bool first, double strain) {
  Particles& p = w.particles;
  // The stretch the grips impose, as the tensile test's damping reference states it.
  const AffineField stretch{0, 0.5 * (g.x_left + g.x_right), 0.5 * g.span * (1.0 + strain),
                            sign * 0.5 * V};
  std::vector<std::uint8_t> held(p.size(), 0);
  for (const auto* side : {&g.left, &g.right}) {
    const double direction = side == &g.left ? -1.0 : 1.0;
    for (const std::int32_t i : *side) {
      held[i] = 1;
      p.Fix(i);
      p.v[i] = Vec3(direction * sign * 0.5 * V, 0.0, 0.0);
      p.omega[i].setZero();
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (held[i]) continue;
    const double affine = stretch.At(p.x[i]).x();
    if (first)
      p.v[i].x() = affine;
    else
      p.v[i].x() += 2.0 * affine;  // the previous affine part was -affine
  }
}

double GripTension(const World& w, const Grips& g) {
  double left = 0.0, right = 0.0;
  for (const std::int32_t i : g.left) left += w.particles.force[i].x();
  for (const std::int32_t i : g.right) right += w.particles.force[i].x();
  return 0.5 * (left - right);
}

double GripPower(const World& w, const Grips& g) {
  double power = 0.0;
  for (const auto* side : {&g.left, &g.right})
    for (const std::int32_t i : *side) power -= w.particles.force[i].dot(w.particles.v[i]);
  return power;
}

double FluctuatingKineticEnergy(const World& w, const std::vector<std::uint8_t>& held,
                                const AffineField& field) {
  const Particles& p = w.particles;
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (held[i]) continue;
    const Vec3 v = p.v[i] - field.At(p.x[i]);
    e += 0.5 * (p.mass[i] * v.squaredNorm() + p.inertia[i] * p.omega[i].squaredNorm());
  }
  return e;
}

void ApplyAffineDrag(World& w, const std::vector<std::uint8_t>& held, const AffineField& field,
                     double tau) {
  Particles& p = w.particles;
  w.physics.applied_loads = true;
  w.applied_force.resize(p.size(), Vec3::Zero());
  w.applied_torque.resize(p.size(), Vec3::Zero());
  const double rate = 1.0 / tau;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static) if (ThreadsPay(p.size()))
  for (std::int64_t i = 0; i < n; ++i) {
    if (held[i]) {
      w.applied_force[i].setZero();
      w.applied_torque[i].setZero();
      continue;
    }
    w.applied_force[i] = -(p.mass[i] * rate) * (p.v[i] - field.At(p.x[i]));
    w.applied_torque[i] = -(p.inertia[i] * rate) * p.omega[i];
  }
}

double DragVirial(const World& w, const std::vector<std::uint8_t>& held, int axis, double origin) {
  if (!w.physics.applied_loads || w.applied_force.size() != w.particles.size()) return 0.0;
  double v = 0.0;
  for (std::size_t i = 0; i < w.particles.size(); ++i)
    if (!held[i]) v += (w.particles.x[i][axis] - origin) * w.applied_force[i][axis];
  return v;
}

Mat3 InteractionVirial(const World& w) {
  const Particles& p = w.particles;
  Mat3 W = Mat3::Zero();
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.broken[b]) continue;
    const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
    BondState copy = w.bonds.state[b];
    const BondGeometry g{w.cell.Delta(p.x[i], p.x[j]), p.q[i], p.q[j], p.v[j] - p.v[i],
                         p.omega[i], p.omega[j]};
    const BondResult r =
        EvaluateBond(g, w.bonds.types[w.bonds.type[b]], copy, 0.0, w.bonds.DampingFactors(b));
    if (!r.broken) W += g.d * r.force_i.transpose();
  }
  if (!w.physics.contacts) return W;
  const NeighbourList& nl = w.neighbours;
  if (nl.size() == 0 && p.size() > 0) return W;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t k = nl.RowBegin(i); k < nl.RowEnd(i); ++k) {
      const std::int32_t j = nl.Partner(k);
      const Vec3 d = w.cell.Delta(p.x[i], p.x[j]);
      const double dist = d.norm();
      if (dist >= p.radius[i] + p.radius[j]) continue;
      const double m_sum = p.mass[i] + p.mass[j];
      const ContactGeometry g{d,          dist,       p.radius[i], p.radius[j],
                              p.mass[i] * p.mass[j] / m_sum,      p.v[j] - p.v[i],
                              p.omega[i], p.omega[j]};
      Vec3 xi = nl.History(k);
      const ContactResult r = EvaluateContact(g, w.contact, xi, 0.0, w.physics.friction);
      W -= d * r.force_j.transpose();
    }
  }
  return W;
}

double FitSlope(const std::vector<double>& x, const std::vector<double>& y,
                const std::vector<double>& key, double key_lo, double key_hi, std::size_t begin,
                std::size_t end) {
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t k = begin; k < end && k < x.size(); ++k) {
    if (!(key[k] >= key_lo && key[k] <= key_hi)) continue;
    n += 1.0;
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double det = n * sxx - sx * sx;
  if (n < 2.0 || !(std::abs(det) > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / det;
}

double Trapezoid(const std::vector<double>& x, const std::vector<double>& y, std::size_t begin,
                 std::size_t end) {
  double area = 0.0;
  for (std::size_t k = begin + 1; k < end && k < x.size(); ++k)
    area += 0.5 * (y[k] + y[k - 1]) * (x[k] - x[k - 1]);
  return area;
}

}  // namespace fibrenet::pipeline
