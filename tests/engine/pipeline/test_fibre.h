// The straight test fibre of the pipeline tests: the generic tissue's cross-section (32 um),
// coarseness 25 mg/100 m, E = 10 GPa, G = 3 GPa, strength 100 mN.
#pragma once

#include "engine/pipeline/fibre.h"

namespace fibrenet::pipeline {

inline FibreProperties TestFibre(double length) {
  FibreProperties f;
  f.length = length;
  f.diameter = 32e-6;
  f.coarseness = 2.5e-7;
  f.youngs_modulus = 10e9;
  f.shear_modulus = 3e9;
  f.strength = 0.1;
  return f;
}

}  // namespace fibrenet::pipeline
