#include "engine/validation/beam_chain.h"

namespace fibrenet::validation {

std::size_t AddChain(World& w, const ChainSpec& spec) {
  const double spacing = spec.length / (spec.particles - 1);
  const double segment_mass = spec.mass_per_length * spacing;
  const std::size_t first = w.particles.size();
  for (int k = 0; k < spec.particles; ++k) {
    const bool end = (k == 0 || k == spec.particles - 1);
    const double m = (end && spec.half_mass_ends) ? 0.5 * segment_mass : segment_mass;
    w.particles.Add(spec.origin + Vec3(k * spacing, 0, 0), spec.radius, m, 0, spec.inertia_scale);
  }
  const std::int32_t type =
      w.bonds.AddType(BeamBondParams::FromBeam(spec.E, spec.G, spec.radius, spacing));
  for (int k = 0; k + 1 < spec.particles; ++k) {
    const auto a = static_cast<std::int32_t>(first + k), b = a + 1;
    w.bonds.Add(a, b, type, BondKind::kFibre,
                MakeBondState(w.particles.x[b] - w.particles.x[a], w.particles.q[a],
                              w.particles.q[b]));
  }
  return first;
}

Cell IsolatedCell(const ChainSpec& spec) {
  Cell c;
  c.lo = spec.origin - Vec3::Constant(2.0 * spec.length);
  c.hi = spec.origin + Vec3::Constant(3.0 * spec.length);
  c.periodic_x = c.periodic_y = false;
  return c;
}

}  // namespace fibrenet::validation
