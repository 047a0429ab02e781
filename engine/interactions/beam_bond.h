// Six-mode bonded interaction between two spheres: tension/compression, shear in two
// directions, bending about two axes, twist (paper Fig. 3; ESyS-Particle rotational bond).
//
// Kinematics. At creation each particle stores the bond frame B0 (x axis from i to j) in its
// own body frame: b_i = q_i^-1 B0, b_j = q_j^-1 B0. Now B_i = q_i b_i and B_j = q_j b_j; the
// relative rotation dq = B_i^-1 B_j gives the rotation vector theta = log(dq) (x: twist,
// y/z: bending) and the mid frame B_m = B_i sqrt(dq), in which the centre-to-centre vector
// u = B_m^T (x_j - x_i) gives the axial stretch u_x - L0 and the shear u_y, u_z. A rigid
// motion of the pair leaves dq, theta and u unchanged, so it produces no force at any
// rotation angle. Swapping i and j conjugates dq and flips u: the physics is unchanged.
//
// Energy (exactly the cubic Hermite beam element for small deformations):
//   U = k_n/2 (u_x - L0 - e_d)^2 + k_s/2 (u_y^2 + u_z^2) + k_b/2 |theta_yz - theta_p|^2
//       + k_t/2 theta_x^2
// e_d: extension of the Maxwell dashpot (axial viscoelasticity, relaxation time tau);
// theta_p: plastic bending rotation (elastic-perfectly plastic, yield moment M_y).
// Beam theory defaults (fibre radius R, bond length L, A = pi R^2, I = pi R^4/4, J = 2I):
//   k_n = E A / L, k_s = 12 E I / L^3, k_b = E I / L, k_t = G J / L.
// Units: stiffness N/m (n, s) and N m/rad (b, t); forces N; torques N m.
//
// Failure. kModeThresholds (fibre bonds): any mode reaching its threshold breaks the bond.
// kHill (fibre-fibre bonds, paper Eq. 3):
//   max(f_r,0)/F_r0 + |f_s|/F_s0 + |tau_b|/G_b0 + |tau_t|/G_t0 >= 1,
// so compression never breaks a bond. A broken bond gives no force from that step on and
// its strain energy is booked as released.
#pragma once

#include <limits>
#include <string>

#include <algorithm>
#include <cmath>

#include "engine/core/quaternion.h"
#include "engine/core/types.h"

namespace fibrenet {

enum class BondFailure { kNone, kModeThresholds, kHill };

struct BeamBondParams {
  double k_n = 0.0;  // axial stiffness [N/m]
  double k_s = 0.0;  // shear stiffness [N/m]
  double k_b = 0.0;  // bending stiffness [N m/rad]
  double k_t = 0.0;  // twist stiffness [N m/rad]

  BondFailure failure = BondFailure::kNone;
  // kModeThresholds: strength in each mode (infinite = never breaks in that mode).
  double max_tension = std::numeric_limits<double>::infinity();  // [N]
  double max_shear = std::numeric_limits<double>::infinity();    // [N]
  double max_bending = std::numeric_limits<double>::infinity();  // [N m]
  double max_twist = std::numeric_limits<double>::infinity();    // [N m]
  // kHill: the four thresholds of paper Eq. 3.
  double F_r0 = 25e-3;  // [N]
  double F_s0 = 5e-3;   // [N]
  double G_b0 = 0.0;    // [N m], see HillDefaults
  double G_t0 = 0.0;    // [N m]

  double maxwell_tau = 0.0;  // axial relaxation time [s]; 0 = elastic
  double yield_moment = std::numeric_limits<double>::infinity();  // [N m]

  // Optional viscous damping of the relative motion [N s/m] and [N m s/rad].
  double damping_n = 0.0;
  double damping_s = 0.0;
  double damping_rot = 0.0;

  // Stiffnesses of an elastic beam of Young's modulus E and shear modulus G [Pa],
  // circular cross-section of radius R [m], length L [m].
  static BeamBondParams FromBeam(double E, double G, double R, double L);
  // Sets G_b0 and G_t0 from equal strain energy at failure in each mode pair:
  // G_b0 = F_r0 sqrt(k_b/k_n), G_t0 = F_s0 sqrt(k_t/k_s).
  void HillDefaults();
  // Empty when valid; otherwise names the offending field and its accepted range.
  std::string Validate() const;
};

// Persistent state of one bond: its reference configuration and history.
// The frames come first: a quaternion is aligned to 32 bytes in an AVX build, and a double
// before them would be padded out to 32 bytes (a state of 128 bytes instead of 96).
struct BondState {
  Quat b_i = Quat::Identity();  // bond frame in the body frame of i
  Quat b_j = Quat::Identity();  // bond frame in the body frame of j
  double L0 = 0.0;              // rest length [m]
  double dashpot = 0.0;         // Maxwell dashpot extension e_d [m]
  double plastic_y = 0.0;       // plastic bending rotation theta_p [rad]
  double plastic_z = 0.0;
};
static_assert(sizeof(BondState) == 2 * sizeof(Quat) + 4 * sizeof(double),
              "BondState carries no padding");

// A bond's factors on its type's dashpots (damping_n and damping_s; damping_rot) for its own
// pair of particles: a type's dashpots are sized for one pair, and a bond between lighter
// particles needs less to be damped at the same fraction of critical.
struct BondDampingFactors {
  float translation = 1.0f;
  float rotation = 1.0f;
};

// What the law needs to know about the pair at this instant.
struct BondGeometry {
  Vec3 d;             // x_j - x_i (minimum image) [m]
  Quat q_i, q_j;      // orientations
  Vec3 v_rel;         // v_j - v_i [m/s]
  Vec3 omega_i, omega_j;
};

struct BondResult {
  Vec3 force_i = Vec3::Zero();  // force on i; the force on j is -force_i [N]
  Vec3 torque_i = Vec3::Zero();
  Vec3 torque_j = Vec3::Zero();
  // Mode loads for failure and diagnostics: f_r > 0 in tension.
  double f_r = 0.0, f_s = 0.0, tau_b = 0.0, tau_t = 0.0;
  // Strain energy per mode [J]: normal, shear, bending, twist.
  double energy_n = 0.0, energy_s = 0.0, energy_b = 0.0, energy_t = 0.0;
  double dissipated = 0.0;     // by dashpot and plastic flow during this step [J]
  double failure_index = 0.0;  // >= 1 means broken
  bool broken = false;

  double Energy() const { return energy_n + energy_s + energy_b + energy_t; }
};

// The failure index of the mode loads (>= 1 means broken), by the bond's failure rule.
inline double FailureIndex(const BeamBondParams& p, double f_r, double f_s, double tau_b,
                           double tau_t) {
  switch (p.failure) {
    case BondFailure::kNone:
      break;
    case BondFailure::kModeThresholds:
      return std::max({f_r / p.max_tension, f_s / p.max_shear, tau_b / p.max_bending,
                       tau_t / p.max_twist});
    case BondFailure::kHill:
      return std::max(f_r, 0.0) / p.F_r0 + f_s / p.F_s0 + tau_b / p.G_b0 + tau_t / p.G_t0;
  }
  return 0.0;
}

// Creates the reference state of a bond in the current configuration (rest length = the
// current distance unless rest_length > 0).
BondState MakeBondState(const Vec3& d, const Quat& q_i, const Quat& q_j, double rest_length = 0.0);

// Evaluates the bond and advances its history (dashpot, plastic rotation) by dt. Pass a
// copy of the state to evaluate without changing it (dt = 0 also leaves it unchanged).
// `damping` scales the type's dashpots for this bond's pair.
// Inline: it runs once per bond per step in the hot loop.
inline BondResult EvaluateBond(const BondGeometry& g, const BeamBondParams& p, BondState& s,
                               double dt, const BondDampingFactors& damping = {}) {
  BondResult r;
  const Quat B_i = g.q_i * s.b_i;
  const Quat B_j = g.q_j * s.b_j;
  const Quat dq = B_i.conjugate() * B_j;
  const Vec3 theta = RotationVector(dq);  // same components in B_i and in the mid frame
  const Mat3 R_m = (B_i * HalfRotation(dq)).toRotationMatrix();
  const Vec3 u = R_m.transpose() * g.d;

  // Axial mode with the Maxwell dashpot in series: de_d/dt = (e - e_d)/tau, integrated
  // exactly for an extension e held over the step.
  const double e = u.x() - s.L0;
  if (p.maxwell_tau > 0.0 && dt > 0.0) {
    const double relaxed = e - (e - s.dashpot) * std::exp(-dt / p.maxwell_tau);
    const double f_before = p.k_n * (e - s.dashpot);
    const double f_after = p.k_n * (e - relaxed);
    r.dissipated += 0.5 * (f_before + f_after) * (relaxed - s.dashpot);
    s.dashpot = relaxed;
  }
  const double e_el = e - s.dashpot;
  const double f_n = p.k_n * e_el;
  const Vec3 f_local(f_n, p.k_s * u.y(), p.k_s * u.z());

  // Bending: elastic-perfectly plastic about the yield moment.
  double m_y = p.k_b * (theta.y() - s.plastic_y);
  double m_z = p.k_b * (theta.z() - s.plastic_z);
  if (p.yield_moment < std::numeric_limits<double>::infinity()) {  // elastic bonds skip it
    const double m_b = std::hypot(m_y, m_z);
    if (m_b > p.yield_moment) {
      const double excess = (m_b - p.yield_moment) / p.k_b;  // plastic rotation increment [rad]
      if (dt > 0.0) {
        s.plastic_y += excess * m_y / m_b;
        s.plastic_z += excess * m_z / m_b;
        r.dissipated += p.yield_moment * excess;
      }
      m_y *= p.yield_moment / m_b;
      m_z *= p.yield_moment / m_b;
    }
  }
  const Vec3 m_local(p.k_t * theta.x(), m_y, m_z);

  r.f_r = f_n;
  // sqrt(a^2 + b^2), not hypot: these magnitudes cannot overflow, and hypot costs a call.
  r.f_s = p.k_s * std::sqrt(u.y() * u.y() + u.z() * u.z());
  r.tau_b = std::sqrt(m_y * m_y + m_z * m_z);
  r.tau_t = std::abs(m_local.x());
  r.energy_n = 0.5 * f_n * e_el;
  r.energy_s = 0.5 * p.k_s * (u.y() * u.y() + u.z() * u.z());
  r.energy_b = 0.5 * (m_y * m_y + m_z * m_z) / (p.k_b > 0.0 ? p.k_b : 1.0);
  r.energy_t = 0.5 * p.k_t * theta.x() * theta.x();

  r.failure_index = FailureIndex(p, r.f_r, r.f_s, r.tau_b, r.tau_t);
  if (r.failure_index >= 1.0) {
    r.broken = true;
    return r;  // no force from the step it breaks on: released energy is r.Energy()
  }

  // Torques are the exact derivatives of the energy with respect to each particle's
  // rotation, so that the bond is conservative at any deformation. The moment acts through
  // the inverse Jacobian of the rotation vector: m_world = A J_l^-T(theta) m_local, with A the
  // frame B_i. The moment d x f of the force pair is shared through the mid frame, which
  // turns by P = J_l(theta/2) J_l^-1(theta) / 2 of a relative rotation: (I - A P^T A^T) to i,
  // A P^T A^T to j (half each for small theta). Both keep angular momentum exact.
  // The products are taken with vectors, right to left, never forming P or A P^T A^T.
  const Mat3 A = B_i.toRotationMatrix();
  Vec3 f_i = R_m * f_local;
  const double theta2 = theta.squaredNorm();
  const double c_inverse = InverseLeftJacobianCoefficientAt(theta2);
  const Vec3 m_world = A * InverseLeftJacobianTransposeTimes(theta, c_inverse, m_local);
  Vec3 couple = Vec3::Zero();

  if (p.damping_n > 0.0 || p.damping_s > 0.0 || p.damping_rot > 0.0) {
    // Relative velocity seen in the co-rotating bond frame: zero for rigid motion.
    const Vec3 omega_m = 0.5 * (g.omega_i + g.omega_j);
    const Vec3 v_r = g.v_rel - omega_m.cross(g.d);
    const Vec3 axis = R_m.col(0);
    const double v_n = v_r.dot(axis);
    const double c_n = p.damping_n * double(damping.translation);
    const double c_s = p.damping_s * double(damping.translation);
    const double c_rot = p.damping_rot * double(damping.rotation);
    const Vec3 f_damp = c_n * v_n * axis + c_s * (v_r - v_n * axis);
    const Vec3 w_rel = g.omega_j - g.omega_i;
    f_i += f_damp;
    couple += c_rot * w_rel;
    r.dissipated += (f_damp.dot(v_r) + c_rot * w_rel.squaredNorm()) * dt;
  }

  // The force pair f_i, -f_i is offset by d: its moment is shared so that angular momentum
  // is conserved exactly (see above; damping forces share it the same way).
  const Vec3 moment = g.d.cross(f_i);
  const Vec3 moment_j =
      A * (0.5 * InverseTimesHalfLeftJacobianTransposeTimes(
                     theta, theta2, c_inverse, LeftJacobianCoefficientsAt(0.25 * theta2),
                     A.transpose() * moment));
  r.force_i = f_i;
  r.torque_i = m_world + couple + (moment - moment_j);
  r.torque_j = -m_world - couple + moment_j;
  return r;
}

}  // namespace fibrenet
