// Fibre model (paper 2.2): a fibre is a chain of straight segments; each segment deviates
// from the previous one by a bending angle theta and the plane of that bend turns about the
// previous segment by a twist angle psi. theta = const, psi = 0 gives a planar curl (an arc),
// random theta gives kinks, psi != 0 gives a helical twist. Every property may be a
// statistical distribution, sampled once per fibre (angles once per segment).
//
// The fibre is then represented by n spheres of radius d/2 at arc lengths (k + 1/2) L / n
// along the centreline, n = max(2, round(L / spacing)) with the spacing a fidelity setting.
// Each sphere carries coarseness * L / n, its share of the fibre length, so the fibre mass
// (and the basis weight of a sheet) is exact at any fidelity. Units: SI.
#pragma once

#include <limits>
#include <random>
#include <string>
#include <vector>

#include "engine/core/types.h"
#include "engine/pipeline/distribution.h"

namespace fibrenet::pipeline {

struct FibreSpec {
  Distribution length = Distribution::Fixed(1.92e-3);        // [m]
  Distribution diameter = Distribution::Fixed(32e-6);        // [m]
  Distribution coarseness = Distribution::Fixed(2.5e-7);     // mass per length [kg/m]
  Distribution youngs_modulus = Distribution::Fixed(10e9);   // axial E [Pa]
  Distribution shear_modulus = Distribution::Fixed(3e9);     // G [Pa]
  Distribution strength = Distribution::Fixed(0.1);          // breaking force [N]
  Distribution bend_angle = Distribution::Fixed(0.0);        // per segment [rad]
  Distribution twist_angle = Distribution::Fixed(0.0);       // per segment [rad]
  int segments = 1;                                          // straight segments per fibre
  double maxwell_tau = 0.0;  // axial relaxation time [s]; 0 = elastic
  double yield_moment = std::numeric_limits<double>::infinity();  // bending [N m]

  // Empty when valid, else the field name and the accepted range.
  std::string Validate() const;
};

// One sampled fibre.
struct FibreProperties {
  double length = 0.0, diameter = 0.0, coarseness = 0.0;  // [m], [m], [kg/m]
  double youngs_modulus = 0.0, shear_modulus = 0.0;       // [Pa]
  double strength = 0.0;                                  // [N]
  std::vector<double> bend, twist;  // per segment after the first [rad]

  double Mass() const { return coarseness * length; }
};

FibreProperties SampleFibre(const FibreSpec& spec, std::mt19937_64& rng);

// The centreline (segments + 1 points) in the fibre's own frame: it starts at the origin
// along +x and its first bend lies in the x-y plane.
std::vector<Vec3> Centreline(const FibreProperties& f);

// Particles of a fibre of the given length at the given spacing (>= 2).
int ParticlesPerFibre(double length, double spacing);

// Centres of n particles at arc lengths (k + 1/2) L / n along a polyline of length L.
std::vector<Vec3> PointsAlong(const std::vector<Vec3>& polyline, int n);

}  // namespace fibrenet::pipeline
