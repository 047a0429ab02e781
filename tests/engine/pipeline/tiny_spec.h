// The pipeline settings of campaigns/scenes/tiny.toml, built in C++ so that engine tests do
// not depend on the scene reader: 0.4 mm fibres on a 0.6 mm cell, formed and pressed in
// seconds with heavy acceleration.
#pragma once

#include "engine/pipeline/pipeline.h"

namespace fibrenet::pipeline::testing {

inline PipelineSpec TinySpec(std::uint64_t seed = 7) {
  PipelineSpec s;
  s.seed = seed;
  s.sheet.Lx = s.sheet.Ly = 0.6e-3;
  s.sheet.basis_weight = 0.020;
  s.sheet.inertia_scale = 4.0;
  s.sheet.fibres.length = Distribution::Fixed(0.4e-3);
  s.sheet.fibres.coarseness = Distribution::Uniform(16e-8, 35e-8);
  s.sheet.fibres.segments = 4;
  s.sheet.fibres.bend_angle = Distribution::Normal(0.0, 5.0 * kPi / 180.0);
  s.sheet.fibres.bend_angle.min = -kPi;
  s.sheet.fibres.bend_angle.max = kPi;
  s.sheet.fibres.twist_angle = Distribution::Uniform(-kPi, kPi);
  s.sheet.contact.restitution = 0.5;
  s.sheet.contact.Derive();
  s.forming.mass_scale = 100;
  s.forming.gravity_scale = 100;
  s.forming.stiffness_scale = 0.01;
  PressingSettings p;
  p.target_thickness = 150e-6;
  p.speed = 0.2;
  p.mass_scale = 1000;
  p.kinetic_work_tolerance = 0.06;
  p.bonding = BondingSettings{};
  s.pressing = p;
  return s;
}

}  // namespace fibrenet::pipeline::testing
