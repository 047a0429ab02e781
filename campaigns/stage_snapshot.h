// The state after a network stage (forming, pressing) as a file: a network snapshot
// (engine/io) labelled with the stage reports so far and the scene and seed that made it.
// `fibrenet run --out` writes one per stage; `fibrenet run --from` continues from one.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/io/snapshot.h"
#include "engine/pipeline/pipeline.h"

namespace fibrenet::campaigns {

struct SnapshotOrigin {
  std::string scene;       // the scene file's name
  std::string scene_hash;  // hash of its text
  std::uint64_t seed = 0;
};

// The network after `stages` (the last one names the stage) as a stage snapshot.
void WriteStageSnapshot(std::span<const pipeline::StageReport> stages,
                        const pipeline::Network& network, const std::string& path,
                        const SnapshotOrigin& origin, const io::PointFields& fields = {});
void WriteStageSnapshot(const pipeline::StageState& state, const std::string& path,
                        const SnapshotOrigin& origin, const io::PointFields& fields = {});

// Writes DIR/snapshots/<stage>.h5 (with its .xdmf) for each earlier state, freeing each once
// written, then for the report's own network (the last network stage, which the virtual
// tests started from). That last one carries the field tensile_peak_fibre_energy_J when a
// tensile test ran: each particle gets its fibre's strain energy increment at the tensile
// peak (ParaView colours the fibres by it). Throws RunError on I/O failure.
void WriteStageSnapshots(const std::string& dir, std::vector<pipeline::StageState> earlier,
                         const SnapshotOrigin& origin, const pipeline::PipelineReport& report);

struct StageSnapshot {
  pipeline::StageState state;
  SnapshotOrigin origin;
};

// Throws InputError naming the file when it is missing or not a stage snapshot.
StageSnapshot ReadStageSnapshot(const std::string& path);

}  // namespace fibrenet::campaigns
