#include "campaigns/stage_snapshot.h"

#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "campaigns/run_report.h"
#include "engine/core/error.h"
#include "engine/io/network_snapshot.h"
#include "engine/io/snapshot.h"

namespace fibrenet::campaigns {

void WriteStageSnapshot(const pipeline::StageState& state, const std::string& path,
                        const SnapshotOrigin& origin, const io::PointFields& fields) {
  nlohmann::json stages = nlohmann::json::array();
  for (const pipeline::StageReport& s : state.stages) stages.push_back(StageJson(s));
  io::WriteNetworkSnapshot(state.network, path, fields,
                           {{"stages", stages.dump()},
                            {"scene", origin.scene},
                            {"scene_hash", origin.scene_hash},
                            {"seed", std::to_string(origin.seed)}});
}

void WriteStageSnapshots(const std::string& dir, const std::vector<pipeline::StageState>& states,
                         const SnapshotOrigin& origin, const pipeline::PipelineReport& report) {
  const std::filesystem::path folder = std::filesystem::path(dir) / "snapshots";
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw RunError(fmt::format("cannot create {}: {}", folder.string(), ec.message()));
  for (std::size_t k = 0; k < states.size(); ++k) {
    const pipeline::StageState& state = states[k];
    io::PointFields fields;
    const bool last = k + 1 == states.size();
    if (last && report.tests && !report.tests->fibre_energy_at_peak.empty()) {
      const std::vector<double>& per_fibre = report.tests->fibre_energy_at_peak;
      std::vector<double>& field = fields["tensile_peak_fibre_energy_J"];
      for (const std::int32_t f : state.network.world.particles.fibre)
        field.push_back(per_fibre.at(static_cast<std::size_t>(f)));
    }
    const std::string path = (folder / (state.stages.back().name + ".h5")).string();
    try {
      WriteStageSnapshot(state, path, origin, fields);
      // Frames taken during the stage (creping's impact): particles with their velocity, so
      // that ParaView colours them by speed as paper Fig. 6 does.
      const std::vector<World>& frames = state.stages.back().frames;
      for (std::size_t f = 0; f < frames.size(); ++f)
        io::WriteSnapshot(frames[f], (folder / fmt::format("{}_frame_{:03d}.h5",
                                                           state.stages.back().name, f))
                                         .string());
    } catch (const Error& e) {
      throw RunError(e.what());
    }
  }
}

StageSnapshot ReadStageSnapshot(const std::string& path) {
  io::SnapshotLabels labels;
  StageSnapshot snapshot;
  snapshot.state.network = io::ReadNetworkSnapshot(path, &labels);
  for (const char* label : {"stages", "scene", "scene_hash", "seed"})
    if (!labels.count(label))
      throw InputError(fmt::format("{}: not a stage snapshot (no label '{}'); expected a file "
                                   "from `fibrenet run --out DIR` (DIR/snapshots/)", path, label));
  try {
    for (const nlohmann::json& j : nlohmann::json::parse(labels["stages"]))
      snapshot.state.stages.push_back(StageFromJson(j));
    snapshot.origin.seed = std::stoull(labels["seed"]);
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: damaged stage labels: {}", path, e.what()));
  }
  if (snapshot.state.stages.empty())
    throw InputError(fmt::format("{}: the snapshot lists no stages", path));
  snapshot.origin.scene = labels["scene"];
  snapshot.origin.scene_hash = labels["scene_hash"];
  return snapshot;
}

}  // namespace fibrenet::campaigns
