#include "engine/pipeline/glue.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/types.h"

namespace fibrenet::pipeline {

std::string AdhesionSettings::Validate() const {
  if (!(F_r0 > 0.0 && std::isfinite(F_r0)))
    return fmt::format("F_r0 = {} N: must be finite and > 0", F_r0);
  if (!(F_s0 > 0.0 && std::isfinite(F_s0)))
    return fmt::format("F_s0 = {} N: must be finite and > 0", F_s0);
  if (!(strength_cv >= 0.0 && strength_cv <= 2.0))
    return fmt::format("strength_cv = {}: must lie in [0, 2]", strength_cv);
  if (!(modulus > 0.0 && modulus <= 1e12))
    return fmt::format("modulus = {} Pa: must lie in (0, 1e12]", modulus);
  if (!(shear_modulus > 0.0 && shear_modulus <= 1e12))
    return fmt::format("shear_modulus = {} Pa: must lie in (0, 1e12]", shear_modulus);
  if (!(bond_radius_fraction > 0.0 && bond_radius_fraction <= 1.0))
    return fmt::format("bond_radius_fraction = {}: must lie in (0, 1]", bond_radius_fraction);
  if (!(reach >= 0.0 && reach <= 1.0)) return fmt::format("reach = {}: must lie in [0, 1]", reach);
  if (!(coating_thickness > 0.0 && coating_thickness <= 1e-3))
    return fmt::format("coating_thickness = {} m: must lie in (0, 1e-3]", coating_thickness);
  if (!(damping_ratio >= 0.0 && damping_ratio <= 1.0))
    return fmt::format("damping_ratio = {}: must lie in [0, 1]", damping_ratio);
  return {};
}

BeamBondParams GlueBond(const AdhesionSettings& a, double R, double m, double I,
                        double strength_factor) {
  const double r_b = a.bond_radius_fraction * R, area = kPi * r_b * r_b;
  const double second_moment = 0.25 * kPi * r_b * r_b * r_b * r_b, t = a.coating_thickness;
  BeamBondParams params;
  params.k_n = a.modulus * area / t;
  params.k_s = a.shear_modulus * area / t;
  params.k_b = a.modulus * second_moment / t;
  params.k_t = a.shear_modulus * 2.0 * second_moment / t;
  params.failure = BondFailure::kHill;
  params.F_r0 = a.F_r0 * strength_factor;
  params.F_s0 = a.F_s0 * strength_factor;
  params.HillDefaults();
  // Critical damping of a mass on a spring whose other end is fixed: 2 sqrt(k m).
  const double zeta = a.damping_ratio;
  params.damping_n = 2.0 * zeta * std::sqrt(params.k_n * m);
  params.damping_s = 2.0 * zeta * std::sqrt(params.k_s * m);
  params.damping_rot = 2.0 * zeta * std::sqrt(std::max(params.k_b, params.k_t) * I);
  return params;
}

BondDampingFactors GlueDampingFactors(double m, double I, double m_type, double I_type) {
  return {static_cast<float>(std::sqrt(m / m_type)), static_cast<float>(std::sqrt(I / I_type))};
}

}  // namespace fibrenet::pipeline
