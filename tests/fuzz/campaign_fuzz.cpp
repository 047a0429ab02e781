// libFuzzer target for the campaign reader (campaigns/campaign_file.h) and its check against
// the base scene (campaigns/campaign_check.h): the input bytes are the text of a campaign file.
// Bad input must end in a fibrenet::InputError; any other exception, a crash or undefined
// behaviour is a finding. scripts/fuzz.sh builds and runs it (docs/reliability.md).
//
// The fuzzer must not read arbitrary files of the machine: the campaign is parsed without
// touching the base scene, and a base scene is read only when it lies in campaigns/scenes/;
// any other scene path is checked against campaigns/scenes/tiny.toml instead, so that the
// campaign's variables and fidelity overrides still go through the scene reader.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include "campaigns/campaign_check.h"
#include "campaigns/campaign_file.h"
#include "engine/core/error.h"

namespace {

namespace fs = std::filesystem;
using fibrenet::campaigns::CampaignSpec;
using fibrenet::campaigns::ParseMode;

const std::string kScenesDir = FIBRENET_SCENES_DIR;
const std::string kSource = "fuzz.toml";

// An accepted campaign must hold what docs/campaigns.md promises of its counts; a count outside
// its range means the reader misread a value (e.g. one wrapped into an int) instead of
// refusing it.
void CheckAccepted(const CampaignSpec& spec) {
  using fibrenet::campaigns::kMaxEvaluations, fibrenet::campaigns::kMaxReplicates,
      fibrenet::campaigns::kMaxPopulation;
  auto within = [](int v, int lo, int hi) { return v >= lo && v <= hi; };
  bool ok = within(spec.stop.max_evaluations, 1, kMaxEvaluations) && !spec.fidelities.empty();
  for (const auto& f : spec.fidelities)
    ok = ok && within(f.replicates, 1, kMaxReplicates) && within(f.top, 1, kMaxEvaluations);
  if (spec.algorithm) ok = ok && within(spec.algorithm->population, 0, kMaxPopulation);
  if (spec.doe) ok = ok && within(spec.doe->points, 1, kMaxEvaluations);
  if (ok) return;
  std::fprintf(stderr, "campaign_fuzz: an accepted campaign holds a count outside its range\n");
  std::abort();
}

void ReadAndCheck(std::string_view text) {
  CampaignSpec spec =
      fibrenet::campaigns::ParseCampaign(text, kSource, kScenesDir, ParseMode::kStored);
  CheckAccepted(spec);
  if (spec.base_scene.rfind(fibrenet::campaigns::kAnalyticPrefix, 0) != 0) {
    std::error_code ec;  // a name too long for the system names no file
    const bool in_scenes = spec.base_scene.rfind(kScenesDir + "/", 0) == 0;
    if (in_scenes && fs::is_regular_file(spec.base_scene, ec))
      spec = fibrenet::campaigns::ParseCampaign(text, kSource, kScenesDir, ParseMode::kFull);
    else
      spec.base_scene = kScenesDir + "/tiny.toml";
  }
  fibrenet::campaigns::CheckAgainstBaseScene(spec);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    ReadAndCheck(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const fibrenet::InputError&) {
    // Bad input refused with a message: the expected outcome.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "campaign_fuzz: bad input escaped as a non-InputError exception: %s\n",
                 e.what());
    std::abort();
  }
  return 0;
}
