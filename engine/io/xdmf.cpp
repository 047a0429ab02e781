#include "engine/io/xdmf.h"

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace fibrenet::io {

namespace {

std::string DataItem(const std::string& h5, const std::string& set, std::size_t rows,
                     std::size_t cols, const char* type, int precision) {
  const std::string dims = cols == 1 ? fmt::format("{}", rows) : fmt::format("{} {}", rows, cols);
  return fmt::format(
      "<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:/{}"
      "</DataItem>",
      dims, type, precision, h5, set);
}

}  // namespace

void WriteXdmf(const std::string& h5_path, std::size_t particles, std::size_t bonds,
               const std::vector<std::string>& fields, double time) {
  const std::filesystem::path h5(h5_path);
  const std::string name = h5.filename().string();  // relative, so the pair can be moved
  std::filesystem::path xdmf = h5;
  xdmf.replace_extension(".xdmf");
  std::ofstream out(xdmf);
  if (!out) throw Error(fmt::format("{}: cannot write XDMF sidecar", xdmf.string()));
  out << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n<Domain>\n";
  out << fmt::format("<Grid Name=\"particles\" GridType=\"Uniform\">\n<Time Value=\"{:.9g}\"/>\n",
                     time);
  out << fmt::format("<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{}\"/>\n", particles);
  out << "<Geometry GeometryType=\"XYZ\">" << DataItem(name, "particles/x", particles, 3, "Float", 8)
      << "</Geometry>\n";
  auto attribute = [&](const std::string& label, const std::string& set, std::size_t cols,
                       const char* type) {
    out << fmt::format("<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"Node\">", label,
                       cols == 3 ? "Vector" : "Scalar")
        << DataItem(name, set, particles, cols, type, 8) << "</Attribute>\n";
  };
  attribute("velocity", "particles/v", 3, "Float");
  attribute("angular_velocity", "particles/omega", 3, "Float");
  attribute("radius", "particles/radius", 1, "Float");
  attribute("fibre", "particles/fibre", 1, "Int");
  for (const std::string& field : fields) attribute(field, "fields/" + field, 1, "Float");
  out << "</Grid>\n";
  out << fmt::format("<Grid Name=\"bonds\" GridType=\"Uniform\">\n<Time Value=\"{:.9g}\"/>\n", time);
  out << fmt::format(
      "<Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\"{}\">{}"
      "</Topology>\n",
      bonds, DataItem(name, "xdmf/bonds", bonds, 2, "Int", 8));
  out << "<Geometry GeometryType=\"XYZ\">" << DataItem(name, "particles/x", particles, 3, "Float", 8)
      << "</Geometry>\n</Grid>\n</Domain>\n</Xdmf>\n";
  out.close();  // flushes: a full disk shows here
  if (!out) throw Error(fmt::format("{}: write failed", xdmf.string()));
}

}  // namespace fibrenet::io
