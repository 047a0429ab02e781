#include "engine/core/time_step.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet {

TimeStepInfo CriticalTimeStep(const World& w) {
  const Particles& p = w.particles;
  const std::size_t n = p.size();
  // Upper bounds on omega^2 per particle, translation and rotation.
  std::vector<double> trans(n, 0.0), rot(n, 0.0);
  std::vector<std::int32_t> worst_bond(n, -1);
  // The most heavily damped dashpot mode of any bond.
  double zeta_max = 0.0;
  std::size_t zeta_bond = 0;
  const char* zeta_mode = "";
  // `inv`: 1 / the pair's reduced mass (or inertia), the ends' inverses summed; a pinned end
  // adds 0.
  auto zeta_of = [](double c, double k, double inv) {
    return c > 0.0 && k > 0.0 && inv > 0.0 ? 0.5 * c / std::sqrt(k / inv) : 0.0;
  };
  auto inv_sqrt = [](double a, double b) { return (a > 0.0 && b > 0.0) ? 1.0 / std::sqrt(a * b) : 0.0; };
  for (std::size_t b = 0; b < w.bonds.size(); ++b) {
    if (w.bonds.broken[b]) continue;
    const BeamBondParams& k = w.bonds.types[w.bonds.type[b]];
    const double L = w.bonds.state[b].L0;
    const double k_lin = std::max(k.k_n, k.k_s);
    const double k_rot = std::max(k.k_b, k.k_t);
    const double k_sl = 0.5 * k.k_s * L;        // shear-rotation coupling
    const double k_sll = 0.25 * k.k_s * L * L;  // shear contribution to rotation
    if (k.damping_n > 0.0 || k.damping_s > 0.0 || k.damping_rot > 0.0) {
      const BondDampingFactors f = w.bonds.DampingFactors(b);
      const std::int32_t i = w.bonds.i[b], j = w.bonds.j[b];
      const double c_n = k.damping_n * double(f.translation), c_s = k.damping_s * double(f.translation);
      const double c_rot = k.damping_rot * double(f.rotation);
      const double inv_m = p.inv_mass[i] + p.inv_mass[j];
      const double inv_I = p.inv_inertia[i] + p.inv_inertia[j];
      const std::pair<double, const char*> modes[4] = {{zeta_of(c_n, k.k_n, inv_m), "stretch"},
                                                       {zeta_of(c_s, k.k_s, inv_m), "shear"},
                                                       {zeta_of(c_rot, k.k_t, inv_I), "twist"},
                                                       {zeta_of(c_rot, k.k_b, inv_I), "bending"}};
      for (const auto& [zeta, mode] : modes)
        if (zeta > zeta_max) {
          zeta_max = zeta;
          zeta_bond = b;
          zeta_mode = mode;
        }
    }
    const std::int32_t ends[2] = {w.bonds.i[b], w.bonds.j[b]};
    for (int e = 0; e < 2; ++e) {
      const std::int32_t a = ends[e], o = ends[1 - e];
      const double m_a = p.mass[a], m_o = p.mass[o], I_a = p.inertia[a], I_o = p.inertia[o];
      trans[a] += k_lin * (1.0 / m_a + inv_sqrt(m_a, m_o)) + k_sl * (inv_sqrt(m_a, I_a) + inv_sqrt(m_a, I_o));
      rot[a] += (k_rot + k_sll) / I_a + std::abs(k_sll - k_rot) * inv_sqrt(I_a, I_o) +
                k_sl * (inv_sqrt(I_a, m_a) + inv_sqrt(I_a, m_o));
      worst_bond[a] = static_cast<std::int32_t>(b);
    }
  }
  // Contacts (and walls) at the stiffness cap of the stiff branch.
  double k_contact = 0.0;
  if (w.physics.contacts || !w.walls.empty()) {
    const VanWykParams& vw = w.contact.normal;
    double r_min = p.size() ? *std::min_element(p.radius.begin(), p.radius.end()) : 1.0;
    const double d_lin = vw.linear_below * 2.0 * r_min;
    const double k_law = vw.C * vw.g * std::pow(1.0 / vw.linear_below, vw.g) / d_lin;
    // The friction spring follows the law's stiffness, not the hard core's (contact.h).
    const double friction_share = w.physics.friction ? w.contact.tangential_ratio : 0.0;
    k_contact = k_law * (1.0 + friction_share) + vw.hard_stiffness;
  }
  // Hard cores of rigid surfaces, as if a particle touched them all at once.
  double k_surfaces = 0.0;
  for (const Wall& wall : w.walls) k_surfaces += wall.hard_stiffness;
  for (const Blade& blade : w.blades) k_surfaces += blade.hard_stiffness;
  TimeStepInfo info;
  double omega2_max = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double contacts =
        (k_contact * w.settings.contacts_per_particle_bound * 2.0 + k_surfaces) / p.mass[i];
    const double contact_rot = contacts * p.mass[i] * p.radius[i] * p.radius[i] / p.inertia[i];
    const double t = trans[i] + contacts, r = rot[i] + contact_rot;
    if (t > omega2_max) {
      omega2_max = t;
      info.limited_by = worst_bond[i] >= 0 ? fmt::format("bond {} (translation of particle {})", worst_bond[i], i)
                                           : fmt::format("contacts of particle {}", i);
    }
    if (r > omega2_max) {
      omega2_max = r;
      info.limited_by = worst_bond[i] >= 0 ? fmt::format("bond {} (rotation of particle {})", worst_bond[i], i)
                                           : fmt::format("contacts of particle {} (rotation)", i);
    }
  }
  info.dt_crit = omega2_max > 0.0 ? 2.0 / std::sqrt(omega2_max) : 1e-3;
  info.dt_damped = info.dt_crit * (std::sqrt(1.0 + zeta_max * zeta_max) - zeta_max);
  info.damped_limited_by =
      zeta_max > 0.0 ? fmt::format("the {} dashpot of bond {}, {:.3g} of critical", zeta_mode,
                                   zeta_bond, zeta_max)
                     : info.limited_by;
  if (w.physics.drag && w.physics.drag_coefficient > 0.0 && n > 0) {
    const double m_min = *std::min_element(p.mass.begin(), p.mass.end());
    const double dt_drag = 2.0 * m_min / w.physics.drag_coefficient;
    if (dt_drag < info.dt_crit) {
      info.dt_crit = dt_drag;
      info.limited_by = "linear drag of the lightest particle";
    }
    if (dt_drag < info.dt_damped) {
      info.dt_damped = dt_drag;
      info.damped_limited_by = "linear drag of the lightest particle";
    }
  }
  return info;
}

std::string ChooseTimeStep(World& w) {
  const TimeStepInfo info = CriticalTimeStep(w);
  const double allowed = std::min(w.settings.safety * info.dt_crit, info.dt_damped);
  if (w.settings.dt <= 0.0) {
    w.settings.dt = allowed;
    return {};
  }
  if (w.settings.dt <= allowed) return {};
  const std::string what =
      info.dt_damped < w.settings.safety * info.dt_crit
          ? fmt::format("time step {:.4g} s exceeds the stability limit with the bond dashpots, "
                        "{:.4g} s (limited by {})",
                        w.settings.dt, info.dt_damped, info.damped_limited_by)
          : fmt::format(
                "time step {:.4g} s exceeds safety {} x critical time step {:.4g} s (limited by {})",
                w.settings.dt, w.settings.safety, info.dt_crit, info.limited_by);
  if (w.settings.policy == TimeStepPolicy::kRefuse)
    throw RunError(what + "; set dt <= " + fmt::format("{:.4g}", allowed) + " s");
  w.settings.dt = allowed;
  return what + fmt::format("; reduced to {:.4g} s", allowed);
}

}  // namespace fibrenet
