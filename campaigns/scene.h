// Scene files: a TOML description of one pipeline run (fibres, cell, stages and their
// settings, fidelity, random seed), read into pipeline::PipelineSpec in SI units. Keys name
// their unit (length_mm, diameter_um, basis_weight_gsm, ...); a stage table present means
// the stage runs. docs/scene-files.md lists every key with unit, default and range.
//
// Errors (unknown key with a close-match suggestion, wrong type, out-of-range or
// non-physical value, missing file, TOML syntax) are fibrenet::InputError messages that
// name the file, the dotted key and the accepted range.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/pipeline/pipeline.h"

namespace fibrenet::campaigns {

// A numeric scene key set by dotted path ("pressing.target_thickness_um" = 150,
// "fibres.length_mm.mean" = 2.1), applied to the file's contents before validation. The
// optimiser sets its design variables this way. The path must name a key the scene
// reader knows (in a stage that is enabled); integer keys take integral values only.
struct Override {
  Override() = default;
  Override(std::string key, double number) : path(std::move(key)), value(number) {}

  std::string path;
  double value = 0.0;
  std::optional<bool> flag;  // a switch's value (KEY=true or KEY=false) instead of a number
};

// Parses "path=value" (as given on a command line): a number, or true / false for a switch.
Override ParseOverride(const std::string& text);

// The stage a key's table feeds, in pipeline order: [cell], [fibres], [contact] and
// [forming] go into the network at forming; [fidelity], [metrics] and top-level keys feed
// every stage. The stage cache and `run --from` both go by it.
enum class KeyStage { kEvery = -1, kForming, kConsolidation, kCreping, kTests };
KeyStage StageOfKey(const std::string& path);

pipeline::PipelineSpec LoadScene(const std::string& path, const std::vector<Override>& overrides = {});

// The text of a scene file (InputError naming the file when it cannot be read).
std::string ReadSceneText(const std::string& path);

// The same from text; `name` stands for the file in messages.
pipeline::PipelineSpec ParseScene(std::string_view text, const std::string& name,
                                  const std::vector<Override>& overrides = {});

}  // namespace fibrenet::campaigns
