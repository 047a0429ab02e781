// Energy and momentum of a World, for the balance checks and diagnostics. Strain energies
// call the same evaluators as the force loops (with copies of their history).
#pragma once

#include "engine/core/world.h"

namespace fibrenet {

struct StrainEnergy {
  double normal = 0.0, shear = 0.0, bending = 0.0, twist = 0.0;  // intact bonds [J]
  double contacts = 0.0;  // non-bonded contacts and walls [J]
  double Total() const { return normal + shear + bending + twist + contacts; }
};

struct EnergyReport {
  double kinetic_translation = 0.0;
  double kinetic_rotation = 0.0;
  StrainEnergy strain;
  double Kinetic() const { return kinetic_translation + kinetic_rotation; }
  // kinetic + strain + dissipated + released - work - regained overlap: constant in an
  // accounted run.
  double Accounted(const EnergyLedger& ledger) const {
    return Kinetic() + strain.Total() + ledger.Dissipated() + ledger.released - ledger.Work() -
           ledger.overlap_regained;
  }
};

EnergyReport MeasureEnergy(const World& w);
double KineticEnergy(const World& w);
// Total linear momentum [kg m/s] and angular momentum about the origin [kg m^2/s]
// (spin included). Positions are used as stored (no unwrapping across periodic faces).
Vec3 LinearMomentum(const World& w);
Vec3 AngularMomentum(const World& w);

}  // namespace fibrenet
