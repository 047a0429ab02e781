// Non-bonded contact between two spheres, composed of parts (as LAMMPS GRANULAR does):
//   normal law   van Wyk / Matsuo (van_wyk_normal.h),
//   damping      viscous, c = 2 zeta sqrt(m_eff k(d)), never pulling the pair together
//                (the total normal force stays >= 0). zeta is calibrated from the
//                restitution coefficient e for that capped law in its gentle-impact limit,
//                where van Wyk is a linear spring: the contact ends when the force reaches
//                zero, not at zero overlap, so the linear-spring zeta = -ln e / sqrt(pi^2 +
//                ln^2 e) would rebound too fast (e = 0.5 gave 0.55). Harder impacts reach
//                the stiffening part of the law and rebound slightly slower (validation
//                case `restitution`, docs/validation-particles.md),
//   friction     Cundall-Strack: a tangential spring k_tan = tangential_ratio * k(d) on the
//                accumulated tangential displacement xi (per-contact history, rotated into
//                the current tangent plane every step), capped by Coulomb mu F_n (slip);
//                k(d) is the normal law's stiffness without its hard core.
// Units: N, m, s. Forces act at the contact point; torques follow from it.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/types.h"
#include "engine/interactions/van_wyk_normal.h"

namespace fibrenet {

struct ContactParams {
  VanWykParams normal;
  double restitution = 1.0;        // (0, 1]; 1 = no normal damping
  double mu = 0.3;                 // Coulomb friction coefficient; 0 = frictionless
  double tangential_ratio = 1.0;   // k_tan / k_normal(d)

  // Derived once from restitution; not user-set.
  double zeta = 0.0;
  // Sets zeta so that a gentle head-on impact rebounds with `restitution` (see above).
  void Derive();
  std::string Validate() const;
  // The law of a particle against a rigid surface (mirror image): the surface carries its own
  // hard core (walls.h, blade.h), so the particle-particle hard core is left out.
  ContactParams ForSurface() const {
    ContactParams s = *this;
    s.normal.hard_stiffness = 0.0;
    return s;
  }
};

// Restitution coefficient of a linear spring-dashpot contact whose total force may not
// become attractive, as a function of the damping ratio zeta >= 0 (closed form: the contact
// ends when k y + c y' = 0). Monotonically decreasing from 1 at zeta = 0.
double CappedRestitution(double zeta);

struct ContactGeometry {
  Vec3 d;            // x_j - x_i (minimum image) [m]
  double dist;       // |d|
  double r_i, r_j;   // radii
  double m_eff;      // m_i m_j / (m_i + m_j) [kg]
  Vec3 v_rel;        // v_j - v_i
  Vec3 omega_i, omega_j;
};

struct ContactResult {
  Vec3 force_j = Vec3::Zero();  // force on j; on i it is -force_j
  Vec3 torque_i = Vec3::Zero();
  Vec3 torque_j = Vec3::Zero();
  double normal_force = 0.0;    // [N], >= 0
  double energy = 0.0;          // elastic (normal + tangential spring) [J]
  double damping_power = 0.0;   // energy rate lost to damping [W]
  double slip_loss = 0.0;       // energy lost to Coulomb slip this step [J]
};

// Evaluates a contact (geometry.dist < r_i + r_j) and advances its tangential history xi
// by dt. Always inlined: it runs once per touching pair per step, and as a call its result
// went through memory (3% of the fibre-bed step).
[[gnu::always_inline]] inline ContactResult EvaluateContact(const ContactGeometry& g,
                                                            const ContactParams& p, Vec3& xi,
                                                            double dt, bool friction) {
  ContactResult r;
  const double sum_radii = g.r_i + g.r_j;
  const NormalResult nr = EvaluateVanWyk(g.dist, sum_radii, p.normal);
  const Vec3 n = g.d / g.dist;  // from i to j
  // Lever arms from each centre to the contact point, split in proportion to the radii.
  const Vec3 a_i = (g.dist * g.r_i / sum_radii) * n;
  const Vec3 a_j = -(g.dist * g.r_j / sum_radii) * n;
  const Vec3 v_c = g.v_rel + g.omega_j.cross(a_j) - g.omega_i.cross(a_i);
  const double v_n = v_c.dot(n);  // > 0 separating

  double f_n = nr.force;
  if (p.zeta > 0.0) {
    const double c = 2.0 * p.zeta * std::sqrt(g.m_eff * nr.stiffness);
    const double f_damp = std::max(-c * v_n, -nr.force);  // never pulls the pair together
    f_n += f_damp;
    r.damping_power = -f_damp * v_n;
  }
  r.normal_force = f_n;
  r.energy = nr.energy;
  r.force_j = f_n * n;

  if (friction && p.mu > 0.0) {
    // Keep the history in the current tangent plane, preserving its length.
    const double len = xi.norm();
    xi -= xi.dot(n) * n;
    const double len_t = xi.norm();
    if (len_t > 0.0) xi *= len / len_t;
    xi += (v_c - v_n * n) * dt;
    const double k_tan = p.tangential_ratio * nr.law_stiffness;
    Vec3 f_t = -k_tan * xi;
    const double f_t_mag = f_t.norm();
    const double f_max = p.mu * f_n;
    if (f_t_mag > f_max) {
      const Vec3 f_slip = f_t * (f_max / f_t_mag);
      const Vec3 xi_new = -f_slip / k_tan;
      // The slip releases the spring energy above the cap. f_max |dxi| would book less where
      // the cap falls by more than the step's slip (a pair leaving the hard core), and the
      // energy would leave the ledger unaccounted.
      r.slip_loss = 0.5 * k_tan * (xi.squaredNorm() - xi_new.squaredNorm());
      xi = xi_new;
      f_t = f_slip;
    }
    r.energy += 0.5 * k_tan * xi.squaredNorm();
    r.force_j += f_t;
    r.torque_j = a_j.cross(f_t);
    r.torque_i = a_i.cross(-f_t);
  }
  return r;
}

}  // namespace fibrenet
