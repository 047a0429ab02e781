#include "engine/pipeline/curves.h"

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::pipeline {

std::size_t Curve::Column(const std::string& column) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == column) return c;
  throw Error(fmt::format("curve {}: no column named {}", name, column));
}

std::vector<double> Curve::Values(const std::string& column) const {
  const std::size_t c = Column(column);
  std::vector<double> out;
  out.reserve(rows.size());
  for (const auto& row : rows) out.push_back(row[c]);
  return out;
}

const Metric* FindMetric(const std::vector<Metric>& metrics, const std::string& name) {
  for (const Metric& m : metrics)
    if (m.name == name) return &m;
  return nullptr;
}

std::string WriteCurveCsv(const Curve& curve, const std::string& directory,
                          const std::string& prefix) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(directory, ec);
  const std::string path = (fs::path(directory) / (prefix + curve.name + ".csv")).string();
  std::ofstream out(path);
  if (!out) throw RunError(fmt::format("cannot write curve file {}", path));
  for (std::size_t c = 0; c < curve.columns.size(); ++c)
    out << (c ? "," : "") << curve.columns[c];
  out << "\n";
  for (const auto& row : curve.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << fmt::format("{:.17g}", row[c]);
    out << "\n";
  }
  if (!out) throw RunError(fmt::format("error while writing curve file {}", path));
  return path;
}

std::vector<std::string> WriteCurves(const std::vector<Curve>& curves, const std::string& directory,
                                     const std::string& prefix) {
  std::vector<std::string> paths;
  if (directory.empty()) return paths;
  for (const Curve& c : curves) paths.push_back(WriteCurveCsv(c, directory, prefix));
  return paths;
}

}  // namespace fibrenet::pipeline
