#include "engine/interactions/beam_bond.h"

#include <cmath>

#include <fmt/format.h>

namespace fibrenet {

BeamBondParams BeamBondParams::FromBeam(double E, double G, double R, double L) {
  const double A = kPi * R * R;
  const double I = kPi * R * R * R * R / 4.0;
  const double J = 2.0 * I;
  BeamBondParams p;
  p.k_n = E * A / L;
  p.k_s = 12.0 * E * I / (L * L * L);
  p.k_b = E * I / L;
  p.k_t = G * J / L;
  return p;
}

void BeamBondParams::HillDefaults() {
  G_b0 = F_r0 * std::sqrt(k_b / k_n);
  G_t0 = F_s0 * std::sqrt(k_t / k_s);
}

std::string BeamBondParams::Validate() const {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(k_n)) return fmt::format("k_n = {} N/m: must be finite and > 0", k_n);
  if (!positive(k_s)) return fmt::format("k_s = {} N/m: must be finite and > 0", k_s);
  if (!positive(k_b)) return fmt::format("k_b = {} N m/rad: must be finite and > 0", k_b);
  if (!positive(k_t)) return fmt::format("k_t = {} N m/rad: must be finite and > 0", k_t);
  if (failure == BondFailure::kHill &&
      !(positive(F_r0) && positive(F_s0) && positive(G_b0) && positive(G_t0)))
    return "Hill thresholds F_r0, F_s0, G_b0, G_t0 must be finite and > 0";
  if (!(maxwell_tau >= 0.0) || std::isinf(maxwell_tau))
    return fmt::format("maxwell_tau = {} s: must be >= 0 (0 = elastic)", maxwell_tau);
  if (!(yield_moment > 0.0)) return fmt::format("yield_moment = {} N m: must be > 0", yield_moment);
  if (!(damping_n >= 0.0 && damping_s >= 0.0 && damping_rot >= 0.0))
    return "bond damping coefficients must be >= 0";
  return {};
}

BondState MakeBondState(const Vec3& d, const Quat& q_i, const Quat& q_j, double rest_length) {
  const double length = d.norm();
  const Quat frame = FrameAlongAxis(d / length);
  BondState s;
  s.L0 = rest_length > 0.0 ? rest_length : length;
  s.b_i = q_i.conjugate() * frame;
  s.b_j = q_j.conjugate() * frame;
  return s;
}

}  // namespace fibrenet
