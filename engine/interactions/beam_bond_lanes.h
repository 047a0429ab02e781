// Four bonds evaluated side by side, one per lane of a vector register: the law of
// EvaluateBond (beam_bond.h) with the same operations in the same order, so that each lane's
// forces and torques equal those of EvaluateBond on that bond bit for bit.
//
// Why: one bond evaluation is a chain of a few hundred dependent multiplications and adds
// (quaternion products, rotation vector, frames, Jacobians), so a single bond keeps the
// floating-point units waiting on latency. Four independent chains in the lanes fill them.
//
// The lanes take the common case only, and say per lane when the bond needs EvaluateBond:
// - its type must have no plastic yield (LanesTakeType); the lanes advance a Maxwell
//   dashpot and return its new extension, which the caller stores for the bonds it takes;
// - it must not reach failure (the caller books the break through EvaluateBond).
// Any relative rotation goes: where every lane lies in the short series (kShortSeriesAngle2,
// nearly every bond of a loaded sheet) their polynomials run as vectors, and otherwise each
// lane takes the scalar branch of its own angle (the compressed sheet's bent bonds).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "engine/core/lanes.h"
#include "engine/interactions/beam_bond.h"

namespace fibrenet {

// One bond per lane of the engine's vector of four doubles (engine/core/lanes.h).
inline constexpr int kBondLanes = kLanes;

// Row-major: m[row][col].
struct Mat3Lanes {
  Lanes m[3][3];
};

// A type the lanes evaluate: one without plastic yield.
inline bool LanesTakeType(const BeamBondParams& p) {
  return !(p.yield_moment < std::numeric_limits<double>::infinity());
}

// A bond type as the lanes read it: its parameters, and the reciprocals of its failure
// thresholds, with which the lanes estimate the failure index without a division.
struct BondLanesType {
  double k_n = 0.0, k_s = 0.0, k_b = 0.0, k_t = 0.0;
  double damping_n = 0.0, damping_s = 0.0, damping_rot = 0.0;
  double inverse_threshold[4] = {0.0, 0.0, 0.0, 0.0};  // f_r, f_s, tau_b, tau_t; 0: never
  double hill = 0.0;  // 1: the ratios add up (paper Eq. 3); 0: the largest counts
  // Maxwell dashpot: 1 when the type has one, and exp(-dt / tau) over this step (the value
  // EvaluateBond computes for each bond of the type).
  double maxwell = 0.0, maxwell_decay = 1.0;
  bool taken = false;  // LanesTakeType: else its bonds go through EvaluateBond
};

// The type as the lanes read it for a step of dt [s].
inline BondLanesType LanesTypeOf(const BeamBondParams& p, double dt) {
  BondLanesType t{p.k_n, p.k_s, p.k_b, p.k_t, p.damping_n, p.damping_s, p.damping_rot};
  t.taken = LanesTakeType(p);
  if (p.maxwell_tau > 0.0 && dt > 0.0) {
    t.maxwell = 1.0;
    t.maxwell_decay = std::exp(-dt / p.maxwell_tau);
  }
  if (p.failure == BondFailure::kHill) {
    const double thresholds[4] = {p.F_r0, p.F_s0, p.G_b0, p.G_t0};
    for (int m = 0; m < 4; ++m) t.inverse_threshold[m] = 1.0 / thresholds[m];
    t.hill = 1.0;
  } else if (p.failure == BondFailure::kModeThresholds) {
    const double thresholds[4] = {p.max_tension, p.max_shear, p.max_bending, p.max_twist};
    for (int m = 0; m < 4; ++m) t.inverse_threshold[m] = 1.0 / thresholds[m];
  }
  return t;
}

// The input of four bonds, gathered by the caller (one lane per bond).
struct BondLanesInput {
  Vec3Lanes d;  // x_j - x_i
  QuatLanes q_i, q_j, b_i, b_j;
  Vec3Lanes v_rel, omega_i, omega_j;
  Lanes L0, dashpot, plastic_y, plastic_z;
  Lanes k_n, k_s, k_b, k_t;
  Lanes damping_n, damping_s, damping_rot;
  Lanes inverse_threshold[4], hill;
  Lanes maxwell, maxwell_decay;
  bool damped = false;   // any lane with damping: else the damping terms are skipped
  bool viscous = false;  // any lane with a Maxwell dashpot: else the dashpot is skipped
};

struct BondLanesResult {
  Vec3Lanes force_i, torque_i, torque_j;
  Lanes dissipated;
  Lanes f_r, f_s, tau_b, tau_t;  // mode loads
  // The failure index from products with the reciprocal thresholds: within 1e-15 relative
  // of FailureIndex's quotients (its terms are never negative where they add up).
  Lanes failure_estimate;
  Lanes dashpot;  // the Maxwell dashpot's extension after the step [m]
};

// Whether lane l's result stands for its bond: so far from failure that FailureIndex would
// certainly say it holds. Otherwise EvaluateBond takes the bond.
inline bool LaneHolds(const BondLanesResult& r, int l) {
  return r.failure_estimate[l] < 1.0 - 1e-12;
}

// Whether bonds of type p need the damping terms, and the Maxwell dashpot.
inline bool Damps(const BondLanesType& p) {
  return p.damping_n > 0.0 || p.damping_s > 0.0 || p.damping_rot > 0.0;
}
inline bool IsViscous(const BondLanesType& p) { return p.maxwell != 0.0; }

// Puts type p into lane l of `in`. `damped` and `viscous` are or-ed in: clear them before
// the first lane.
inline void SetLaneType(BondLanesInput& in, int l, const BondLanesType& p) {
  in.k_n[l] = p.k_n, in.k_s[l] = p.k_s, in.k_b[l] = p.k_b, in.k_t[l] = p.k_t;
  in.damping_n[l] = p.damping_n, in.damping_s[l] = p.damping_s;
  in.damping_rot[l] = p.damping_rot;
  for (int m = 0; m < 4; ++m) in.inverse_threshold[m][l] = p.inverse_threshold[m];
  in.hill[l] = p.hill;
  in.maxwell[l] = p.maxwell, in.maxwell_decay[l] = p.maxwell_decay;
  in.damped = in.damped || Damps(p);
  in.viscous = in.viscous || IsViscous(p);
}

// Puts type p into every lane, for four bonds of one type (the common case): each input is
// one broadcast instead of four stores. Sets `damped` and `viscous`.
inline void SetAllLanesType(BondLanesInput& in, const BondLanesType& p) {
  const auto splat = [](double v) { return Lanes{v, v, v, v}; };
  in.k_n = splat(p.k_n), in.k_s = splat(p.k_s), in.k_b = splat(p.k_b), in.k_t = splat(p.k_t);
  in.damping_n = splat(p.damping_n), in.damping_s = splat(p.damping_s);
  in.damping_rot = splat(p.damping_rot);
  for (int m = 0; m < 4; ++m) in.inverse_threshold[m] = splat(p.inverse_threshold[m]);
  in.hill = splat(p.hill);
  in.maxwell = splat(p.maxwell), in.maxwell_decay = splat(p.maxwell_decay);
  in.damped = Damps(p);
  in.viscous = IsViscous(p);
}

// Puts one bond into lane l of `in`. `damped` and `viscous` are or-ed in: clear them before
// the first lane.
inline void SetLane(BondLanesInput& in, int l, const BondGeometry& g, const BondState& s,
                    const BondLanesType& p, const BondDampingFactors& damping = {}) {
  in.d.x[l] = g.d.x(), in.d.y[l] = g.d.y(), in.d.z[l] = g.d.z();
  for (auto [lanes, q] :
       {std::pair{&in.q_i, &g.q_i}, {&in.q_j, &g.q_j}, {&in.b_i, &s.b_i}, {&in.b_j, &s.b_j}}) {
    lanes->w[l] = q->w(), lanes->x[l] = q->x(), lanes->y[l] = q->y(), lanes->z[l] = q->z();
  }
  for (auto [lanes, v] :
       {std::pair{&in.v_rel, &g.v_rel}, {&in.omega_i, &g.omega_i}, {&in.omega_j, &g.omega_j}}) {
    lanes->x[l] = v->x(), lanes->y[l] = v->y(), lanes->z[l] = v->z();
  }
  in.L0[l] = s.L0, in.dashpot[l] = s.dashpot;
  in.plastic_y[l] = s.plastic_y, in.plastic_z[l] = s.plastic_z;
  SetLaneType(in, l, p);
  // The bond's own damping, as EvaluateBond forms it.
  in.damping_n[l] *= double(damping.translation);
  in.damping_s[l] *= double(damping.translation);
  in.damping_rot[l] *= double(damping.rotation);
}

namespace lanes {

// Eigen's 3x3 matrix times vector sums rows 0 and 1 two at a time in a vector register,
// (m0 v0 + m1 v1) + m2 v2, and the last row alone as m0 v0 + (m1 v1 + m2 v2).
inline Vec3Lanes Times(const Mat3Lanes& M, const Vec3Lanes& v) {
  return {M.m[0][0] * v.x + M.m[0][1] * v.y + M.m[0][2] * v.z,
          M.m[1][0] * v.x + M.m[1][1] * v.y + M.m[1][2] * v.z,
          M.m[2][0] * v.x + (M.m[2][1] * v.y + M.m[2][2] * v.z)};
}
// Its transpose times vector: (m0 v0 + m1 v1) + m2 v2 in every row.
inline Vec3Lanes TransposeTimes(const Mat3Lanes& M, const Vec3Lanes& v) {
  return {M.m[0][0] * v.x + M.m[1][0] * v.y + M.m[2][0] * v.z,
          M.m[0][1] * v.x + M.m[1][1] * v.y + M.m[2][1] * v.z,
          M.m[0][2] * v.x + M.m[1][2] * v.y + M.m[2][2] * v.z};
}

// Eigen's Quaternion::toRotationMatrix, term for term.
inline Mat3Lanes RotationMatrix(const QuatLanes& q) {
  const Lanes tx = 2.0 * q.x, ty = 2.0 * q.y, tz = 2.0 * q.z;
  const Lanes twx = tx * q.w, twy = ty * q.w, twz = tz * q.w;
  const Lanes txx = tx * q.x, txy = ty * q.x, txz = tz * q.x;
  const Lanes tyy = ty * q.y, tyz = tz * q.y, tzz = tz * q.z;
  Mat3Lanes R;
  R.m[0][0] = 1.0 - (tyy + tzz);
  R.m[0][1] = txy - twz;
  R.m[0][2] = txz + twy;
  R.m[1][0] = txy + twz;
  R.m[1][1] = 1.0 - (txx + tzz);
  R.m[1][2] = tyz - twx;
  R.m[2][0] = txz - twy;
  R.m[2][1] = tyz + twx;
  R.m[2][2] = 1.0 - (txx + tyy);
  return R;
}

}  // namespace lanes

// EvaluateBond of four bonds (see the conditions above), without failure: the caller reads
// the mode loads for the failure index and hands a bond that breaks to EvaluateBond.
inline void EvaluateBondLanes(const BondLanesInput& in, double dt, BondLanesResult& r) {
  using namespace lanes;
  const QuatLanes B_i = Product(in.q_i, in.b_i);
  const QuatLanes B_j = Product(in.q_j, in.b_j);
  const QuatLanes dq = Product(Conjugate(B_i), B_j);

  // RotationVector(dq) and HalfRotation(dq).
  Lanes sign;
  for (int l = 0; l < kBondLanes; ++l) sign[l] = dq.w[l] < 0.0 ? -1.0 : 1.0;
  const Vec3Lanes v{sign * dq.x, sign * dq.y, sign * dq.z};
  const Lanes w = sign * dq.w;
  const Lanes s2 = v.x * v.x + v.y * v.y + v.z * v.z;
  const Lanes inv_w = 1.0 / w;
  const Lanes t2 = s2 * inv_w * inv_w;
  const Lanes scale =
      AllLanes((s2 < 0.25 * kBondSeriesAngle2 * w * w) & (t2 < 0.25 * kShortSeriesAngle2))
          ? (2.0 * inv_w) * AtanOverTShortSeries(t2)
          : Across([&](int l) { return RotationVectorScale(s2[l], w[l]); });
  const Vec3Lanes theta = Scale(scale, v);
  // HalfRotation's branch for a half turn (1 + w near 0) never applies: w >= 0 here.
  const Lanes h_w = 1.0 + w;
  const Lanes inv_norm = 1.0 / Sqrt(2.0 * h_w);
  const QuatLanes half{h_w * inv_norm, v.x * inv_norm, v.y * inv_norm, v.z * inv_norm};

  const Mat3Lanes R_m = RotationMatrix(Product(B_i, half));
  const Vec3Lanes u = TransposeTimes(R_m, in.d);

  // Axial mode with the Maxwell dashpot in series, as EvaluateBond integrates it.
  const Lanes e = u.x - in.L0;
  r.dashpot = in.dashpot;
  r.dissipated = Splat(0.0);
  if (in.viscous) {
    const Lanes relaxed = e - (e - in.dashpot) * in.maxwell_decay;
    const Lanes f_before = in.k_n * (e - in.dashpot);
    const Lanes f_after = in.k_n * (e - relaxed);
    const Lanes loss = 0.5 * (f_before + f_after) * (relaxed - in.dashpot);
    for (int l = 0; l < kBondLanes; ++l) {
      if (in.maxwell[l] == 0.0) continue;
      r.dissipated[l] += loss[l];
      r.dashpot[l] = relaxed[l];
    }
  }
  const Lanes e_el = e - r.dashpot;
  const Lanes f_n = in.k_n * e_el;
  const Vec3Lanes f_local{f_n, in.k_s * u.y, in.k_s * u.z};
  const Lanes m_y = in.k_b * (theta.y - in.plastic_y);
  const Lanes m_z = in.k_b * (theta.z - in.plastic_z);
  const Vec3Lanes m_local{in.k_t * theta.x, m_y, m_z};

  r.f_r = f_n;
  r.f_s = in.k_s * Sqrt(u.y * u.y + u.z * u.z);
  r.tau_b = Sqrt(m_y * m_y + m_z * m_z);
  for (int l = 0; l < kBondLanes; ++l) r.tau_t[l] = std::abs(m_local.x[l]);
  const Lanes shear = r.f_s * in.inverse_threshold[1];
  const Lanes bending = r.tau_b * in.inverse_threshold[2];
  const Lanes twist = r.tau_t * in.inverse_threshold[3];
  const Lanes tension = r.f_r * in.inverse_threshold[0];
  for (int l = 0; l < kBondLanes; ++l) {
    r.failure_estimate[l] = in.hill[l] != 0.0
                                ? std::max(r.f_r[l], 0.0) * in.inverse_threshold[0][l] + shear[l] +
                                      bending[l] + twist[l]
                                : std::max({tension[l], shear[l], bending[l], twist[l]});
  }

  const Mat3Lanes A = RotationMatrix(B_i);
  Vec3Lanes f_i = Times(R_m, f_local);
  const Lanes theta2 = theta.x * theta.x + theta.y * theta.y + theta.z * theta.z;
  // Every lane in the short series (the common case), else each lane on its own branch.
  const bool short_series = AllLanes(theta2 < kShortSeriesAngle2);
  const Lanes c_inverse =
      short_series ? InverseLeftJacobianShortSeries(theta2)
                   : Across([&](int l) { return InverseLeftJacobianCoefficientAt(theta2[l]); });
  const Vec3Lanes pm = Cross(theta, m_local);
  const Vec3Lanes m_world =
      Times(A, Add(Add(m_local, Scale(Splat(0.5), pm)), Scale(c_inverse, Cross(theta, pm))));
  Vec3Lanes couple{Splat(0.0), Splat(0.0), Splat(0.0)};

  if (in.damped) {
    const Vec3Lanes omega_m = Scale(Splat(0.5), Add(in.omega_i, in.omega_j));
    const Vec3Lanes v_r = Sub(in.v_rel, Cross(omega_m, in.d));
    const Vec3Lanes axis{R_m.m[0][0], R_m.m[1][0], R_m.m[2][0]};
    const Lanes v_n = Dot(v_r, axis);
    const Vec3Lanes f_damp =
        Add(Scale(in.damping_n * v_n, axis), Scale(in.damping_s, Sub(v_r, Scale(v_n, axis))));
    const Vec3Lanes w_rel = Sub(in.omega_j, in.omega_i);
    f_i = Add(f_i, f_damp);
    couple = Add(couple, Scale(in.damping_rot, w_rel));
    r.dissipated += (Dot(f_damp, v_r) + in.damping_rot * Dot(w_rel, w_rel)) * dt;
  }

  // InverseTimesHalfLeftJacobianTransposeTimes.
  const Vec3Lanes moment = Cross(in.d, f_i);
  const Lanes a2 = 0.25 * theta2;
  Lanes c1, c2;
  if (short_series) {  // a2 = theta2 / 4 is then too
    c1 = LeftJacobianC1ShortSeries(a2), c2 = LeftJacobianC2ShortSeries(a2);
  } else {
    for (int l = 0; l < kBondLanes; ++l) {
      const LeftJacobianCoefficients c = LeftJacobianCoefficientsAt(a2[l]);
      c1[l] = c.c1, c2[l] = c.c2;
    }
  }
  const Lanes alpha = InverseTimesHalfAlpha(theta2, c_inverse, c1, c2);
  const Lanes beta = InverseTimesHalfBeta(theta2, c_inverse, c1, c2);
  const Vec3Lanes local = TransposeTimes(A, moment);
  const Vec3Lanes pv = Cross(theta, local);
  const Vec3Lanes product = Add(Add(local, Scale(alpha, pv)), Scale(beta, Cross(theta, pv)));
  const Vec3Lanes moment_j = Times(A, Scale(Splat(0.5), product));

  r.force_i = f_i;
  r.torque_i = Add(Add(m_world, couple), Sub(moment, moment_j));
  r.torque_j = Add(Sub(Negate(m_world), couple), moment_j);
}

}  // namespace fibrenet
