#include "engine/pipeline/compression_rig.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/error.h"

namespace fibrenet::pipeline {

CompressionRig::CompressionRig(Network& net, const CompressionSettings& s,
                               const MaterialSwitches& switches, const std::string& test_name,
                               bool affine)
    : w(net.world),
      name(test_name),
      loading_time(s.max_strain / s.strain_rate),
      affine_(affine),
      drag_tau_(s.quasi_static.drag_time_fraction * loading_time),
      held_(net.world.particles.size(), 0),
      sim_(net.world) {
  Particles& p = w.particles;
  if (!w.physics.contacts) {
    w.physics.contacts = true;
    w.physics.friction = w.contact.mu > 0.0;
  }
  ApplyTestPhysics(net, switches);
  if (p.size() == 0) throw RunError("compression test: the network has no particles");
  double z_hi = -std::numeric_limits<double>::infinity();
  z_lo = -z_hi;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v[i].setZero();
    p.omega[i].setZero();
    z_lo = std::min(z_lo, p.x[i].z() - p.radius[i]);
    z_hi = std::max(z_hi, p.x[i].z() + p.radius[i]);
  }
  h0 = z_hi - z_lo;
  area = SheetArea(w);
  Wall floor;
  floor.z = z_lo;
  floor.side = +1;
  Wall top;
  top.z = z_hi;
  top.side = -1;
  w.walls = {floor, top};
  mass_scale = ChooseMassScale(w, s.quasi_static, loading_time);
  ApplyQuasiStaticDamping(w, s.quasi_static);
  speed = s.strain_rate * h0;
  curve.name = name;
  curve.columns = {"strain",        "pressure_Pa",     "gap_m",        "kinetic_J",
                   "platen_work_J", "drag_load_ratio", "bonds_broken", "branch"};
}

void CompressionRig::Prepare() {
  if (std::string warn = sim_.Prepare(); !warn.empty()) warnings.push_back(warn);
  dt = w.settings.dt;
}

void CompressionRig::Step() {
  if (drag_tau_ > 0.0) ApplyAffineDrag(w, held_, Field(), drag_tau_);
  w.damping_reference = Field();
  sim_.Step();
}

void CompressionRig::Sample(bool unloading) {
  // Share of the platen load carried by the drag: |drag virial| / (platen force x gap).
  const double lever = w.walls[1].reaction.z() * Gap();
  const double drag_share = lever > 0.0 ? std::abs(DragVirial(w, held_, 2, z_lo)) / lever : 0.0;
  curve.Add({Strain(), Pressure(), Gap(), FluctuatingKinetic(), PlatenWork(), drag_share,
             static_cast<double>(w.bonds.events.size()), unloading ? 1.0 : 0.0});
}

void CompressionRig::SetPlatenVelocity(double vz) {
  if (!affine_) {
    w.walls[1].vz = vz;
    return;
  }
  const AffineField before = Field();
  w.walls[1].vz = vz;
  const AffineField after = Field();
  Particles& p = w.particles;
  for (std::size_t i = 0; i < p.size(); ++i) p.v[i] += after.At(p.x[i]) - before.At(p.x[i]);
}

AffineField CompressionRig::Field() const {
  return AffineField{2, z_lo, Gap(), affine_ ? w.walls[1].vz : 0.0};
}

double CompressionRig::Gap() const { return w.walls[1].z - z_lo; }
double CompressionRig::Strain() const { return (h0 - Gap()) / h0; }
double CompressionRig::Pressure() const {
  return 0.5 * (w.walls[1].reaction.z() - w.walls[0].reaction.z()) / area;
}
double CompressionRig::PlatenWork() const { return w.walls[0].work + w.walls[1].work; }
double CompressionRig::PlatenSpeed() const { return -w.walls[1].vz; }
double CompressionRig::FluctuatingKinetic() const {
  return FluctuatingKineticEnergy(w, held_, Field());
}

double CompressionRig::ForceImbalance(double floor_force) const {
  const double top = w.walls[1].reaction.z(), floor = w.walls[0].reaction.z();
  const double scale = std::max({std::abs(top), std::abs(floor), floor_force});
  return std::abs(top + floor) / scale;
}

}  // namespace fibrenet::pipeline
