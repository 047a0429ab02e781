#include "engine/pipeline/softness.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::pipeline {

namespace {

// Adds the one-sided power of a periodic profile of n samples: harmonics k = 1..n/2 (at
// wavelength L/k for a profile of length L), adding up to the profile's variance.
void AddProfileSpectrum(const std::vector<double>& z, std::vector<double>& power) {
  const int n = static_cast<int>(z.size());
  power.resize(n / 2, 0.0);
  for (int k = 1; k <= n / 2; ++k) {
    std::complex<double> c = 0.0;
    for (int j = 0; j < n; ++j) c += z[j] * std::polar(1.0, -2.0 * kPi * k * j / n);
    c /= static_cast<double>(n);
    const double one_sided = (2 * k == n) ? std::norm(c) : 2.0 * std::norm(c);
    power[k - 1] += one_sided;
  }
}

Spectrum ProfileSpectrum(const HeightMap& m, bool along_x) {
  const int n = along_x ? m.nx : m.ny, profiles = along_x ? m.ny : m.nx;
  const double L = n * (along_x ? m.pitch_x : m.pitch_y);
  std::vector<double> power, z(n);
  for (int p = 0; p < profiles; ++p) {
    for (int j = 0; j < n; ++j) z[j] = along_x ? m.z[p * m.nx + j] : m.z[j * m.nx + p];
    AddProfileSpectrum(z, power);
  }
  Spectrum s;
  for (std::size_t k = 0; k < power.size(); ++k) {
    s.wavelength.push_back(L / static_cast<double>(k + 1));
    s.amplitude.push_back(std::sqrt(power[k] / profiles));
  }
  return s;
}

double Value(const std::vector<Metric>& metrics, const std::string& name) {
  if (const Metric* m = FindMetric(metrics, name)) return m->value;
  throw Error("softness: no metric " + name);
}

}  // namespace

std::string SoftnessIndexSettings::Validate() const {
  for (double w : {w_bulk, w_roughness, w_bending})
    if (!(w >= 0.0 && w <= 5.0)) return fmt::format("index weight {}: must lie in [0, 5]", w);
  if (!(bulk_ref_um_per_kPa > 0.0 && roughness_ref_um > 0.0 && bending_ref_mN_mm > 0.0))
    return "index references bulk_ref_um_per_kPa, roughness_ref_um, bending_ref_mN_mm must be > 0";
  return {};
}

std::string SoftnessSettings::Validate() const {
  if (!(grid_pitch > 0.0 && grid_pitch <= 1e-3))
    return fmt::format("grid_pitch = {} m: must lie in (0, 1e-3]", grid_pitch);
  if (!(probe_radius >= 0.0 && probe_radius <= 1e-2))
    return fmt::format("probe_radius = {} m: must lie in [0, 1e-2]", probe_radius);
  if (std::string why = index.Validate(); !why.empty()) return why;
  if (bending == BendingMethod::kPureBending)
    if (std::string why = bending_test.Validate(); !why.empty()) return "bending." + why;
  return {};
}

double SoftnessResult::Value(const std::string& name) const {
  return fibrenet::pipeline::Value(metrics, name);
}

HeightMap TopSurface(const World& w, double pitch, double probe_radius) {
  const Particles& p = w.particles;
  HeightMap m;
  m.nx = std::max(2, static_cast<int>(std::lround(w.cell.Lx() / pitch)));
  m.ny = std::max(2, static_cast<int>(std::lround(w.cell.Ly() / pitch)));
  m.pitch_x = w.cell.Lx() / m.nx;
  m.pitch_y = w.cell.Ly() / m.ny;
  // A probe narrower than the sampling pitch would drop into holes narrower than the pitch
  // where a grid point happens to fall on one and miss them elsewhere: the map would alias
  // the particle spacing (a spectral spike at the pitch of the particles, and an Sq made of
  // how many grid points hit holes). The map resolves nothing finer than its pitch, so the
  // probe is at least one pitch in radius.
  probe_radius = std::max(probe_radius, std::max(m.pitch_x, m.pitch_y));
  double bottom = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) bottom = std::min(bottom, p.x[i].z() - p.radius[i]);
  if (p.size() == 0) bottom = 0.0;
  m.z.assign(static_cast<std::size_t>(m.nx) * m.ny, bottom);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double reach = p.radius[i] + probe_radius;
    const double gx = (p.x[i].x() - w.cell.lo.x()) / m.pitch_x;
    const double gy = (p.x[i].y() - w.cell.lo.y()) / m.pitch_y;
    const int rx = static_cast<int>(std::ceil(reach / m.pitch_x));
    const int ry = static_cast<int>(std::ceil(reach / m.pitch_y));
    for (int iy = static_cast<int>(std::floor(gy)) - ry; iy <= static_cast<int>(gy) + ry + 1; ++iy) {
      const double dy = (iy - gy) * m.pitch_y;
      const int wy = ((iy % m.ny) + m.ny) % m.ny;
      for (int ix = static_cast<int>(std::floor(gx)) - rx; ix <= static_cast<int>(gx) + rx + 1;
           ++ix) {
        const double dx = (ix - gx) * m.pitch_x;
        const double rho2 = dx * dx + dy * dy;
        if (rho2 > reach * reach) continue;
        const int wx = ((ix % m.nx) + m.nx) % m.nx;
        double& z = m.z[static_cast<std::size_t>(wy) * m.nx + wx];
        z = std::max(z, p.x[i].z() + std::sqrt(reach * reach - rho2) - probe_radius);
      }
    }
  }
  return m;
}

Roughness MeasureRoughness(const HeightMap& m) {
  Roughness r;
  if (m.z.empty()) return r;
  double mean = 0.0;
  for (double z : m.z) mean += z;
  mean /= static_cast<double>(m.z.size());
  double var = 0.0;
  for (double z : m.z) var += (z - mean) * (z - mean);
  r.sq = std::sqrt(var / static_cast<double>(m.z.size()));
  r.md = ProfileSpectrum(m, true);
  r.cd = ProfileSpectrum(m, false);
  double best = -1.0;
  for (const Spectrum* s : {&r.md, &r.cd})
    for (std::size_t k = 0; k < s->amplitude.size(); ++k)
      if (s->amplitude[k] > best) {
        best = s->amplitude[k];
        r.dominant_wavelength = s->wavelength[k];
      }
  return r;
}

double SoftnessIndex(double bulk_um_per_kPa, double roughness_um, double bending_mN_mm,
                     const SoftnessIndexSettings& s) {
  if (!(bulk_um_per_kPa > 0.0 && roughness_um > 0.0 && bending_mN_mm > 0.0))
    return std::numeric_limits<double>::quiet_NaN();
  return 100.0 * std::pow(bulk_um_per_kPa / s.bulk_ref_um_per_kPa, s.w_bulk) *
         std::pow(s.roughness_ref_um / roughness_um, s.w_roughness) *
         std::pow(s.bending_ref_mN_mm / bending_mN_mm, s.w_bending);
}

SoftnessResult RunSoftnessTest(const Network& net, const SoftnessSettings& s,
                               const SoftnessInputs& inputs, const Progress& progress) {
  if (std::string why = s.Validate(); !why.empty()) throw InputError("softness." + why);
  SoftnessResult res;

  // Surface.
  const HeightMap map = TopSurface(net.world, s.grid_pitch, s.probe_radius);
  const Roughness rough = MeasureRoughness(map);
  for (const auto& [name, spectrum] :
       {std::pair{"roughness_spectrum_md", &rough.md}, std::pair{"roughness_spectrum_cd", &rough.cd}}) {
    Curve c{name, {"wavelength_um", "amplitude_um"}, {}};
    for (std::size_t k = 0; k < spectrum->wavelength.size(); ++k)
      c.Add({spectrum->wavelength[k] * 1e6, spectrum->amplitude[k] * 1e6});
    res.curves.push_back(std::move(c));
  }
  Curve profile{"height_profile", {"x_um", "height_um"}, {}};
  for (int ix = 0; ix < map.nx; ++ix)
    profile.Add({(ix * map.pitch_x) * 1e6, map.z[static_cast<std::size_t>(map.ny / 2) * map.nx + ix] * 1e6});
  res.curves.push_back(std::move(profile));

  // Bulk softness from the ZD compression in its low-pressure window.
  CompressionResult own_zd;
  const CompressionResult* zd = inputs.compression;
  if (!zd) {
    own_zd = RunCompressionTest(net, s.compression, progress);
    res.steps += own_zd.steps;
    for (auto& c : own_zd.curves) res.curves.push_back(c);
    for (auto& warn : own_zd.warnings) res.warnings.push_back(warn);
    zd = &own_zd;
  }
  const double h0_um = zd->h0 * 1e6;
  const double bulk = h0_um / zd->Value("zd_modulus_kPa");

  // Bending stiffness.
  double bending = std::numeric_limits<double>::quiet_NaN();
  if (s.bending == BendingMethod::kPureBending) {
    BendingResult b = RunBendingTest(net, s.bending_test, progress);
    res.steps += b.steps;
    bending = Value(b.metrics, "bending_stiffness");
    for (const Metric& m : b.metrics)
      if (m.name != "bending_stiffness") res.metrics.push_back(m);
    for (auto& warn : b.warnings) res.warnings.push_back(warn);
    res.curves.push_back(std::move(b.curve));
  } else {
    TensileResult own_md, own_cd;
    const TensileResult* md = inputs.md;
    const TensileResult* cd = inputs.cd;
    TensileSettings t = s.tensile;
    if (!md) {
      t.axis = LoadAxis::kMD;
      own_md = RunTensileTest(net, t, progress);
      res.steps += own_md.steps;
      md = &own_md;
    }
    if (!cd) {
      t.axis = LoadAxis::kCD;
      own_cd = RunTensileTest(net, t, progress);
      res.steps += own_cd.steps;
      cd = &own_cd;
    }
    const double S = std::sqrt(md->Value("tensile_modulus_N_per_m") *
                               cd->Value("tensile_modulus_N_per_m"));
    bending = S * zd->h0 * zd->h0 / 12.0 * 1e6;  // N m -> mN mm
  }

  res.metrics.insert(res.metrics.begin(),
                     {{"bulk_softness_um_per_kPa", bulk, "um/kPa"},
                      {"surface_roughness_um", rough.sq * 1e6, "um"},
                      {"surface_dominant_wavelength_um", rough.dominant_wavelength * 1e6, "um"},
                      {"bending_stiffness", bending, "mN mm"},
                      {"softness_index", SoftnessIndex(bulk, rough.sq * 1e6, bending, s.index), "-"}});
  return res;
}

}  // namespace fibrenet::pipeline
