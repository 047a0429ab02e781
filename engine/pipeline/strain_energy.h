// Strain energy stored in each fibre, split by deformation mode (paper 3.5, Fig. 8), and how
// unevenly it is spread over the fibres ("undemocratic" networks).
//
// Assignment. An intra-fibre bond belongs to its fibre; a fibre-fibre bond gives half of its
// energy to each of the two fibres it joins. Bond energies come from EvaluateBond on a copy
// of the bond state (as engine/core/energy.cpp does), so this bookkeeping and the force loop
// share one law. Contact energies are not fibre energies and are left out. Units: J.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/pipeline/network.h"

namespace fibrenet::pipeline {

struct ModeEnergy {
  double normal = 0.0, shear = 0.0, bending = 0.0, twist = 0.0;  // [J]
  double Total() const { return normal + shear + bending + twist; }
  ModeEnergy& operator+=(const ModeEnergy& o);
  ModeEnergy operator-(const ModeEnergy& o) const;
};

// Energy of every fibre (index = fibre id) by mode, from the intact bonds.
std::vector<ModeEnergy> FibreEnergies(const Network& net);
// Sum over fibres.
ModeEnergy TotalEnergy(const std::vector<ModeEnergy>& fibres);

// Gini coefficient of non-negative values: 0 when all are equal, (n - 1)/n when one holds
// everything. G = 2 sum_i i x_(i) / (n sum x) - (n + 1)/n with x_(i) sorted ascending,
// i = 1..n. Negative values are counted as 0; an all-zero or empty set gives 0.
double Gini(std::vector<double> values);
// Share of the total held by the largest ceil(fraction * n) values (negatives as 0).
double TopShare(std::vector<double> values, double fraction);

// What the tensile test reports about the energy distribution at one instant.
struct EnergyDistribution {
  ModeEnergy total;               // summed over fibres [J]
  double per_fibre_mean = 0.0;    // [J]
  double top10_share = 0.0;       // share of the 10% most loaded fibres
  double gini = 0.0;
  std::vector<double> per_fibre;  // total per fibre [J], negatives kept
};

// Distribution of the energy increments `now - before` (fibre by fibre, mode by mode): the
// energy the test itself stored, without the residual energy the sheet carried in.
EnergyDistribution DistributionOfIncrement(const std::vector<ModeEnergy>& before,
                                           const std::vector<ModeEnergy>& now);

}  // namespace fibrenet::pipeline
