// Normal compression of fibre cross-sections: generalised van Wyk / Matsuo law, paper Eq. 4,
//   F(d) = C [ ((R_i + R_j)/d)^g - 1 ]  for d < R_i + R_j,   F = 0 otherwise,
// with C = 0.00026 N and g = 3.45 fitted to single-fibre transverse collapse (paper 2.4).
// F stiffens without bound as d -> 0. Below d_lin = linear_below * (R_i + R_j) the law
// continues on its tangent line (the documented stiff branch), which bounds the contact
// stiffness and so the critical time step; the smallest d reached is reported. An optional
// hard core adds a linear spring of stiffness hard_stiffness below d_lin: the collapsed
// fibre wall (transverse modulus times a particle's length along the fibre), which keeps
// cross-sections from passing through each other under impact loads (creping).
// Units: C in N, distances in m, energy in J.
#pragma once

#include <cmath>
#include <string>

namespace fibrenet {

struct VanWykParams {
  double C = 0.00026;         // [N]
  double g = 3.45;            // exponent [-]
  double linear_below = 0.5;  // d_lin / (R_i + R_j), in (0, 1)
  double hard_stiffness = 0.0;  // hard core below d_lin [N/m], >= 0; 0 = off

  std::string Validate() const;
};

struct NormalResult {
  double force = 0.0;      // repulsive, >= 0 [N]
  double stiffness = 0.0;  // -dF/dd [N/m]
  double energy = 0.0;     // integral of F from d to R_i + R_j [J]
  // The law's stiffness without the hard core [N/m]: the friction spring's scale. The core
  // stands for the collapsed wall in compression; a tangential spring that stiffened 25-fold
  // as a contact entered it would store (or lose) energy no force did work for.
  double law_stiffness = 0.0;
};

inline NormalResult EvaluateVanWyk(double d, double sum_radii, const VanWykParams& p) {
  NormalResult r;
  if (d >= sum_radii) return r;
  const double d_lin = p.linear_below * sum_radii;
  const double d_eval = d > d_lin ? d : d_lin;
  const double ratio_g = std::pow(sum_radii / d_eval, p.g);
  r.force = p.C * (ratio_g - 1.0);
  r.stiffness = p.C * p.g * ratio_g / d_eval;
  // U(d) = C [ (R (R/d)^(g-1) - R) / (g - 1) - (R - d) ], with R (R/d)^(g-1) = ratio_g d.
  r.energy = p.C * ((ratio_g * d_eval - sum_radii) / (p.g - 1.0) - (sum_radii - d_eval));
  r.law_stiffness = r.stiffness;
  if (d < d_lin) {
    const double x = d_lin - d;
    const double k = r.stiffness + p.hard_stiffness;
    r.energy += r.force * x + 0.5 * k * x * x;
    r.force += k * x;
    r.stiffness = k;
  }
  return r;
}

}  // namespace fibrenet
