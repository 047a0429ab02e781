// Particle state in structure-of-arrays form: one contiguous array per property, so
// hot loops stream through memory. Units: m, m/s, kg, kg m^2, rad/s, N, N m.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/core/types.h"

namespace fibrenet {

struct Particles {
  std::vector<Vec3> x;      // position [m]
  std::vector<Vec3> v;      // velocity [m/s]
  std::vector<Quat> q;      // orientation, body -> world, unit quaternion
  std::vector<Vec3> omega;  // angular velocity, world frame [rad/s]
  std::vector<Vec3> force;  // accumulated force of the current step [N]
  std::vector<Vec3> torque; // accumulated torque of the current step [N m]
  std::vector<double> radius;       // contact radius [m]
  std::vector<double> mass;         // [kg]
  std::vector<double> inv_mass;     // 1/mass; 0 fixes the particle in translation
  std::vector<double> inertia;      // scalar moment of inertia of the sphere [kg m^2]
  std::vector<double> inv_inertia;  // 1/inertia; 0 fixes the particle in rotation
  std::vector<std::int32_t> fibre;  // owning fibre id, -1 for a free particle

  std::size_t size() const { return x.size(); }

  // Appends a sphere at rest. `inertia_scale` multiplies the solid-sphere inertia
  // 2/5 m R^2: the sphere is a numerical device, so its inertia may be scaled.
  std::size_t Add(const Vec3& position, double radius_m, double mass_kg, std::int32_t fibre_id,
                  double inertia_scale = 1.0) {
    x.push_back(position);
    v.push_back(Vec3::Zero());
    q.push_back(Quat::Identity());
    omega.push_back(Vec3::Zero());
    force.push_back(Vec3::Zero());
    torque.push_back(Vec3::Zero());
    radius.push_back(radius_m);
    mass.push_back(mass_kg);
    inv_mass.push_back(1.0 / mass_kg);
    const double inertia_kgm2 = 0.4 * mass_kg * radius_m * radius_m * inertia_scale;
    inertia.push_back(inertia_kgm2);
    inv_inertia.push_back(1.0 / inertia_kgm2);
    fibre.push_back(fibre_id);
    return x.size() - 1;
  }

  // Pins a particle: it keeps its velocity and spin (a prescribed motion) whatever the forces.
  void Fix(std::size_t i) {
    inv_mass[i] = 0.0;
    inv_inertia[i] = 0.0;
  }

  void Reserve(std::size_t n) {
    x.reserve(n); v.reserve(n); q.reserve(n); omega.reserve(n);
    force.reserve(n); torque.reserve(n); radius.reserve(n); mass.reserve(n);
    inv_mass.reserve(n); inertia.reserve(n); inv_inertia.reserve(n); fibre.reserve(n);
  }
};

}  // namespace fibrenet
