// A fibre network: the World that the DEM engine evolves plus the fibre table that maps
// each fibre to its particles and intra-fibre bonds. Every pipeline stage (forming,
// consolidation, and later tensile/compression tests and creping) takes a Network and
// leaves it in its new state.
//
// Invariant: the particles of fibre f are world.particles[first_particle, first_particle +
// particle_count), in order along the fibre, and its intra-fibre bonds are
// world.bonds[first_bond, first_bond + bond_count), bond k joining particles k and k + 1.
// Fibre-fibre bonds come after all intra-fibre bonds. Whatever reorders particles must
// keep this table in step (CheckInvariants says whether it holds).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/world.h"
#include "engine/pipeline/fibre.h"

namespace fibrenet::pipeline {

struct FibreRecord {
  std::int32_t first_particle = 0;
  std::int32_t particle_count = 0;
  std::int32_t first_bond = 0;
  std::int32_t bond_count = 0;
  std::int32_t bond_type = 0;  // its row in world.bonds.types
  double length = 0.0;         // [m]
  double diameter = 0.0;       // [m]
  double coarseness = 0.0;     // [kg/m]
  double youngs_modulus = 0.0, shear_modulus = 0.0;  // [Pa]
  double strength = 0.0;       // [N]
};

// Options of the intra-fibre bonds that are not sampled per fibre.
struct FibreBondOptions {
  double maxwell_tau = 0.0;  // [s]
  double yield_moment = std::numeric_limits<double>::infinity();  // [N m]
  double inertia_scale = 1.0;  // multiplies the solid-sphere moment of inertia
};

struct Network {
  World world;
  std::vector<FibreRecord> fibres;

  // Appends a fibre whose particle centres are given in world coordinates (wrapped into
  // the cell here). Bonds: beam theory from the fibre's E, G, radius and spacing, failing
  // in tension at the fibre strength. Returns the fibre id.
  std::int32_t AddFibre(const FibreProperties& f, const std::vector<Vec3>& centres,
                        const FibreBondOptions& options);

  double Area() const { return world.cell.Lx() * world.cell.Ly(); }  // [m^2]
  double TotalMass() const;                                          // [kg]
  std::size_t IntactFibreFibreBonds() const;
  // Empty when the fibre table matches the world; otherwise what is wrong.
  std::string CheckInvariants() const;
};

// Multiplies every particle's mass and moment of inertia by `factor` (mass scaling); keeps
// the originals so RestoreMasses puts back exactly the same values.
struct SavedMasses {
  std::vector<double> mass, inertia;
};
SavedMasses ScaleMasses(World& w, double factor);
void RestoreMasses(World& w, const SavedMasses& saved);

// Moves the whole world rigidly, x -> R x + shift (R a rotation): positions, velocities,
// spins, orientations, and the tangential histories of contacts and walls turn with it;
// bonds keep their state (it lives in the particles' body frames). The cell is left alone.
void TransformRigidly(World& w, const Mat3& R, const Vec3& shift);

// Removes every particle i with keep[i] == 0 (dust shed by creping), with its bonds: a bond
// stays when both its ends stay. A fibre that loses particles is split into one fibre per run
// of consecutive kept particles (a run may hold broken bonds), each with its share of the
// fibre's length. Order is kept, so the fibre table's invariant holds afterwards; bond
// failure events of kept bonds and the tangential histories of kept contacts carry over.
// Returns the number of particles removed.
std::size_t KeepParticles(Network& net, const std::vector<std::uint8_t>& keep);

// Multiplies the four stiffnesses (k_n, k_s, k_b, k_t) of every fibre's intra-fibre bond
// type by `factor` (soft falling or wet fibres). Returns the bond types as they were; the
// caller puts them back (fibre-fibre bond types added meanwhile come after them).
std::vector<BeamBondParams> ScaleFibreStiffness(Network& net, double factor);

}  // namespace fibrenet::pipeline
