#include "campaigns/run_report.h"

#include <filesystem>
#include <fstream>
#include <limits>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::campaigns {

namespace {

nlohmann::json MetricsJson(const pipeline::NetworkMetrics& m) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, value] : m.List()) j[name] = value;
  return j;
}

std::ofstream OpenOut(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw RunError(fmt::format("cannot write {}", path.string()));
  out.precision(10);
  return out;
}

// JSON has no NaN: nlohmann writes it as null.
double Number(const nlohmann::json& j) {
  return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

}  // namespace

nlohmann::json StageJson(const pipeline::StageReport& s) {
  nlohmann::json details = nlohmann::json::object();
  for (const auto& [name, value] : s.details) details[name] = value;
  return {{"name", s.name},
          {"wall_s", s.wall_s},
          {"steps", s.steps},
          {"metrics", MetricsJson(s.metrics)},
          {"details", details},
          {"warnings", s.warnings}};
}

pipeline::StageReport StageFromJson(const nlohmann::json& j) {
  pipeline::StageReport s;
  s.name = j.at("name").get<std::string>();
  s.wall_s = j.at("wall_s").get<double>();
  s.steps = j.at("steps").get<std::int64_t>();
  for (const auto& [name, value] : j.at("metrics").items())
    if (!s.metrics.Set(name, Number(value)))
      throw Error(fmt::format("stage {}: unknown metric {}", s.name, name));
  for (const auto& [name, value] : j.at("details").items())
    s.details.emplace_back(name, Number(value));
  s.warnings = j.at("warnings").get<std::vector<std::string>>();
  return s;
}

nlohmann::json ReportJson(const pipeline::PipelineReport& report) {
  nlohmann::json stages = nlohmann::json::array();
  for (const pipeline::StageReport& s : report.stages) stages.push_back(StageJson(s));
  nlohmann::json metrics = nlohmann::json::object();
  nlohmann::json units = nlohmann::json::object();
  for (const pipeline::Metric& m : report.AllMetrics()) {
    metrics[m.name] = m.value;
    units[m.name] = m.unit;
  }
  return {{"metrics", metrics},
          {"units", units},
          {"stages", stages},
          {"wall_s", report.wall_s}};
}

void WriteOutputs(const std::string& dir, const pipeline::PipelineReport& report) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RunError(fmt::format("cannot create output folder {}: {}", dir, ec.message()));
  const fs::path root(dir);
  OpenOut(root / "metrics.json") << ReportJson(report).dump(2) << "\n";
  for (const pipeline::StageReport& s : report.stages) {
    // The tests work on copies (no new profile); a stage read from a snapshot has none.
    if (s.name == "tests" || s.metrics.profile.z.empty()) continue;
    auto out = OpenOut(root / (s.name + "_density_profile.csv"));
    out << "z_um,density_kg_per_m3\n";
    for (std::size_t k = 0; k < s.metrics.profile.z.size(); ++k)
      out << s.metrics.profile.z[k] * 1e6 << "," << s.metrics.profile.density[k] << "\n";
    if (!s.press_curve.empty()) {
      auto curve = OpenOut(root / (s.name + "_curve.csv"));
      curve << "time_s,plate_z_um,pressure_Pa,kinetic_J\n";
      for (const auto& p : s.press_curve)
        curve << p.time << "," << p.plate_z * 1e6 << "," << p.pressure << "," << p.kinetic << "\n";
    }
  }
  for (const pipeline::StageReport& s : report.stages)
    pipeline::WriteCurves(s.curves, (root / "curves").string());
  if (report.tests) pipeline::WriteCurves(report.tests->curves, (root / "curves").string());
  const World& w = report.network.world;
  auto out = OpenOut(root / "particles.csv");
  out << "x_um,y_um,z_um,radius_um,fibre\n";
  for (std::size_t i = 0; i < w.particles.size(); ++i)
    out << w.particles.x[i].x() * 1e6 << "," << w.particles.x[i].y() * 1e6 << ","
        << w.particles.x[i].z() * 1e6 << "," << w.particles.radius[i] * 1e6 << ","
        << w.particles.fibre[i] << "\n";
}

}  // namespace fibrenet::campaigns
