// The Yankee coating's hold on one sheet particle: an adhesive beam bond (six modes) from the
// particle to a fixed anchor, its mirror image below the surface (creping.h).
//
// Stiffness of a glue layer of thickness t_c over a patch of radius r_b: k_n = E_c A / t_c,
// k_s = G_c A / t_c, k_b = E_c I / t_c, k_t = G_c J / t_c (A = pi r_b^2, I = pi r_b^4 / 4,
// J = 2 I). Failure by the Hill criterion with the coating's peel and shear strengths.
//
// The coating is a polymer film (polyvinyl alcohol, polyamide-epichlorohydrin resins) whose
// loss factor near its softening point is of order one: a purely elastic glue lets a struck
// strip ring on it undamped. damping_ratio adds dashpots to the glue's modes, each at that
// fraction of critical for the glued particle on its glue (the anchor does not move; each
// bond's factors fit it to its own particle, GlueDampingFactors): a particle pulled off its
// glue site and let go rings down with the logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2)
// per period.
#pragma once

#include <string>

#include "engine/interactions/beam_bond.h"

namespace fibrenet::pipeline {

struct AdhesionSettings {
  // Calibrated on the generic tissue against the paper's bond loss (docs/creping.md).
  double F_r0 = 7e-3;                 // peel (tensile) strength of one adhesive bond [N]
  double F_s0 = 7e-3;                 // shear strength [N]
  double strength_cv = 0.0;           // scatter of both strengths (lognormal), [0, 2]
  double modulus = 1e8;               // coating's Young's modulus E_c [Pa]
  double shear_modulus = 3e7;         // coating's shear modulus [Pa]
  double coating_thickness = 5e-6;    // t_c [m]
  double bond_radius_fraction = 0.5;  // glued patch radius / particle radius, (0, 1]
  double reach = 0.5;                 // glue particles whose bottom is this many radii up, [0, 1]
  double damping_ratio = 0.0;         // the glue's dashpots, fraction of critical, [0, 1]

  std::string Validate() const;
};

// The glue bond of a particle of radius R, mass m and moment of inertia I, its strengths
// scaled by `strength_factor` (a class of the coating's scatter).
BeamBondParams GlueBond(const AdhesionSettings& a, double R, double m, double I,
                        double strength_factor);

// Particles of one radius share a glue type, its dashpots sized for one particle of mass
// m_type and inertia I_type; fibres differ in coarseness and segment length, so the particles
// do not share a mass. These factors on the type's dashpots (Bonds::damping_factors) put a
// glued particle of mass m and inertia I at the type's fraction of critical.
BondDampingFactors GlueDampingFactors(double m, double I, double m_type, double I_type);

}  // namespace fibrenet::pipeline
