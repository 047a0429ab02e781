// Fibre-fibre bonds (paper 2.3): created between touching particles of different fibres
// during consolidation. Six-mode beam bonds with transverse fibre properties:
//   k_n = E_T A / L, k_s = 12 E_T I / L^3, k_b = E_T I / L, k_t = G_T J / L,
// A = pi R_b^2, I = pi R_b^4 / 4, J = 2 I, with the bond radius R_b = bond_radius_fraction *
// min(R_i, R_j) (the bonded area) and L = R_i + R_j. Failure: Hill mixed mode (paper Eq. 3)
// with F_r0, F_s0 and G_b0 = F_r0 sqrt(k_b / k_n), G_t0 = F_s0 sqrt(k_t / k_s).
// Rest length: the current centre distance (a bond formed stress-free), or R_i + R_j, so
// that the overlap at bonding is kept as residual stress in the bond.
// Share: the properties above belong to each particle bond (kParticle: a crossing is as stiff
// and strong as the particle pairs the discretisation puts in contact), or to each crossing
// (kCrossing, bond_crossings.h), whose n particle bonds then take 1/n of every stiffness and
// threshold each, so that a crossing's stiffness and strength do not follow the spacing.
#pragma once

#include <cstddef>
#include <string>

#include "engine/pipeline/network.h"

namespace fibrenet::pipeline {

enum class RestLength { kCurrent, kContact };
enum class BondShare { kParticle, kCrossing };

struct BondingSettings {
  RestLength rest_length = RestLength::kCurrent;
  BondShare share = BondShare::kParticle;
  double transverse_modulus = 1e9;        // E_T [Pa]
  double transverse_shear_modulus = 3e8;  // G_T [Pa]
  double bond_radius_fraction = 0.5;      // R_b / min(R_i, R_j), (0, 1]
  double F_r0 = 25e-3;                    // [N]
  double F_s0 = 5e-3;                     // [N]
  // Pairs bond when their centre distance is below (R_i + R_j) (1 + gap_tolerance):
  // positive also bonds pairs a little apart, negative bonds only pairs pressed together by
  // at least -gap_tolerance (R_i + R_j) (the firmer the contact, the likelier the bond).
  double gap_tolerance = 0.0;

  std::string Validate() const;
};

// Bonds every touching pair of particles of different fibres that is not bonded yet;
// returns the number of bonds made. Bond types are shared by pairs of equal radii (and, when
// shared per crossing, equal crossing sizes). Per crossing, every intact fibre-fibre bond
// takes its share anew, since a new bond joins the crossing of older ones.
std::size_t FormFibreFibreBonds(Network& net, const BondingSettings& s);

// Makes the current shape of every fibre its rest shape (the intra-fibre bonds' reference
// state is taken anew): a wet fibre pressed into shape keeps it as it dries.
void SetFibreShape(Network& net);

}  // namespace fibrenet::pipeline
