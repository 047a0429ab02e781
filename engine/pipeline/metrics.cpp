#include "engine/pipeline/metrics.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "engine/pipeline/pairs.h"
#include "engine/pipeline/percentile.h"

namespace fibrenet::pipeline {

namespace {

// Volume of the slice z in [a, b] of a sphere of radius r centred at z = 0.
double SliceVolume(double r, double a, double b) {
  a = std::clamp(a, -r, r);
  b = std::clamp(b, -r, r);
  if (b <= a) return 0.0;
  auto primitive = [r](double z) { return r * r * z - z * z * z / 3.0; };
  return kPi * (primitive(b) - primitive(a));
}

}  // namespace

std::string MetricsSettings::Validate() const {
  if (!(fibre_density > 0.0 && fibre_density <= 1e5))
    return fmt::format("fibre_density = {} kg/m^3: must lie in (0, 1e5]", fibre_density);
  if (!(thickness_grid > 0.0 && thickness_grid <= 0.1))
    return fmt::format("thickness_grid = {} m: must lie in (0, 0.1]", thickness_grid);
  if (!(surface_percentile >= 0.0 && surface_percentile < 50.0))
    return fmt::format("surface_percentile = {}: must lie in [0, 50)", surface_percentile);
  if (!(profile_bin > 0.0 && profile_bin <= 0.01))
    return fmt::format("profile_bin = {} m: must lie in (0, 0.01]", profile_bin);
  return {};
}

namespace {

// Every scalar metric by name, in the order List() gives them.
constexpr std::pair<const char*, double NetworkMetrics::*> kScalarMetrics[] = {
    {"basis_weight_gsm", &NetworkMetrics::basis_weight_gsm},
    {"thickness_um", &NetworkMetrics::thickness_um},
    {"density_kg_per_m3", &NetworkMetrics::density_kg_per_m3},
    {"porosity", &NetworkMetrics::porosity},
    {"bonds_per_fibre", &NetworkMetrics::bonds_per_fibre},
    {"bonded_pairs_per_fibre", &NetworkMetrics::bonded_pairs_per_fibre},
    {"contacts_per_fibre", &NetworkMetrics::contacts_per_fibre},
    {"crossings_per_fibre", &NetworkMetrics::crossings_per_fibre},
    {"crossings_per_fibre_kallmes_corte", &NetworkMetrics::crossings_per_fibre_kallmes_corte},
    {"fibre_count", &NetworkMetrics::fibre_count},
    {"particle_count", &NetworkMetrics::particle_count},
    {"out_of_plane_angle_deg_mean", &NetworkMetrics::out_of_plane_angle_deg_mean},
    {"orientation_anisotropy", &NetworkMetrics::orientation_anisotropy}};

}  // namespace

std::vector<std::pair<std::string, double>> NetworkMetrics::List() const {
  std::vector<std::pair<std::string, double>> list;
  for (const auto& [name, field] : kScalarMetrics) list.emplace_back(name, this->*field);
  return list;
}

bool NetworkMetrics::Set(const std::string& name, double value) {
  for (const auto& [known, field] : kScalarMetrics)
    if (name == known) {
      this->*field = value;
      return true;
    }
  return false;
}

const char* NetworkMetricUnit(const std::string& name) {
  if (name == "basis_weight_gsm") return "g/m^2";
  if (name == "thickness_um") return "um";
  if (name == "density_kg_per_m3") return "kg/m^3";
  if (name == "out_of_plane_angle_deg_mean") return "deg";
  return "-";
}

SheetSurfaces MeasureSurfaces(const World& w, double grid, double percentile) {
  const Particles& p = w.particles;
  const int nx = std::max(1, static_cast<int>(std::lround(w.cell.Lx() / grid)));
  const int ny = std::max(1, static_cast<int>(std::lround(w.cell.Ly() / grid)));
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> top(static_cast<std::size_t>(nx) * ny, -inf), bottom(top.size(), inf);
  for (std::size_t i = 0; i < p.size(); ++i) {
    Vec3 x = p.x[i];
    w.cell.Wrap(x);
    const int cx = std::clamp(static_cast<int>((x.x() - w.cell.lo.x()) / w.cell.Lx() * nx), 0, nx - 1);
    const int cy = std::clamp(static_cast<int>((x.y() - w.cell.lo.y()) / w.cell.Ly() * ny), 0, ny - 1);
    const std::size_t c = static_cast<std::size_t>(cy) * nx + cx;
    top[c] = std::max(top[c], x.z() + p.radius[i]);
    bottom[c] = std::min(bottom[c], x.z() - p.radius[i]);
  }
  std::vector<double> tops, bottoms;
  for (std::size_t c = 0; c < top.size(); ++c)
    if (std::isfinite(top[c])) {
      tops.push_back(top[c]);
      bottoms.push_back(bottom[c]);
    }
  const double q = percentile / 100.0;
  return {Percentile(tops, 1.0 - q), Percentile(bottoms, q)};
}

double Thickness(const World& w, double grid, double percentile) {
  const SheetSurfaces s = MeasureSurfaces(w, grid, percentile);
  return s.top - s.bottom;
}

DensityProfile MeasureDensityProfile(const World& w, double bin) {
  const Particles& p = w.particles;
  DensityProfile prof;
  prof.bin = bin;
  if (p.size() == 0) return prof;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < p.size(); ++i) {
    lo = std::min(lo, p.x[i].z() - p.radius[i]);
    hi = std::max(hi, p.x[i].z() + p.radius[i]);
  }
  const double z0 = std::floor(lo / bin) * bin;
  const auto bins = static_cast<std::size_t>(std::ceil((hi - z0) / bin));
  std::vector<double> mass(bins, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i], zc = p.x[i].z();
    const double volume = 4.0 / 3.0 * kPi * r * r * r;
    const auto first = static_cast<std::size_t>(std::max(0.0, std::floor((zc - r - z0) / bin)));
    for (std::size_t k = first; k < bins && z0 + k * bin < zc + r; ++k)
      mass[k] += p.mass[i] * SliceVolume(r, z0 + k * bin - zc, z0 + (k + 1) * bin - zc) / volume;
  }
  const double area = w.cell.Lx() * w.cell.Ly();
  for (std::size_t k = 0; k < bins; ++k) {
    prof.z.push_back(z0 + (k + 0.5) * bin);
    prof.density.push_back(mass[k] / (area * bin));
  }
  return prof;
}

NetworkMetrics Measure(const Network& net, const MetricsSettings& s) {
  const World& w = net.world;
  const Particles& p = w.particles;
  NetworkMetrics m;
  const double fibres = static_cast<double>(net.fibres.size());
  m.fibre_count = fibres;
  m.particle_count = static_cast<double>(p.size());
  const double bw = net.TotalMass() / net.Area();  // [kg/m^2]
  m.basis_weight_gsm = bw * 1e3;
  const double thickness = Thickness(w, s.thickness_grid, s.surface_percentile);
  m.thickness_um = thickness * 1e6;
  m.density_kg_per_m3 = thickness > 0.0 ? bw / thickness : 0.0;
  m.porosity = 1.0 - m.density_kg_per_m3 / s.fibre_density;
  if (fibres > 0.0) {
    m.bonds_per_fibre = 2.0 * static_cast<double>(net.IntactFibreFibreBonds()) / fibres;
    std::set<std::pair<std::int32_t, std::int32_t>> pairs;
    const Bonds& b = w.bonds;
    for (std::size_t k = 0; k < b.size(); ++k)
      if (b.kind[k] == BondKind::kFibreFibre && !b.broken[k])
        pairs.insert(std::minmax(p.fibre[b.i[k]], p.fibre[b.j[k]]));
    m.bonded_pairs_per_fibre = 2.0 * static_cast<double>(pairs.size()) / fibres;
    m.contacts_per_fibre = 2.0 * static_cast<double>(TouchingPairs(w, 0.0).size()) / fibres;
    m.crossings_per_fibre = CrossingsPerFibre(net, &m.crossings_per_fibre_kallmes_corte);
  }

  double angle_sum = 0.0, c2 = 0.0, s2 = 0.0, weight = 0.0;
  std::size_t segments = 0;
  for (const FibreRecord& f : net.fibres)
    for (int k = 0; k + 1 < f.particle_count; ++k) {
      const Vec3 d = w.cell.Delta(p.x[f.first_particle + k], p.x[f.first_particle + k + 1]);
      const double l = std::hypot(d.x(), d.y());
      angle_sum += std::atan2(std::abs(d.z()), l);
      ++segments;
      const double phi = std::atan2(d.y(), d.x());
      c2 += l * std::cos(2.0 * phi);
      s2 += l * std::sin(2.0 * phi);
      weight += l;
    }
  if (segments > 0) m.out_of_plane_angle_deg_mean = angle_sum / segments * 180.0 / kPi;
  if (weight > 0.0) m.orientation_anisotropy = std::hypot(c2, s2) / weight;
  m.profile = MeasureDensityProfile(w, s.profile_bin);
  return m;
}

}  // namespace fibrenet::pipeline
