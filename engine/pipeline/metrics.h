// Network metrics measured after each stage. Definitions (docs/network.md gives the why):
//  basis_weight_gsm      total particle mass / cell area [g/m^2]
//  thickness_um          caliper-like thickness: the cell is divided into square columns of
//                        side thickness_grid; in each column holding particle centres the top
//                        surface is max(z + R) and the bottom surface min(z - R); thickness =
//                        P_(100-p)(top) - P_p(bottom) over the columns (p = surface_percentile,
//                        1 by default), like a plate resting on the highest asperities
//  density_kg_per_m3     basis weight / thickness (apparent sheet density)
//  porosity              1 - density / fibre_density (cell-wall density, 1500 kg/m^3)
//  bonds_per_fibre       2 x intact fibre-fibre bonds / fibres (each bond counts on both)
//  bonded_pairs_per_fibre  2 x fibre pairs joined by at least one intact bond / fibres
//  contacts_per_fibre    2 x touching, non-bonded particle pairs of different fibres / fibres
//  crossings_per_fibre   crossings of the fibres' centrelines projected on the sheet plane,
//                        2 x crossings / fibres; crossings_per_fibre_kallmes_corte is the
//                        expectation for a random 2D network of the same projected fibre
//                        lengths l_i: 2 (S^2 - sum l_i^2) / (pi A N), S = sum l_i
//  out_of_plane_angle_deg_mean  mean over fibre segments of atan(|dz| / |d_xy|)
//  orientation_anisotropy       |sum l e^(2 i phi)| / sum l over segments of projected length
//                        l and in-plane angle phi: 0 isotropic, 1 all parallel
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/pipeline/network.h"

namespace fibrenet::pipeline {

struct MetricsSettings {
  double fibre_density = 1500.0;     // cell-wall density for the porosity [kg/m^3]
  double thickness_grid = 50e-6;     // column side for the surfaces [m]
  double surface_percentile = 1.0;   // p in [0, 50) [%]
  double profile_bin = 10e-6;        // bin height of the z density profile [m]

  std::string Validate() const;
};

// Density in z: mass of the spheres' slices in each bin / (cell area x bin height).
struct DensityProfile {
  double bin = 0.0;                // [m]
  std::vector<double> z;           // bin centres [m]
  std::vector<double> density;     // [kg/m^3]
};

struct NetworkMetrics {
  double basis_weight_gsm = 0.0;
  double thickness_um = 0.0;
  double density_kg_per_m3 = 0.0;
  double porosity = 0.0;
  double bonds_per_fibre = 0.0;
  double bonded_pairs_per_fibre = 0.0;
  double contacts_per_fibre = 0.0;
  double crossings_per_fibre = 0.0;
  double crossings_per_fibre_kallmes_corte = 0.0;
  double fibre_count = 0.0;
  double particle_count = 0.0;
  double out_of_plane_angle_deg_mean = 0.0;
  double orientation_anisotropy = 0.0;
  DensityProfile profile;

  // Name and value of each scalar metric, in a fixed order (for JSON and CSV).
  std::vector<std::pair<std::string, double>> List() const;
  // Sets the scalar metric `name` (as List() names it); false when there is none.
  bool Set(const std::string& name, double value);
};

NetworkMetrics Measure(const Network& net, const MetricsSettings& s);

// Unit of a network metric of List() ("-" when dimensionless).
const char* NetworkMetricUnit(const std::string& name);

// The parts of Measure, usable on their own.
// Heights of the sheet's top and bottom surfaces as the thickness measure reads them [m].
struct SheetSurfaces {
  double top = 0.0, bottom = 0.0;
};
SheetSurfaces MeasureSurfaces(const World& w, double grid, double percentile);
double Thickness(const World& w, double grid, double percentile);
DensityProfile MeasureDensityProfile(const World& w, double bin);
// Returns crossings per fibre; kallmes_corte (optional) receives the 2D random expectation.
double CrossingsPerFibre(const Network& net, double* kallmes_corte = nullptr);

}  // namespace fibrenet::pipeline
