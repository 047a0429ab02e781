// XDMF sidecar describing a snapshot's HDF5 datasets, so ParaView (Xdmf3 reader) shows the
// particles as points with their fields and the intact bonds as line segments.
#pragma once

#include <string>
#include <vector>

namespace fibrenet::io {

// Writes h5_path with its extension replaced by .xdmf. Field names refer to /fields/NAME.
void WriteXdmf(const std::string& h5_path, std::size_t particles, std::size_t bonds,
               const std::vector<std::string>& fields, double time);

}  // namespace fibrenet::io
