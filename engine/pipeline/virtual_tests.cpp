#include "engine/pipeline/virtual_tests.h"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::pipeline {

namespace {

const char* Prefix(LoadAxis a) { return a == LoadAxis::kMD ? "md_" : "cd_"; }

void Append(VirtualTestsReport& report, std::vector<std::string> warnings) {
  for (std::string& w : warnings) report.warnings.push_back(std::move(w));
}

}  // namespace

std::string VirtualTestsSpec::Validate() const {
  if (tensile) {
    if (tensile->axes.empty() || tensile->axes.size() > 2 ||
        (tensile->axes.size() == 2 && tensile->axes[0] == tensile->axes[1]))
      return "tensile.direction: give MD, CD or both";
    if (std::string why = tensile->settings.Validate(); !why.empty()) return "tensile." + why;
  }
  if (compression)
    if (std::string why = compression->Validate(); !why.empty()) return "compression." + why;
  if (softness)
    if (std::string why = softness->Validate(); !why.empty()) return "softness." + why;
  return {};
}

VirtualTestsReport RunVirtualTests(const Network& net, const VirtualTestsSpec& spec,
                                   const Progress& progress) {
  if (std::string why = spec.Validate(); !why.empty()) throw InputError(why);
  VirtualTestsReport report;
  Stopwatch clock;

  std::optional<TensileResult> md, cd;
  if (spec.tensile) {
    bool first = true;
    for (LoadAxis axis : spec.tensile->axes) {
      TensileSettings s = spec.tensile->settings;
      s.axis = axis;
      TensileResult r = RunTensileTest(net, s, progress);
      report.steps += r.steps;
      for (const Metric& m : r.metrics)
        report.metrics.push_back({first ? m.name : Prefix(axis) + m.name, m.value, m.unit});
      if (first) report.fibre_energy_at_peak = r.fibre_energy_at_peak;
      report.curves.push_back(r.curve);
      Append(report, r.warnings);
      (axis == LoadAxis::kMD ? md : cd) = std::move(r);
      first = false;
    }
    if (md && cd)
      report.metrics.push_back({"gmt_tensile_strength_N_per_m",
                                std::sqrt(md->Value("tensile_strength_N_per_m") *
                                          cd->Value("tensile_strength_N_per_m")),
                                "N/m"});
  }

  std::optional<CompressionResult> zd;
  if (spec.compression) {
    CompressionResult r = RunCompressionTest(net, *spec.compression, progress);
    report.steps += r.steps;
    report.metrics.insert(report.metrics.end(), r.metrics.begin(), r.metrics.end());
    report.curves.insert(report.curves.end(), r.curves.begin(), r.curves.end());
    Append(report, r.warnings);
    zd = std::move(r);
  }

  if (spec.softness) {
    SoftnessInputs inputs;
    inputs.compression = zd ? &*zd : nullptr;
    inputs.md = md ? &*md : nullptr;
    inputs.cd = cd ? &*cd : nullptr;
    SoftnessResult r = RunSoftnessTest(net, *spec.softness, inputs, progress);
    report.steps += r.steps;
    report.metrics.insert(report.metrics.end(), r.metrics.begin(), r.metrics.end());
    report.curves.insert(report.curves.end(), r.curves.begin(), r.curves.end());
    Append(report, r.warnings);
  }
  report.wall_s = clock.Seconds();
  return report;
}

}  // namespace fibrenet::pipeline
