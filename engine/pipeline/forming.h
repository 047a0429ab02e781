// Forming (paper 3.1): fibres are placed at random positions and orientations in a box
// above the forming wire at a set consistency and fall under gravity with linear drag onto
// the wire (a floor wall at z = 0), periodic in x and y. Forming ends when the web has
// settled (kinetic energy criterion), not after a fixed time.
//
// Consistency c is the fibre mass fraction of the suspension: the box holds the sheet's
// fibre mass m in a volume m / (c rho_s) over the cell area (rho_s the suspension density),
// so its height is basis_weight / (c rho_s): 2 mm for 20 g/m^2 at 1%.
//
// Drag. Each particle feels F = -c_d (v - v_air) with c_d chosen so that a particle of mean
// mass falls through still air at the terminal velocity v_t: c_d = m_p g / v_t. The air
// moves down through the wire at air_velocity (air-laid forming with suction; 0 = still
// air): a fibre at rest in the web then feels the drag c_d v_air, air_velocity / v_t times
// its weight, the flow's pressure gradient that compacts the web.
//
// Acceleration (each a named setting, 1 = real physics; docs/network.md has the study that
// checks their effect on the final network):
//  - mass_scale M >= 1: particle masses and inertias x M. Drag follows the mass (c_d from
//    v_t), so the free-fall path is unchanged; the critical time step grows by sqrt(M).
//  - gravity_scale G >= 1: g x G with the drag matched so that v_t (and the air velocity)
//    grow by sqrt(G): the relaxation time v_t / g shrinks by sqrt(G) and the path length
//    v_t^2 / g is kept, so the same trajectories are run sqrt(G) times faster.
//  - stiffness_scale S <= 1: fibre bond stiffnesses x S while falling (restored after), for a
//    larger time step where bonds limit it.
//  - drop_gap: height of the box's bottom above the wire (a shorter drop, less free fall).
// The web's own weight grows by M G: keep it far below the pressing pressures.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "engine/interactions/contact.h"
#include "engine/pipeline/fibre.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"

namespace fibrenet::pipeline {

// Settings of the sheet that every stage shares.
struct SheetSpec {
  double Lx = 2.5e-3, Ly = 2.5e-3;   // periodic cell [m]
  double basis_weight = 0.020;       // target [kg/m^2]
  FibreSpec fibres;
  double particle_spacing = 1.0;     // fidelity: particle spacing in fibre diameters
  double inertia_scale = 1.0;        // multiplies the solid-sphere inertia of particles
  double time_step_safety = 0.5;     // dt = safety * dt_crit
  double neighbour_skin = 0.5;       // neighbour-list skin in smallest radii (speed only)
  ContactParams contact;             // non-bonded contacts and walls

  std::string Validate() const;
};

// Sets a stage's time-step safety and neighbour skin from the sheet's fidelity settings;
// the time step and the skin are then chosen afresh when the stage's simulation prepares.
inline void UseSheetStepSettings(World& w, const SheetSpec& sheet) {
  w.settings.safety = sheet.time_step_safety;
  w.settings.dt = 0.0;
  w.settings.skin_radii = sheet.neighbour_skin;
  w.settings.skin = 0.0;
}

enum class Orientation { kIsotropic, kPlanar };

struct FormingSettings {
  double consistency = 0.01;          // fibre mass fraction in the suspension, (0, 1)
  double suspension_density = 1000;   // [kg/m^3]
  double drop_gap = 0.0;              // wire to box bottom [m]
  Orientation orientation = Orientation::kIsotropic;
  double terminal_velocity = 0.05;    // real settling velocity of a fibre [m/s]
  double air_velocity = 0.0;          // downward air flow through the wire [m/s]
  double mass_scale = 1.0;            // M >= 1
  double gravity_scale = 1.0;         // G >= 1
  double stiffness_scale = 1.0;       // S in (0, 1]
  // Settled when the kinetic energy falls below this fraction of (1/2) m_total v_t^2 (all
  // fibres at the terminal velocity), after at least three drag relaxation times.
  double settle_kinetic_ratio = 1e-3;
  std::int64_t max_steps = 5'000'000;
  int placement_attempts = 10000;     // tries per fibre to find a place without overlap

  std::string Validate() const;
};

struct PlacementStats {
  double box_height = 0.0;           // [m]
  int overlapping_fibres = 0;        // fibres placed overlapping others after all tries
};

struct FormingResult {
  std::int64_t steps = 0;
  double simulated_time = 0.0;  // [s] (in the accelerated time)
  double dt = 0.0;              // [s]
  bool settled = false;
  double kinetic_ratio = 0.0;   // final value of the settling criterion
  std::string dt_warning;
};

// Samples fibres until their mass is nearest the sheet's basis weight times the cell area
// and places them in the forming box (no dynamics). The cell, fibres and contact law of the
// returned network are set; no physics is switched on yet. The fibres lie in memory in the
// Morton order of their centres in the plane, not in the order they were drawn.
Network PlaceFibres(const SheetSpec& sheet, const FormingSettings& forming,
                    std::mt19937_64& rng, PlacementStats* stats = nullptr);

// Lets the placed fibres fall onto the wire until settled. Masses and stiffnesses are the
// real ones again on return; the wire (wall 0) stays in the world.
FormingResult Settle(Network& net, const SheetSpec& sheet, const FormingSettings& forming,
                     const Progress& progress);

}  // namespace fibrenet::pipeline
