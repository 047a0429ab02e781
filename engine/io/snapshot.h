// Snapshots of a World in HDF5: the complete state needed to continue a run bit for bit
// (particles, bonds with their reference frames and history, bond parameters, broken-bond
// events, contact histories, walls, physics switches, settings, energy ledger), plus an
// XDMF sidecar so that ParaView opens the particles (with any extra per-particle fields,
// e.g. strain energy) and the intact bonds as line segments.
//
// Layout (datasets, row-major): /particles/{x,v,omega (N x 3), q (N x 4: w x y z), radius,
// mass, inertia, inv_mass, inv_inertia, fibre}, /bonds/{ij (B x 2), type, kind, broken, L0,
// b_i, b_j (B x 4), dashpot, plastic (B x 2)}, /bonds/types (T x 18, columns in
// snapshot.cpp), /bonds/events, /contacts/{ij, xi}, /walls/..., /fields/NAME, /xdmf/bonds;
// scalars are root attributes.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "engine/core/world.h"

namespace fibrenet::io {

class Hdf5File;

using PointFields = std::map<std::string, std::vector<double>>;  // one value per particle

// Writes what a layer above the World stores with it (e.g. a fibre table) into the open file.
using ExtraWriter = std::function<void(Hdf5File&)>;

// Writes `path` (.h5) and, beside it, `path` with extension .xdmf. Throws fibrenet::Error.
void WriteSnapshot(const World& w, const std::string& path, const PointFields& fields = {},
                   const ExtraWriter& extra = {});

// Reads a snapshot into a fresh World, with contact histories restored into a rebuilt
// neighbour list. Throws fibrenet::Error naming the file.
World ReadSnapshot(const std::string& path);

}  // namespace fibrenet::io
