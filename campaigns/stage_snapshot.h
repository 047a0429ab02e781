// The state after a network stage (forming, pressing) as a file: a network snapshot
// (engine/io) labelled with the stage reports so far and the scene and seed that made it.
// `fibrenet run --out` writes one per stage; `fibrenet run --from` continues from one.
#pragma once

#include <cstdint>
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

void WriteStageSnapshot(const pipeline::StageState& state, const std::string& path,
                        const SnapshotOrigin& origin, const io::PointFields& fields = {});

// Writes DIR/snapshots/<stage>.h5 (with its .xdmf) for each state. The last one, the
// network the virtual tests started from, carries the field tensile_peak_fibre_energy_J
// when a tensile test ran: each particle gets its fibre's strain energy increment at the
// tensile peak (ParaView colours the fibres by it). Throws RunError on I/O failure.
void WriteStageSnapshots(const std::string& dir, const std::vector<pipeline::StageState>& states,
                         const SnapshotOrigin& origin, const pipeline::PipelineReport& report);

struct StageSnapshot {
  pipeline::StageState state;
  SnapshotOrigin origin;
};

// Throws InputError naming the file when it is missing or not a stage snapshot.
StageSnapshot ReadStageSnapshot(const std::string& path);

}  // namespace fibrenet::campaigns
