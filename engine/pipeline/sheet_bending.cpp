#include "engine/pipeline/sheet_bending.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/simulation.h"

namespace fibrenet::pipeline {

namespace {

// Steps between the parts of a ramped curvature increment.
constexpr int kRampStepsPerPart = 10;

double Sinc(double t) { return std::abs(t) < 1e-4 ? 1.0 - t * t / 6.0 : std::sin(t) / t; }

// The kinematics of pure bending of a strip whose free span S lies between pivots at x_c -+
// S/2 on the mid-plane z_mid.
struct BendingGeometry {
  double x_c = 0.0, z_mid = 0.0, span = 0.0;

  // Where a free particle with reference point X goes at curvature kappa: the mid-plane
  // becomes the arc through the pivots (centre of curvature above it), plane sections stay
  // plane and normal to it:
  //   x = O + (1/kappa - Z) (sin phi, -cos phi),  phi = kappa a,  a = X - x_c,
  //   O = (x_c, z_mid + cos(kappa S / 2) / kappa),  Z = X_z - z_mid,
  // written with sinc so that it stays exact as kappa -> 0 (p = (S/2 + a)/2, q = (S/2 - a)/2,
  // from cos B - cos A = -2 sin((B+A)/2) sin((B-A)/2)).
  Vec3 Bent(const Vec3& X, double kappa) const {
    const double Z = X.z() - z_mid, a = X.x() - x_c, phi = kappa * a;
    const double p = 0.5 * (0.5 * span + a), q = 0.5 * (0.5 * span - a);
    return Vec3(x_c + a * Sinc(phi) - Z * std::sin(phi), X.y(),
                z_mid - 2.0 * kappa * p * q * Sinc(kappa * p) * Sinc(kappa * q) + Z * std::cos(phi));
  }
  // Rotation angle about +y of the section at X (the tangent turns by phi toward +z).
  double Angle(const Vec3& X, double kappa) const { return -kappa * (X.x() - x_c); }
  // Pivot of the left (-1) or right (+1) grip.
  Vec3 Pivot(int side, double kappa) const {
    const double chord = span * Sinc(0.5 * kappa * span);
    return Vec3(x_c + side * 0.5 * chord, 0.0, z_mid);
  }
};

}  // namespace

std::string BendingSettings::Validate() const {
  if (!(grip_length >= 0.0 && grip_length <= 1.0))
    return fmt::format("grip_length = {} m: must lie in [0, 1] (0 = 10% of the strip)", grip_length);
  if (!(max_curvature > 0.0 && max_curvature <= 1e5))
    return fmt::format("max_curvature = {} 1/m: must lie in (0, 1e5]", max_curvature);
  if (!(fit_from >= 0.0 && fit_from < 1.0))
    return fmt::format("fit_from = {}: must lie in [0, 1)", fit_from);
  if (levels < 2 || levels > 100) return fmt::format("levels = {}: must lie in [2, 100]", levels);
  if (relax_steps < 10 || relax_steps > 10'000'000)
    return fmt::format("relax_steps = {}: must lie in [10, 1e7]", relax_steps);
  if (relax_check < 1 || relax_check > relax_steps)
    return fmt::format("relax_check = {}: must lie in [1, relax_steps = {}]", relax_check,
                       relax_steps);
  if (ramp_steps < 0 || ramp_steps > 10'000'000)
    return fmt::format("ramp_steps = {}: must lie in [0, 1e7] (0 = each level at once)", ramp_steps);
  if (!(relax_tolerance > 0.0 && relax_tolerance < 1.0))
    return fmt::format("relax_tolerance = {}: must lie in (0, 1)", relax_tolerance);
  if (!(relax_time_steps >= 0.0 && relax_time_steps <= 1e6))
    return fmt::format("relax_time_steps = {}: must lie in [0, 1e6] (0 = no drag)",
                       relax_time_steps);
  if (!(local_damping >= 0.0 && local_damping < 1.0))
    return fmt::format("local_damping = {}: must lie in [0, 1) (0 = off)", local_damping);
  if (relax_time_steps == 0.0 && local_damping == 0.0)
    return "relax_time_steps = 0 and local_damping = 0: the relaxation needs a drag or local "
           "damping";
  if (!(bond_damping_ratio >= 0.0 && bond_damping_ratio <= 1.0))
    return fmt::format("bond_damping_ratio = {}: must lie in [0, 1]", bond_damping_ratio);
  if (!(time_step_safety > 0.0 && time_step_safety <= 1.0))
    return fmt::format("time_step_safety = {}: must lie in (0, 1]", time_step_safety);
  return switches.Validate();
}

BendingResult RunBendingTest(Network net, const BendingSettings& s, const Progress& progress) {
  if (std::string why = s.Validate(); !why.empty()) throw InputError("bending." + why);
  World& w = net.world;
  Particles& p = w.particles;
  if (p.size() == 0) throw RunError("bending test: the network has no particles");
  ApplyTestPhysics(net, s.switches);
  if (s.axis == LoadAxis::kCD) QuarterTurn(net);
  double z_mid = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v[i].setZero();
    p.omega[i].setZero();
    z_mid += p.x[i].z();
  }
  z_mid /= static_cast<double>(p.size());
  const StripEnds ends = FindStripEnds(w);
  const double width = w.cell.Ly(), length = ends.length;
  const double grip = GripLength(ends, s.grip_length, "bending.grip_length");
  CutAlongX(net, 0.5 * length);
  const Grips g = MakeGrips(w, ends, grip);
  if (g.left.empty() || g.right.empty()) throw RunError("bending test: a grip holds no particles");
  const BendingGeometry geo{0.5 * (g.x_left + g.x_right), z_mid, g.span};
  std::vector<std::uint8_t> held(p.size(), 0);
  for (const auto* side : {&g.left, &g.right})
    for (const std::int32_t i : *side) {
      held[i] = 1;
      p.Fix(i);
    }
  const std::vector<Vec3> ref = p.x;
  const std::vector<Quat> q0 = p.q;

  // Local damping adds up to local_damping x the force while a particle decelerates, which
  // stiffens the fastest mode by up to 1 + local_damping: the step shrinks to keep its margin
  // (at 0.5 of the critical step, 0.7 diverged on a strip of parallel fibres, 0.5 held).
  w.settings.safety = s.time_step_safety / std::sqrt(1.0 + s.local_damping);
  w.settings.dt = 0.0;
  AddBondDamping(w, s.bond_damping_ratio);
  w.physics.local_damping = s.local_damping;
  w.damping_reference = AffineField{};  // damped against rest
  Simulation sim(w);
  BendingResult res;
  if (std::string warn = sim.Prepare(); !warn.empty()) res.warnings.push_back(warn);
  const double dt = res.dt = w.settings.dt;
  const double tau = s.relax_time_steps * dt;
  // The drag is the only applied load: without it the step skips the applied-load passes.
  w.physics.applied_loads = tau > 0.0;
  if (tau > 0.0) {
    w.applied_force.assign(p.size(), Vec3::Zero());
    w.applied_torque.assign(p.size(), Vec3::Zero());
  }

  // Moment per width about the pivots and axial force per width from the last step's forces.
  auto measure = [&](double kappa, double& moment, double& axial) {
    double m_side[2] = {0.0, 0.0}, f_side[2] = {0.0, 0.0};
    for (int k = 0; k < 2; ++k) {
      const std::vector<std::int32_t>& side = k == 0 ? g.left : g.right;
      const Vec3 pivot = geo.Pivot(k == 0 ? -1 : 1, kappa);
      for (const std::int32_t i : side) {
        Vec3 r = p.x[i] - pivot;
        r.y() = 0.0;
        m_side[k] += (r.cross(p.force[i]) + p.torque[i]).y();
        f_side[k] += p.force[i].x();
      }
    }
    moment = 0.5 * (m_side[1] - m_side[0]) / width;
    axial = 0.5 * (f_side[0] - f_side[1]) / width;
  };
  // One step at fixed grips, with the drag toward rest where there is one.
  auto step = [&] {
    if (tau > 0.0)
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (held[i]) continue;
        w.applied_force[i] = -(p.mass[i] / tau) * p.v[i];
        w.applied_torque[i] = -(p.inertia[i] / tau) * p.omega[i];
      }
    sim.Step();
  };
  // Relaxes at fixed grips (local damping, or a drag toward rest); returns the steps run and
  // the last relative change of the moment.
  auto relax = [&](double kappa, double& moment, double& axial, double& residual) {
    int steps = 0;
    double previous = 0.0;
    residual = 1.0;
    int settled_checks = 0;
    while (steps < s.relax_steps) {
      for (int k = 0; k < s.relax_check && steps < s.relax_steps; ++k, ++steps) step();
      measure(kappa, moment, axial);
      const double scale = std::max(std::abs(moment), std::abs(previous));
      residual = scale > 0.0 ? std::abs(moment - previous) / scale : 0.0;
      previous = moment;
      settled_checks = residual <= s.relax_tolerance ? settled_checks + 1 : 0;
      if (settled_checks >= 2) break;
    }
    return steps;
  };

  res.curve.name = s.axis == LoadAxis::kMD ? "bending_md" : "bending_cd";
  res.curve.columns = {"curvature_per_m", "moment_N_m_per_m", "axial_force_N_per_m",
                       "relax_steps", "residual"};
  double m0 = 0.0, a0 = 0.0, residual = 0.0, worst = 0.0;
  int used = relax(0.0, m0, a0, residual);
  res.steps += used;
  res.curve.Add({0.0, 0.0, 0.0, static_cast<double>(used), residual});
  double kappa_old = 0.0;
  // Moves the free particles by the increment of the bending field from kappa_from to
  // kappa_to, the grips exactly.
  auto impose = [&](double kappa_from, double kappa_to) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (held[i]) continue;
      p.x[i] += geo.Bent(ref[i], kappa_to) - geo.Bent(ref[i], kappa_from);
      const double turn = geo.Angle(ref[i], kappa_to) - geo.Angle(ref[i], kappa_from);
      p.q[i] = (Quat(Eigen::AngleAxisd(turn, Vec3::UnitY())) * p.q[i]).normalized();
    }
    const double half = 0.5 * kappa_to * g.span;
    for (int k = 0; k < 2; ++k) {
      const int side = k == 0 ? -1 : 1;
      const Vec3 pivot0 = geo.Pivot(side, 0.0), pivot = geo.Pivot(side, kappa_to);
      const Quat turn(Eigen::AngleAxisd(side < 0 ? half : -half, Vec3::UnitY()));
      for (const std::int32_t i : (k == 0 ? g.left : g.right)) {
        Vec3 r = ref[i] - pivot0;
        r.y() = 0.0;
        const Vec3 y = p.x[i];
        p.x[i] = pivot + turn * r;
        p.x[i].y() = y.y();
        p.q[i] = (turn * q0[i]).normalized();
      }
    }
  };
  for (int level = 1; level <= s.levels; ++level) {
    const double kappa = s.max_curvature * level / s.levels;
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.v[i].setZero();
      p.omega[i].setZero();
    }
    // A level's increment imposed at once sets the strip ringing, and the overshoot can break
    // bonds the quasi-static path does not: the ramp imposes it in small parts a few steps
    // apart.
    const int parts = std::max(1, s.ramp_steps / kRampStepsPerPart);
    const int steps_per_part = parts > 1 ? kRampStepsPerPart : 0;  // one part: no ramp
    for (int part = 1; part <= parts; ++part) {
      const double from = kappa_old + (kappa - kappa_old) * (part - 1) / parts,
                   to = kappa_old + (kappa - kappa_old) * part / parts;
      impose(from, to);
      for (int k = 0; k < steps_per_part; ++k) step();
    }
    res.steps += static_cast<std::int64_t>(parts) * steps_per_part;
    double moment = 0.0, axial = 0.0;
    used = relax(kappa, moment, axial, residual);
    res.steps += used;
    worst = std::max(worst, residual);
    res.curve.Add({kappa, moment - m0, axial - a0, static_cast<double>(used), residual});
    kappa_old = kappa;
    progress.Say(fmt::format("bending: curvature {:.4g} 1/m, moment {:.4g} N m/m after {} steps",
                             kappa, moment - m0, used));
  }

  const std::vector<double> kappa = res.curve.Values("curvature_per_m"),
                            moment = res.curve.Values("moment_N_m_per_m");
  // A strip that breaks or buckles at a level sheds moment there. The stiffness is read below
  // that level, as the tensile and ZD moduli are read below their peaks; a fall within the
  // relaxation tolerance is the moment's settling noise, not a failure.
  std::size_t last_rising = 0;
  while (last_rising + 1 < moment.size() &&
         moment[last_rising + 1] >= moment[last_rising] * (1.0 - s.relax_tolerance))
    ++last_rising;
  double D = FitSlope(kappa, moment, kappa, s.fit_from * s.max_curvature, s.max_curvature, 0,
                      last_rising + 1);
  if (last_rising + 1 < moment.size()) {
    const bool from_zero = std::isnan(D);  // fewer than two levels in the window
    if (from_zero) D = FitSlope(kappa, moment, kappa, 0.0, s.max_curvature, 0, last_rising + 1);
    res.warnings.push_back(fmt::format(
        "bending: the moment fell from {:.4g} to {:.4g} N m/m between curvatures {:.4g} and {:.4g} "
        "1/m (bonds broke or the strip buckled); the stiffness is fitted below {:.4g} 1/m{}",
        moment[last_rising], moment[last_rising + 1], kappa[last_rising], kappa[last_rising + 1],
        kappa[last_rising + 1], from_zero ? ", from zero curvature" : ""));
  }
  res.settled = worst <= s.relax_tolerance;
  if (!res.settled)
    res.warnings.push_back(fmt::format(
        "bending: a curvature level did not settle: the moment still changed by {:.3g} (> {:.3g}) "
        "over the last {} steps; raise relax_steps", worst, s.relax_tolerance, s.relax_check));
  res.metrics = {
      {"bending_stiffness", D * 1e6, "mN mm"},
      {"bending_relaxation_residual", worst, "-"},
  };
  return res;
}

}  // namespace fibrenet::pipeline
