// Results of the virtual tests: named scalar metrics with units, and curves (tables of
// samples with named, unit-carrying columns) that can be written as CSV. The engine writes
// files only when a caller hands it an output directory; otherwise results stay in memory.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace fibrenet::pipeline {

// One scalar result, e.g. {"tensile_strength_N_per_m", 21.3, "N/m"}.
struct Metric {
  std::string name;
  double value = 0.0;
  std::string unit;  // "-" for dimensionless
};

// A table of samples. Column names carry their unit in the name ("strain", "stress_N_per_m")
// so the CSV header alone says what each column is.
struct Curve {
  std::string name;                  // file stem, e.g. "tensile_md"
  std::vector<std::string> columns;  // header
  std::vector<std::vector<double>> rows;

  void Add(std::vector<double> row) { rows.push_back(std::move(row)); }
  // Index of a column by name; throws fibrenet::Error when absent.
  std::size_t Column(const std::string& column) const;
  // All values of one column, in row order.
  std::vector<double> Values(const std::string& column) const;
};

// Finds a metric by name; nullptr when absent.
const Metric* FindMetric(const std::vector<Metric>& metrics, const std::string& name);

// Writes `curve` as <directory>/<prefix><curve.name>.csv (header line, then one line per
// row, full double precision) and returns the path. Creates the directory when missing.
// Throws fibrenet::RunError when the file cannot be written.
std::string WriteCurveCsv(const Curve& curve, const std::string& directory,
                          const std::string& prefix = "");
// Writes every curve; returns the paths. An empty directory writes nothing.
std::vector<std::string> WriteCurves(const std::vector<Curve>& curves, const std::string& directory,
                                     const std::string& prefix = "");

}  // namespace fibrenet::pipeline
