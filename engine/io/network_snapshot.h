// Snapshots of a fibre network: the World snapshot (snapshot.h) plus the fibre table, and
// labels (free text such as the stages that made the network), so that a later run can
// continue from the network bit for bit (`fibrenet run --from`).
//
// Extra layout: /fibres/index (F x 5: first_particle, particle_count, first_bond,
// bond_count, bond_type), /fibres/properties (F x 6: length, diameter, coarseness, E, G,
// strength, SI units); each label is a root text attribute "label_NAME".
#pragma once

#include <map>
#include <string>

#include "engine/io/snapshot.h"
#include "engine/pipeline/network.h"

namespace fibrenet::io {

using SnapshotLabels = std::map<std::string, std::string>;

void WriteNetworkSnapshot(const pipeline::Network& net, const std::string& path,
                          const PointFields& fields = {}, const SnapshotLabels& labels = {});

// Throws InputError when the file is missing or holds no fibre network, Error when it is
// damaged. `labels` (optional) receives the stored labels.
pipeline::Network ReadNetworkSnapshot(const std::string& path, SnapshotLabels* labels = nullptr);

}  // namespace fibrenet::io
