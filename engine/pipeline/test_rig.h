// The rig shared by the virtual tests (tensile, ZD compression, sheet bending): material
// switches for the test variants, quasi-static control, grips, and stress measurement.
//
// Quasi-static control. A test loads at a set rate; the kinetic energy of the sheet must stay
// a small fraction (kinetic_work_tolerance, default 1%) of the work the grips or platens put
// in. Two devices make that affordable:
//  - Mass scaling: masses and moments of inertia x M (mass_scale, or automatic from a step
//    budget). The loading rate and so the time of Maxwell relaxation stay real; only
//    inertia grows, which the measured kinetic/work ratio guards. The critical time step
//    grows by sqrt(M).
//  - Bond damping: each bond gets dashpots in its six modes at a fraction
//    bond_damping_ratio of critical damping of its own pair of particles (reduced mass and
//    moment of inertia), so a light fibre is damped at the same fraction as a heavy one.
//    They act on relative motion only (zero for rigid motion) and take out ringing; their
//    force at the loading rate is negligible against the elastic one (measured as part of
//    the guard) and their dissipation is booked with the bond losses.
//  - Local non-viscous damping (Cundall 1987; Physics::local_damping), the default: each
//    force component on a particle is reduced by a fraction of its magnitude while it drives
//    the motion beyond the imposed affine field (World::damping_reference). It vanishes in
//    equilibrium whatever the velocity, so unlike a drag it carries no load in a non-affine
//    but steady deformation (a platen pushing the top of a loose mat). Measured against rest
//    instead, it would brake the imposed stretch itself.
//  - Background drag relative to the imposed affine velocity field (ApplyAffineDrag), with a
//    relaxation time drag_time_fraction of the loading time; off by default. It damps the
//    floppy modes of sparse networks, which carry too little force for local damping to
//    touch, but it resists the non-affine motion of a real sheet.
//  The guards bound both the kinetic energy (beyond the affine motion) against the external
//  work and the share of the load the drag carries (DragVirial) against the measured load.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/affine_field.h"
#include "engine/pipeline/network.h"

namespace fibrenet::pipeline {

// Which irreversible mechanisms a test variant keeps (paper 3.6 switches them one by one).
struct MaterialSwitches {
  bool bond_failure = true;   // false: no bond of any kind breaks
  bool viscoelastic = true;   // false: Maxwell relaxation off on every bond
  double maxwell_tau = 0.0;   // > 0: axial relaxation time of fibre bonds [s] for the test
  std::optional<bool> friction;  // absent: as the network has it; else on/off for the test

  std::string Validate() const;
};

struct QuasiStaticSettings {
  // Mass scale M >= 1; 0 chooses M so that loading to the test's largest strain at the set
  // rate takes loading_steps time steps (M = 1 when the real inertia already allows it).
  // What makes a test quasi-static is the number of steps per loading, whatever M is: the
  // sheet's slowest period and the time step both grow by sqrt(M).
  double mass_scale = 0.0;
  double loading_steps = 20000.0;
  double bond_damping_ratio = 0.1;       // fraction of critical damping, [0, 1]
  // Background drag relaxation time as a fraction of the loading time (ApplyAffineDrag);
  // 0 = off (the default: local damping instead, see the header comment).
  double drag_time_fraction = 0.0;
  // Local non-viscous damping coefficient (Physics::local_damping), [0, 1); 0 = off. The
  // default 0.7 is the customary value (Cundall 1987).
  double local_damping = 0.7;
  double kinetic_work_tolerance = 0.01;  // guard on kinetic energy / external work, (0, 1]
  double time_step_safety = 0.5;         // dt = safety * dt_crit, (0, 1]

  std::string Validate() const;
};

// The checks every loading test shares: curve samples in [10, 100000], a step cap >= 1, the
// switches and the quasi-static control. Empty when valid.
std::string ValidateLoading(int samples, std::int64_t max_steps, const MaterialSwitches& s,
                            const QuasiStaticSettings& q);

// Turns the network's world into a test world: gravity, drag, applied loads and walls off,
// the switches applied to every bond type. Contacts stay as the network had them.
void ApplyTestPhysics(Network& net, const MaterialSwitches& s);

// Adds bond dashpots (see the header comment) for the current masses: the types' damping
// for the mean pair, and each bond's factors (Bonds::damping_factors) for its own.
void AddBondDamping(World& w, double ratio);
// The damping of quasi-static control: bond dashpots and local damping as `s` sets them.
void ApplyQuasiStaticDamping(World& w, const QuasiStaticSettings& s);

// Scales masses for the test: returns M (the given one, or the automatic choice that makes
// the loading, which lasts `loading_time` seconds, take loading_steps steps). Call after the
// physics is final.
double ChooseMassScale(World& w, const QuasiStaticSettings& s, double loading_time);

// Rotates the network a quarter turn about z, (x, y) -> (y, -x) shifted back into the cell,
// so that a CD test runs along x. Orientations, velocities and contact histories turn too.
void QuarterTurn(Network& net);

// Makes the cell open along x, as a strip cut from the sheet: bonds that crossed the periodic
// face x = lo.x are removed (marked broken, not counted as failures). The cell is widened by
// `margin` on both sides for the neighbour grid. Returns the number of bonds cut.
std::size_t CutAlongX(Network& net, double margin);

// Where a strip along x ends, for its grips. A sheet cut from a periodic cell has clean ends:
// its outermost centres. A sheet that comes to the test already open along x (a creped strip)
// trails loose fibres and fragments from its cut ends; its ends are its outermost centres in
// the bins (of two particle diameters) from the first to the last where its mass per unit
// length reaches half its median, so that the clamps close on the whole sheet and the loose
// ends stick out beyond them, as they would from a tester's clamps. Call it before CutAlongX.
struct StripEnds {
  double lo = 0.0, hi = 0.0;  // [m]
  double length = 0.0;        // the strip's length [m]: the cell's for a periodic sheet
};
StripEnds FindStripEnds(const World& w);
// The area of the sheet a test loads [m^2]: the cell's for a periodic sheet; for an open
// strip, its footprint between the ends above (their distance plus a mean particle diameter)
// times the cell's width, so that neither the cell's margins nor loose ends dilute a pressure.
double SheetArea(const World& w);
// The length of each grip: grip_length, or a tenth of the strip when it is 0. The grips must
// leave at least 20% of the strip free, else InputError naming the setting `key`.
double GripLength(const StripEnds& ends, double grip_length, const std::string& key);
// Particles held by the two grips of a strip along x: the centres within grip_length of
// either end, and those beyond the ends. A grip's clamp line is its innermost held centre:
// the free span runs from one clamp line to the other, so a fibre held at both ends has
// exactly the span free.
struct Grips {
  std::vector<std::int32_t> left, right;
  double span = 0.0;                   // initial distance between the clamp lines [m]
  double x_left = 0.0, x_right = 0.0;  // clamp lines [m]
};
Grips MakeGrips(const World& w, const StripEnds& ends, double grip_length);
// Fixes the grip particles (Particles::Fix: they keep their velocity): left at -V/2, right at
// +V/2 along x, no spin, and gives the free particles the matching affine velocity so that
// loading starts without a shock. `sign` = +1 pulls the grips apart, -1 brings them together
// (the affine part of the free particles' velocity is reversed, the rest is kept).
// `strain` is the current grip strain (the span has grown by 1 + strain).
void DriveGrips(World& w, const Grips& g, double V, int sign, bool first, double strain);
// Force the grips pull with [N]: mean of the left grip's pull and the right grip's pull.
double GripTension(const World& w, const Grips& g);
// Power the grips feed into the sheet in the last step [W].
double GripPower(const World& w, const Grips& g);
// Kinetic energy of the particles not held, with the affine velocity subtracted [J]: what
// the quasi-static guard must bound is the motion beyond the imposed deformation.
double FluctuatingKineticEnergy(const World& w, const std::vector<std::uint8_t>& held,
                                const AffineField& field);

// Background drag on the motion beyond the affine field (dynamic relaxation): applied force
// -m_i / tau (v_i - u(x_i)) and torque -I_i / tau omega_i on every particle not held. It
// vanishes in the quasi-static limit and damps the slow, floppy modes of sparse networks that
// bond dashpots barely touch. Sets w.physics.applied_loads; call before every step.
void ApplyAffineDrag(World& w, const std::vector<std::uint8_t>& held, const AffineField& field,
                     double tau);

// Virial of the background drag along `axis` about `origin`: sum over the particles not
// held of (x_axis - origin) * applied_force_axis [N m]. Against the load times its lever (grip
// force x span, platen force x gap) it is the share of the load the drag carries, which the
// guard bounds: a drag that only damps non-affine fluctuations has no such share.
double DragVirial(const World& w, const std::vector<std::uint8_t>& held, int axis, double origin);

// Interaction virial sum over pairs of d (x) f_i (bonds and contacts, d = x_j - x_i, f_i the
// force on i; tension positive) [N m]. Divided by an area it is the mean in-plane stress
// resultant [N/m]. Uses copies of all histories.
Mat3 InteractionVirial(const World& w);

// Least-squares slope of y on x over the samples k in [begin, end) whose key[k] lies in
// [key_lo, key_hi]; NaN when fewer than two samples qualify.
double FitSlope(const std::vector<double>& x, const std::vector<double>& y,
                const std::vector<double>& key, double key_lo, double key_hi, std::size_t begin,
                std::size_t end);
// Trapezoidal integral of y dx over the samples [begin, end).
double Trapezoid(const std::vector<double>& x, const std::vector<double>& y, std::size_t begin,
                 std::size_t end);

}  // namespace fibrenet::pipeline
