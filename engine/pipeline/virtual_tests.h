// The virtual-test stage of a pipeline run (SPEC 2.5): in-plane tensile (MD, CD or both),
// ZD compression with unloading, and softness, each on its own copy of the finished network,
// so their order does not matter. Softness reuses the compression and tensile results when
// those tests run too.
//
// Metric names: the first tensile direction gets the plain names of tensile_test.h
// (tensile_strength_N_per_m, ...), a second one the prefix "cd_" (or "md_"); with both,
// gmt_tensile_strength_N_per_m = sqrt(MD x CD strength), the geometric-mean tensile that
// tissue makers quote. Compression and softness metrics keep their names.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/pipeline/compression_test.h"
#include "engine/pipeline/curves.h"
#include "engine/pipeline/network.h"
#include "engine/pipeline/progress.h"
#include "engine/pipeline/softness.h"
#include "engine/pipeline/tensile_test.h"

namespace fibrenet::pipeline {

struct TensileStage {
  std::vector<LoadAxis> axes = {LoadAxis::kMD, LoadAxis::kCD};
  TensileSettings settings;  // its axis is overridden by each entry of `axes`
};

struct VirtualTestsSpec {
  std::optional<TensileStage> tensile;
  std::optional<CompressionSettings> compression;
  std::optional<SoftnessSettings> softness;

  bool Any() const { return tensile || compression || softness; }
  // Empty when valid; otherwise "<test>.<field>: what is wrong and the accepted range".
  std::string Validate() const;
};

struct VirtualTestsReport {
  std::vector<Metric> metrics;
  std::vector<Curve> curves;
  std::vector<std::string> warnings;
  // Strain energy increment of each fibre at the tensile peak of the first direction [J]
  // (empty without a tensile test), for snapshots coloured by it.
  std::vector<double> fibre_energy_at_peak;
  std::int64_t steps = 0;
  double wall_s = 0.0;
};

// Throws InputError for an invalid spec and RunError when a test fails.
VirtualTestsReport RunVirtualTests(const Network& net, const VirtualTestsSpec& spec,
                                   const Progress& progress = {});

}  // namespace fibrenet::pipeline
