#include "engine/io/network_snapshot.h"

#include <filesystem>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/io/hdf5_file.h"

namespace fibrenet::io {

namespace {

constexpr std::size_t kIndexColumns = 5, kPropertyColumns = 6;
constexpr const char* kLabelPrefix = "label_";

}  // namespace

void WriteNetworkSnapshot(const pipeline::Network& net, const std::string& path,
                          const PointFields& fields, const SnapshotLabels& labels) {
  auto write_fibres = [&](Hdf5File& f) {
    std::vector<std::int64_t> index;
    std::vector<double> properties;
    for (const pipeline::FibreRecord& r : net.fibres) {
      index.insert(index.end(), {r.first_particle, r.particle_count, r.first_bond, r.bond_count,
                                 r.bond_type});
      properties.insert(properties.end(), {r.length, r.diameter, r.coarseness, r.youngs_modulus,
                                           r.shear_modulus, r.strength});
    }
    f.CreateGroup("fibres");
    f.WriteInts("fibres/index", index, kIndexColumns);
    f.WriteDoubles("fibres/properties", properties, kPropertyColumns);
    for (const auto& [name, text] : labels) f.WriteText(kLabelPrefix + name, text);
  };
  WriteSnapshot(net.world, path, fields, write_fibres);
}

pipeline::Network ReadNetworkSnapshot(const std::string& path, SnapshotLabels* labels) {
  if (!std::filesystem::exists(path))
    throw InputError(fmt::format("{}: snapshot file not found", path));
  if (!IsHdf5(path))
    throw InputError(fmt::format("{}: not an HDF5 file; expected a snapshot written by "
                                 "`fibrenet run --out`", path));
  pipeline::Network net;
  {
    Hdf5File f(path, Hdf5File::Mode::kRead);
    if (!f.Exists("fibres"))
      throw InputError(fmt::format(
          "{}: not a fibre-network snapshot (no /fibres table); expected a file written by "
          "`fibrenet run --out`", path));
    const auto index = f.ReadInts("fibres/index", kIndexColumns);
    const auto properties = f.ReadDoubles("fibres/properties", kPropertyColumns);
    if (index.size() / kIndexColumns != properties.size() / kPropertyColumns)
      throw Error(fmt::format("{}: fibre tables have different lengths", path));
    for (std::size_t k = 0; k < index.size() / kIndexColumns; ++k) {
      const std::int64_t* i = index.data() + kIndexColumns * k;
      const double* p = properties.data() + kPropertyColumns * k;
      pipeline::FibreRecord r;
      r.first_particle = static_cast<std::int32_t>(i[0]);
      r.particle_count = static_cast<std::int32_t>(i[1]);
      r.first_bond = static_cast<std::int32_t>(i[2]);
      r.bond_count = static_cast<std::int32_t>(i[3]);
      r.bond_type = static_cast<std::int32_t>(i[4]);
      r.length = p[0]; r.diameter = p[1]; r.coarseness = p[2];
      r.youngs_modulus = p[3]; r.shear_modulus = p[4]; r.strength = p[5];
      net.fibres.push_back(r);
    }
    if (labels) {
      labels->clear();
      const std::string prefix = kLabelPrefix;
      for (const std::string& name : f.AttributeNames())
        if (name.rfind(prefix, 0) == 0) (*labels)[name.substr(prefix.size())] = f.ReadText(name);
    }
  }
  net.world = ReadSnapshot(path);
  if (std::string why = net.CheckInvariants(); !why.empty())
    throw Error(fmt::format("{}: fibre table does not match the particles: {}", path, why));
  return net;
}

}  // namespace fibrenet::io
