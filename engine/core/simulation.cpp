#include "engine/core/simulation.h"

#include <cmath>

#include <fmt/format.h>

#include "engine/core/diagnose.h"
#include "engine/core/error.h"
#include "engine/core/float_mode.h"
#include "engine/core/quaternion.h"
#include "engine/core/rotation_lanes.h"
#include "engine/core/time_step.h"

namespace fibrenet {

namespace {

// 0 when every component of v is finite, NaN otherwise: a component times zero is 0 (or -0),
// or NaN for an infinity or a NaN, and a NaN carries through the sum. One test per particle
// instead of a branch per component.
template <class Vector>
double NonFiniteMark(const Vector& v) {
  return (v * 0.0).sum();
}

// Eigen's sign of one component: -1, 0 or 1, and NaN for NaN.
double SignOf(double a) { return std::isnan(a) ? a : static_cast<double>((a > 0.0) - (a < 0.0)); }

// Local non-viscous damping of a load `load` (force or torque) on a particle moving with
// `motion`: -alpha |load| sign(motion), component by component, as Eigen's
// -alpha * load.cwiseAbs().cwiseProduct(motion.cwiseSign()) forms it. Built from scalars:
// Eigen's expression stored its components one at a time and read them back in pairs, which
// stalls on the store forwarding.
Vec3 LocalDampingOf(double alpha, const Vec3& load, const Vec3& motion) {
  return Vec3(-alpha * (std::abs(load.x()) * SignOf(motion.x())),
              -alpha * (std::abs(load.y()) * SignOf(motion.y())),
              -alpha * (std::abs(load.z()) * SignOf(motion.z())));
}

// Turns particles [first, end) (at most kLanes) by their spins over the step; bit l of
// `advanced` says whether particle first + l moves this step.
void RotateGroup(Quat* __restrict q, const Vec3* __restrict omega, std::int64_t first,
                 std::int64_t end, unsigned advanced, double dt) {
  unsigned left = advanced;  // particles still to turn by the scalar line
  if (end - first == kLanes && advanced != 0) {
    QuatLanes q_lanes;
    Vec3Lanes omega_lanes;
    const Quat* g = q + first;
    GatherQuatLanes({&g[0], &g[1], &g[2], &g[3]}, q_lanes);
    omega_lanes.x = Across([&](int l) { return omega[first + l].x(); });
    omega_lanes.y = Across([&](int l) { return omega[first + l].y(); });
    omega_lanes.z = Across([&](int l) { return omega[first + l].z(); });
    const RotationLanesResult r = RotateLanes(q_lanes, omega_lanes, dt);
    for (int l = 0; l < kLanes; ++l) {
      if (!(advanced & r.holds & (1u << l))) continue;
      q[first + l] = Quat(r.q.w[l], r.q.x[l], r.q.y[l], r.q.z[l]);
      left &= ~(1u << l);
    }
  }
  for (std::int64_t i = first; i < end; ++i)
    if (left & (1u << (i - first)))
      q[i] = (QuatFromRotationVector(omega[i] * dt) * q[i]).normalized();
}

}  // namespace

std::string Simulation::Prepare() {
  FlushDenormalsToZero();
  Particles& p = w_.particles;
  const SerialWhenSmall serial(p.size());
  if (w_.settings.skin <= 0.0 && p.size() > 0) {
    double r_min = p.radius[0];
    for (double r : p.radius) r_min = std::min(r_min, r);
    w_.settings.skin = w_.settings.skin_radii * r_min;
  }
  if (w_.physics.applied_loads) {
    w_.applied_force.resize(p.size(), Vec3::Zero());
    w_.applied_torque.resize(p.size(), Vec3::Zero());
  }
  const std::string warning = ChooseTimeStep(w_);
  buffers_.Prepare(p, w_.bonds);
  if (w_.physics.contacts) w_.neighbours.Build(p, w_.cell, w_.bonds, w_.settings.skin);
  return warning;
}

void Simulation::ComputeForces() {
  ComputeForces(w_.physics.contacts && w_.neighbours.NeedsRebuild(w_.particles, w_.cell));
}

void Simulation::ComputeForces(bool rebuild_neighbours) {
  Particles& p = w_.particles;
  if (rebuild_neighbours) w_.neighbours.Build(p, w_.cell, w_.bonds, w_.settings.skin);
  buffers_.Prepare(p, w_.bonds);
  losses_ = StepLosses{};
  StartForces(w_);
  if (w_.bonds.size() > 0) AccumulateBondForces(w_, buffers_, losses_);
  if (w_.physics.contacts) AccumulateContactForces(w_, buffers_, losses_);
  buffers_.Reduce();
  if (!w_.walls.empty()) AccumulateWallForces(w_, losses_);
  if (!w_.blades.empty()) AccumulateBladeForces(w_, losses_);
}

void Simulation::Step() {
  Particles& p = w_.particles;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  const SerialWhenSmall serial(p.size());
  // A non-finite state (set from outside, e.g. by a prescribed motion) is named before its
  // forces spread it to the neighbours. The smallest bad index is reported. The same pass
  // checks the neighbour list's skin, which would otherwise read the positions once more.
  const NeighbourList& nl = w_.neighbours;
  const bool contacts = w_.physics.contacts;
  const bool check_skin = contacts && !nl.Stale(p.size());
  std::int64_t bad = n;
  int moved = 0;
#pragma omp parallel for schedule(static) reduction(min : bad) reduction(| : moved)
  for (std::int64_t i = 0; i < n; ++i) {
    const double mark = NonFiniteMark(p.x[i]) + NonFiniteMark(p.v[i]) +
                        NonFiniteMark(p.q[i].coeffs()) + NonFiniteMark(p.omega[i]);
    if (mark != 0.0) bad = std::min(bad, i);
    if (check_skin) moved |= nl.MovedTooFar(i, p.x[i], w_.cell) ? 1 : 0;
  }
  if (bad < n)
    FailAt(static_cast<std::size_t>(bad), "non-finite position, velocity, orientation or spin");
  double wall_work = 0.0;
  for (const Wall& wall : w_.walls) wall_work -= wall.work;
  for (const Blade& blade : w_.blades) wall_work -= blade.work;
  ComputeForces(contacts && (!check_skin || moved != 0));
  for (const Wall& wall : w_.walls) wall_work += wall.work;
  for (const Blade& blade : w_.blades) wall_work += blade.work;

  // Integrate checks the forces and torques it reads (a non-finite one stops the run).
  Integrate();

  EnergyLedger& e = w_.energy;
  e.damping += losses_.damping;
  e.friction += losses_.friction;
  e.bond_inelastic += losses_.bond_inelastic;
  e.released += losses_.released;
  e.overlap_regained += losses_.overlap_regained;
  e.work_walls += wall_work;
  for (Wall& wall : w_.walls) wall.z += wall.vz * w_.settings.dt;
  for (Blade& blade : w_.blades) blade.tip += blade.velocity * w_.settings.dt;
  w_.min_contact_ratio = std::min(w_.min_contact_ratio, losses_.min_contact_ratio);
  // The pair of a broken bond meets as a contact from now on. With contacts it joins the
  // list at once, so that energy measured between steps sees the contact whose overlap the
  // ledger booked. It joins the rows as they are: a full build at every step of a tearing
  // sheet took a fifth of a tensile test's time.
  if (losses_.bonds_broke) {
    if (contacts) {
      std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
      const std::vector<BondBreakEvent>& events = w_.bonds.events;
      for (auto e = events.rbegin(); e != events.rend() && e->step == w_.step; ++e)
        pairs.emplace_back(w_.bonds.i[e->bond], w_.bonds.j[e->bond]);
      if (!w_.neighbours.AddBrokenBondPairs(std::move(pairs)))
        w_.neighbours.Build(p, w_.cell, w_.bonds, w_.settings.skin);
    } else {
      w_.neighbours.Invalidate();
    }
  }
  w_.time += w_.settings.dt;
  ++w_.step;
}

void Simulation::Integrate() {
  Particles& p = w_.particles;
  const Physics& ph = w_.physics;
  const double dt = w_.settings.dt;
  const std::int64_t n = static_cast<std::int64_t>(p.size());
  const double limit = w_.settings.max_step_displacement;
  const double alpha = ph.local_damping;
  const AffineField reference = w_.damping_reference;
  const bool moving_reference = !reference.IsRest();
  double work_gravity = 0.0, work_drag = 0.0, work_applied = 0.0, damping_loss = 0.0;
  std::int64_t runaway = -1, bad = n;
  // Particles go in groups of kLanes: the translation one by one, then the group's
  // orientations side by side (rotation_lanes.h), each equal to the scalar line bit for bit.
  const std::int64_t groups = (n + kLanes - 1) / kLanes;
  // Plain pointers and local copies: a store to a particle array cannot then change them, so
  // they are not loaded again for every particle.
  Vec3* __restrict x = p.x.data();
  Vec3* __restrict v = p.v.data();
  Vec3* __restrict omega = p.omega.data();
  Quat* __restrict q = p.q.data();
  Vec3* __restrict force = p.force.data();
  Vec3* __restrict torque = p.torque.data();
  const double* __restrict inv_mass = p.inv_mass.data();
  const double* __restrict inv_inertia = p.inv_inertia.data();
  const double* __restrict mass = p.mass.data();
  const double* __restrict radius = p.radius.data();
  const Cell cell = w_.cell;
  const bool gravity = ph.gravity, drag = ph.drag, applied = ph.applied_loads;
  const bool damped = alpha > 0.0;
  const Vec3 g = ph.g, air_velocity = ph.air_velocity;
  const double drag_coefficient = ph.drag_coefficient;
#pragma omp parallel for schedule(static) \
    reduction(+ : work_gravity, work_drag, work_applied, damping_loss) \
    reduction(max : runaway) reduction(min : bad)
  for (std::int64_t group = 0; group < groups; ++group) {
    const std::int64_t first = group * kLanes, end = std::min(first + kLanes, n);
    unsigned advanced = 0;  // bit l: particle first + l moves this step
    for (std::int64_t i = first; i < end; ++i) {
      // Local non-viscous damping (Physics::local_damping) of a free particle, in this pass
      // rather than one of its own: the particle's arrays are then read once per step.
      const bool damp_this = damped && inv_mass[i] != 0.0;
      Vec3 damping_force = Vec3::Zero(), damping_torque = Vec3::Zero();
      if (damp_this) {
        const Vec3 motion = moving_reference ? Vec3(v[i] - reference.At(x[i])) : v[i];
        damping_force = LocalDampingOf(alpha, force[i], motion);
        damping_torque = LocalDampingOf(alpha, torque[i], omega[i]);
        force[i] += damping_force;
        torque[i] += damping_torque;
      }
      // A non-finite force or torque stops the run after this pass; its particle stays put so
      // that the report shows where it was.
      if (!force[i].allFinite() || !torque[i].allFinite()) {
        bad = std::min(bad, i);
        continue;
      }
      v[i] += force[i] * (inv_mass[i] * dt);
      omega[i] += torque[i] * (inv_inertia[i] * dt);
      // The damping's work over the drift below, with v_n+1 and omega_n+1.
      if (damp_this)
        damping_loss -= (damping_force.dot(v[i]) + damping_torque.dot(omega[i])) * dt;
      const Vec3 dx = v[i] * dt;
      // Work of body forces over the drift x_n -> x_n+1 = x_n + v_n+1 dt.
      if (inv_mass[i] > 0.0) {
        if (gravity) work_gravity += mass[i] * g.dot(dx);
        if (drag) work_drag -= drag_coefficient * (v[i] - air_velocity).dot(dx);
        if (applied)
          work_applied += w_.applied_force[i].dot(dx) + w_.applied_torque[i].dot(omega[i]) * dt;
      }
      x[i] += dx;
      cell.Wrap(x[i]);
      if (!(dx.squaredNorm() <= limit * limit * radius[i] * radius[i]))
        runaway = std::max(runaway, i);
      advanced |= 1u << (i - first);
    }
    RotateGroup(q, omega, first, end, advanced, dt);
  }
  if (bad < n) FailAt(static_cast<std::size_t>(bad), "non-finite force or torque");
  w_.energy.work_gravity += work_gravity;
  w_.energy.work_drag += work_drag;
  w_.energy.work_applied += work_applied;
  w_.energy.damping += damping_loss;
  if (runaway >= 0)
    FailAt(static_cast<std::size_t>(runaway),
           fmt::format("kinetic-energy blow-up: moved more than {} radius in one step", limit));
}

void Simulation::FailAt(std::size_t particle, const std::string& cause) {
  throw RunError(fmt::format("unstable at step {} (t = {:.6g} s, dt = {:.4g} s): particle {} "
                             "(fibre {}): {}; largest interaction: {}",
                             w_.step, w_.time, w_.settings.dt, particle,
                             w_.particles.fibre[particle], cause,
                             DescribeLargestInteraction(w_, particle)));
}

void Simulation::Run(std::int64_t steps, std::int64_t every, const std::function<void()>& observe) {
  for (std::int64_t s = 0; s < steps; ++s) {
    Step();
    if (every > 0 && observe && (s + 1) % every == 0) observe();
  }
}

std::size_t Simulation::MemoryBytes() const { return buffers_.MemoryBytes() + w_.neighbours.MemoryBytes(); }

}  // namespace fibrenet
