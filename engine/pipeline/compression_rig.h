// The ZD compression's rig (compression_test.h): the sheet between a floor and a top platen,
// its mass scale and damping, what is measured and the curve. Shared by the two loadings:
// continuous (compression_test.cpp) and stepped (compression_stepped.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "engine/core/simulation.h"
#include "engine/pipeline/compression_test.h"

namespace fibrenet::pipeline {

class CompressionRig {
 public:
  // Works on net's world (the caller's copy of the network): velocities zeroed, the test
  // physics and switches applied, platens at the lowest bottom and the highest top, masses
  // scaled and damping set. `affine`: the imposed field follows the platen (the continuous
  // loading); otherwise it is rest, and only what the platen pushes moves.
  CompressionRig(Network& net, const CompressionSettings& s, const MaterialSwitches& switches,
                 const std::string& name, bool affine);
  CompressionRig(const CompressionRig&) = delete;
  CompressionRig& operator=(const CompressionRig&) = delete;

  // Sizes the simulation and chooses its time step; call once the initial velocities are set.
  void Prepare();
  // One time step: the drag (when on) and the damping reference for the current field first.
  void Step();
  // Appends a curve row; `unloading` is the branch.
  void Sample(bool unloading);
  // A new platen velocity (negative: down). With the affine field, the affine part of the
  // particles' motion changes to match.
  void SetPlatenVelocity(double vz);

  AffineField Field() const;
  double Gap() const;
  double Strain() const;    // (h0 - gap) / h0
  double Pressure() const;  // [Pa], the mean of the two platens' reactions over the area
  double PlatenWork() const;
  double PlatenSpeed() const;  // [m/s], positive going down
  double FluctuatingKinetic() const;
  // |top + floor reaction| / the larger of the two and of `floor_force` [N]: 0 when the
  // sheet carries the load at rest.
  double ForceImbalance(double floor_force) const;

  World& w;
  const std::string name;
  double z_lo = 0.0, h0 = 0.0, area = 0.0;
  double loading_time = 0.0;  // max_strain / strain_rate [s]
  double speed = 0.0;         // full platen speed, strain_rate x h0 [m/s]
  double mass_scale = 1.0, dt = 0.0;
  Curve curve;
  std::vector<std::string> warnings;

 private:
  const bool affine_;
  const double drag_tau_;
  const std::vector<std::uint8_t> held_;
  Simulation sim_;
};

// The stepped loading (CompressionSettings::Loading::kStepped): returns the steps run.
std::int64_t LoadStepped(CompressionRig& rig, const CompressionSettings& s,
                         const Progress& progress);

}  // namespace fibrenet::pipeline
