// Four contacts evaluated side by side, one per lane (engine/core/lanes.h): the law of
// EvaluateContact (contact.h) with the same operations in the same order, so that each
// lane's force, torques, losses and new tangential history equal EvaluateContact's on that
// pair bit for bit.
//
// Why: one contact is a chain of dependent operations (the van Wyk power, three square roots,
// four divisions, the history's rotation into the tangent plane), and the contact loop waited
// on it: 24-28% of the samples of a fibre bed or a pressing. Branches become selects: a lane
// computes both sides of each and keeps the one its scalar code would take.
//
// The lanes leave out only what the contact loop does not read: the elastic energy.
#pragma once

#include <cmath>

#include "engine/core/lanes.h"
#include "engine/interactions/contact.h"

namespace fibrenet {

// Four pairs, gathered by the caller (one lane per pair), as ContactGeometry holds them, and
// each pair's tangential history.
struct ContactLanesInput {
  Vec3Lanes d;  // x_j - x_i
  Lanes dist, r_i, r_j, m_eff;
  Vec3Lanes v_rel, omega_i, omega_j;
  Vec3Lanes xi;
};

struct ContactLanesResult {
  Vec3Lanes force_j, torque_i, torque_j;
  Lanes damping_power, slip_loss;
  Vec3Lanes xi;  // the history after the step
};

// Four pairs as EvaluateContact takes them, g[0..3], with their histories xi[0..3], put into
// the lanes' input (the contact loop gathers its own from the particles instead).
inline void SetContactLanes(const ContactGeometry* g, const Vec3* xi, ContactLanesInput& in) {
  in.d.x = Across([&](int l) { return g[l].d.x(); });
  in.d.y = Across([&](int l) { return g[l].d.y(); });
  in.d.z = Across([&](int l) { return g[l].d.z(); });
  in.dist = Across([&](int l) { return g[l].dist; });
  in.r_i = Across([&](int l) { return g[l].r_i; });
  in.r_j = Across([&](int l) { return g[l].r_j; });
  in.m_eff = Across([&](int l) { return g[l].m_eff; });
  GatherVec3Lanes({g[0].v_rel, g[1].v_rel, g[2].v_rel, g[3].v_rel}, in.v_rel);
  GatherVec3Lanes({g[0].omega_i, g[1].omega_i, g[2].omega_i, g[3].omega_i}, in.omega_i);
  GatherVec3Lanes({g[0].omega_j, g[1].omega_j, g[2].omega_j, g[3].omega_j}, in.omega_j);
  GatherVec3Lanes({xi[0], xi[1], xi[2], xi[3]}, in.xi);
}

namespace lanes {

inline Lanes Pow(Lanes base, double exponent) {
  return Across([&](int l) { return std::pow(base[l], exponent); });
}

}  // namespace lanes

// EvaluateContact of four pairs at once (any of them may be apart: its force is zero there,
// and its history moves as EvaluateContact moves it).
inline void EvaluateContactLanes(const ContactLanesInput& in, const ContactParams& p, double dt,
                                 bool friction, ContactLanesResult& r) {
  using namespace lanes;
  const Lanes zero = Splat(0.0);
  // EvaluateVanWyk, term for term (its energy aside).
  const VanWykParams& law = p.normal;
  const Lanes sum_radii = in.r_i + in.r_j;
  const Lanes d = in.dist;
  const Lanes d_lin = law.linear_below * sum_radii;
  const Lanes d_eval = d > d_lin ? d : d_lin;
  const Lanes ratio_g = Pow(sum_radii / d_eval, law.g);
  Lanes force = law.C * (ratio_g - 1.0);
  Lanes stiffness = law.C * law.g * ratio_g / d_eval;
  const Lanes law_stiffness_touching = stiffness;
  {
    const Lanes x = d_lin - d;
    const Lanes k = stiffness + law.hard_stiffness;
    const auto core = d < d_lin;
    force = core ? force + k * x : force;
    stiffness = core ? k : stiffness;
  }
  const auto apart = d >= sum_radii;
  force = apart ? zero : force;
  stiffness = apart ? zero : stiffness;
  const Lanes law_stiffness = apart ? zero : law_stiffness_touching;

  const Vec3Lanes n{in.d.x / in.dist, in.d.y / in.dist, in.d.z / in.dist};
  const Vec3Lanes a_i = Scale(in.dist * in.r_i / sum_radii, n);
  const Vec3Lanes a_j = Scale(-(in.dist * in.r_j / sum_radii), n);
  const Vec3Lanes v_c = Sub(Add(in.v_rel, Cross(in.omega_j, a_j)), Cross(in.omega_i, a_i));
  const Lanes v_n = Dot(v_c, n);

  Lanes f_n = force;
  r.damping_power = zero;
  if (p.zeta > 0.0) {
    const Lanes c = 2.0 * p.zeta * Sqrt(in.m_eff * stiffness);
    const Lanes a = -c * v_n, b = -force;
    const Lanes f_damp = a < b ? b : a;  // std::max(a, b)
    f_n += f_damp;
    r.damping_power = -f_damp * v_n;
  }
  r.force_j = Scale(f_n, n);
  r.xi = in.xi;
  r.slip_loss = zero;
  r.torque_i = r.torque_j = Vec3Lanes{zero, zero, zero};
  if (!(friction && p.mu > 0.0)) return;

  Vec3Lanes& xi = r.xi;
  const Lanes len = Sqrt(Dot(xi, xi));
  xi = Sub(xi, Scale(Dot(xi, n), n));
  const Lanes len_t = Sqrt(Dot(xi, xi));
  {
    const Lanes keep = len / len_t;
    const auto turned = len_t > 0.0;
    xi = {turned ? xi.x * keep : xi.x, turned ? xi.y * keep : xi.y,
          turned ? xi.z * keep : xi.z};
  }
  const Lanes step = Splat(dt);
  xi = Add(xi, Scale(step, Sub(v_c, Scale(v_n, n))));
  const Lanes k_tan = p.tangential_ratio * law_stiffness;
  Vec3Lanes f_t = Scale(-k_tan, xi);
  const Lanes f_t_mag = Sqrt(Dot(f_t, f_t));
  const Lanes f_max = p.mu * f_n;
  const auto slips = f_t_mag > f_max;
  {
    const Vec3Lanes f_slip = Scale(f_max / f_t_mag, f_t);
    const Vec3Lanes xi_new{-f_slip.x / k_tan, -f_slip.y / k_tan, -f_slip.z / k_tan};
    const Lanes loss = 0.5 * k_tan * (Dot(xi, xi) - Dot(xi_new, xi_new));
    r.slip_loss = slips ? loss : zero;
    xi = {slips ? xi_new.x : xi.x, slips ? xi_new.y : xi.y, slips ? xi_new.z : xi.z};
    f_t = {slips ? f_slip.x : f_t.x, slips ? f_slip.y : f_t.y, slips ? f_slip.z : f_t.z};
  }
  r.force_j = Add(r.force_j, f_t);
  r.torque_j = Cross(a_j, f_t);
  r.torque_i = Cross(a_i, Negate(f_t));
}

}  // namespace fibrenet
