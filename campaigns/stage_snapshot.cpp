#include "campaigns/stage_snapshot.h"

#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "campaigns/run_report.h"
#include "engine/core/error.h"
#include "engine/io/network_snapshot.h"
#include "engine/io/snapshot.h"

namespace fibrenet::campaigns {

void WriteStageSnapshot(std::span<const pipeline::StageReport> stages,
                        const pipeline::Network& network, const std::string& path,
                        const SnapshotOrigin& origin, const io::PointFields& fields) {
  nlohmann::json labels = nlohmann::json::array();
  for (const pipeline::StageReport& s : stages) labels.push_back(StageJson(s));
  io::WriteNetworkSnapshot(network, path, fields,
                           {{"stages", labels.dump()},
                            {"scene", origin.scene},
                            {"scene_hash", origin.scene_hash},
                            {"seed", std::to_string(origin.seed)}});
}

void WriteStageSnapshot(const pipeline::StageState& state, const std::string& path,
                        const SnapshotOrigin& origin, const io::PointFields& fields) {
  WriteStageSnapshot(state.stages, state.network, path, origin, fields);
}

namespace {

// DIR/snapshots/<stage>.h5 of the network after `stages`, and the frames taken during its
// last stage (creping's impact: particles with their velocity, so that ParaView colours them
// by speed as paper Fig. 6 does).
void WriteSnapshotFiles(const std::filesystem::path& folder,
                        std::span<const pipeline::StageReport> stages,
                        const pipeline::Network& network, const SnapshotOrigin& origin,
                        const io::PointFields& fields) {
  const std::string& name = stages.back().name;
  try {
    WriteStageSnapshot(stages, network, (folder / (name + ".h5")).string(), origin, fields);
    const std::vector<World>& frames = stages.back().frames;
    for (std::size_t f = 0; f < frames.size(); ++f)
      io::WriteSnapshot(frames[f], (folder / fmt::format("{}_frame_{:03d}.h5", name, f)).string());
  } catch (const Error& e) {
    throw RunError(e.what());
  }
}

}  // namespace

void WriteStageSnapshots(const std::string& dir, std::vector<pipeline::StageState> earlier,
                         const SnapshotOrigin& origin, const pipeline::PipelineReport& report) {
  const std::filesystem::path folder = std::filesystem::path(dir) / "snapshots";
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw RunError(fmt::format("cannot create {}: {}", folder.string(), ec.message()));
  for (pipeline::StageState& state : earlier) {
    WriteSnapshotFiles(folder, state.stages, state.network, origin, {});
    state = {};  // its network is on disk: free it before the next is written
  }
  const std::span<const pipeline::StageReport> stages = pipeline::NetworkStages(report);
  if (stages.empty()) return;
  io::PointFields fields;
  if (report.tests && !report.tests->fibre_energy_at_peak.empty()) {
    const std::vector<double>& per_fibre = report.tests->fibre_energy_at_peak;
    std::vector<double>& field = fields["tensile_peak_fibre_energy_J"];
    for (const std::int32_t f : report.network.world.particles.fibre)
      field.push_back(per_fibre.at(static_cast<std::size_t>(f)));
  }
  WriteSnapshotFiles(folder, stages, report.network, origin, fields);
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
