// What the beam validation cases (axial_torsion.cpp, cantilever.cpp, buckling_frequency.cpp)
// share: the paper's fibre, fidelity labels, a stopwatch, one-thread runs and a damped
// relaxation to static equilibrium. Header-only so that the cases stay one file each.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>

#include "engine/core/simulation.h"
#include "engine/core/stopwatch.h"
#include "engine/validation/beam_chain.h"

namespace fibrenet::validation::beam {

// Cross-section of the paper's fibre (ChainSpec defaults: R = 16 um, E = 10 GPa, G = 3 GPa,
// coarseness 2.5e-7 kg/m) with the engine's convention A = pi R^2, I = pi R^4 / 4, J = 2 I.
inline double Area(const ChainSpec& s) { return kPi * s.radius * s.radius; }
inline double SecondMoment(const ChainSpec& s) { return kPi * std::pow(s.radius, 4) / 4.0; }
inline double PolarMoment(const ChainSpec& s) { return 2.0 * SecondMoment(s); }

// A straight fibre of the paper along x from the origin: `particles` spheres over `length` m.
inline ChainSpec PaperFibre(int particles, double length = 1e-3) {
  ChainSpec s;
  s.particles = particles;
  s.length = length;
  return s;
}

// Static cases only: the spheres' rotational inertia is scaled by this factor. A static
// equilibrium does not depend on inertia, and with the inertia of solid spheres the
// rotational modes set the critical time step; 4x moves the limit to the axial springs and
// lengthens the step by ~1.4x. The dynamic cases keep the true inertia.
constexpr double kStaticInertiaScale = 4.0;

// "n=21 safety=0.5 (default)".
inline std::string FidelityLabel(int particles, double safety, bool is_default) {
  return fmt::format("n={} safety={}{}", particles, safety, is_default ? " (default)" : "");
}

// A world holding one paper fibre in an isolated cell, with applied loads switched on
// (all zero) and the given time-step safety factor. Call Simulation::Prepare after fixing
// particles and setting loads.
inline World FibreWorld(const ChainSpec& spec, double safety) {
  World w;
  w.cell = IsolatedCell(spec);
  AddChain(w, spec);
  w.physics.applied_loads = true;
  w.applied_force.assign(w.particles.size(), Vec3::Zero());
  w.applied_torque.assign(w.particles.size(), Vec3::Zero());
  w.settings.safety = safety;
  return w;
}

struct RelaxSettings {
  // Mass-proportional damping rate gamma [1/s]: each step multiplies the velocity and spin
  // of every free particle by exp(-gamma dt). gamma = 2 omega_1 damps the slowest mode
  // critically and every faster mode decays at least as fast, as e^(-omega_1 t).
  double rate = 0.0;
  // Converged when the observed quantity changes by less than tolerance times its size
  // over each of three successive intervals of 2 / gamma = 1 / omega_1. Near rest the
  // remaining error is then about 1.6 times that change. (A net-force criterion would sit
  // on the round-off of the stiff axial springs, k_n eps L, which for a bending load is
  // ~1e-7 of the load and says nothing about the deflection.)
  double tolerance = 1e-9;
  double max_time = 1.0;  // give up after this much simulated time [s]
};

struct Relaxation {
  std::int64_t steps = 0;
  double change = 0.0;  // relative change of the observed quantity over the last interval
  bool converged = false;
};

// Dynamic relaxation: steps the world with the damping of `s` until `observe` (e.g. the
// displacement of the loaded end) stops changing. The damping changes the path, never the
// equilibrium, and it acts outside the engine's ledger (the static cases check no energy).
inline Relaxation RelaxToRest(World& w, Simulation& sim, const RelaxSettings& s,
                              const std::function<Vec3()>& observe) {
  Particles& p = w.particles;
  const double dt = w.settings.dt;
  const double keep = std::exp(-s.rate * dt);
  const auto max_steps = static_cast<std::int64_t>(std::ceil(s.max_time / dt));
  const auto interval = std::max<std::int64_t>(1, std::llround(2.0 / (s.rate * dt)));
  Relaxation r;
  Vec3 last = observe();
  int calm = 0;
  while (r.steps < max_steps) {
    sim.Step();
    ++r.steps;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.inv_mass[i] > 0.0) p.v[i] *= keep;
      if (p.inv_inertia[i] > 0.0) p.omega[i] *= keep;
    }
    if (r.steps % interval != 0) continue;
    const Vec3 now = observe();
    r.change = (now - last).norm() / std::max(now.norm(), 1e-300);
    last = now;
    calm = r.change <= s.tolerance ? calm + 1 : 0;
    if (calm >= 3) {
      r.converged = true;
      break;
    }
  }
  return r;
}

}  // namespace fibrenet::validation::beam
