#include "io/vtk.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/markup.hpp"

namespace rupture::io {

namespace {

std::size_t array_size(const VtkArray& a) {
  return std::visit([](const auto& v) { return v.size(); }, a.values);
}

void append_array(fmt::memory_buffer& out, const VtkArray& a, std::size_t tuples, const char* where) {
  if (a.components < 1 || array_size(a) != tuples * static_cast<std::size_t>(a.components))
    throw std::invalid_argument(fmt::format("VTK {} array '{}' holds {} values, expected {} x {}", where,
                                            a.name, array_size(a), tuples, a.components));
  const bool is_float = std::holds_alternative<std::vector<double>>(a.values);
  fmt::format_to(std::back_inserter(out),
                 "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n",
                 is_float ? "Float64" : "Int64", escape_markup(a.name), a.components);
  std::visit(
      [&](const auto& values) {
        for (std::size_t k = 0; k < values.size(); ++k)
          fmt::format_to(std::back_inserter(out), "{}{}", values[k], (k + 1) % 8 == 0 ? '\n' : ' ');
      },
      a.values);
  fmt::format_to(std::back_inserter(out), "\n        </DataArray>\n");
}

}  // namespace

std::string format_vtp(const VtkPolyData& data) {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it, "<?xml version=\"1.0\"?>\n");
  for (const auto& comment : data.comments) {
    std::string safe = comment;
    for (std::size_t p; (p = safe.find("--")) != std::string::npos;) safe.replace(p, 2, "- -");
    fmt::format_to(it, "<!-- {} -->\n", safe);
  }
  fmt::format_to(
      it, "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  fmt::format_to(it,
                 "  <PolyData>\n    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                 "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
                 data.points.size(), data.lines.size());
  fmt::format_to(
      it,
      "      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
      "format=\"ascii\">\n");
  for (const Vec3& p : data.points) fmt::format_to(it, "{} {} {}\n", p.x, p.y, p.z);
  fmt::format_to(it, "        </DataArray>\n      </Points>\n");
  fmt::format_to(it, "      <PointData>\n");
  for (const auto& a : data.point_data) append_array(out, a, data.points.size(), "point");
  fmt::format_to(it, "      </PointData>\n      <Lines>\n");
  fmt::format_to(it, "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& line : data.lines) {
    if (line[0] >= data.points.size() || line[1] >= data.points.size())
      throw std::invalid_argument(
          fmt::format("VTK line ({}, {}) refers past the {} points", line[0], line[1], data.points.size()));
    fmt::format_to(it, "{} {}\n", line[0], line[1]);
  }
  fmt::format_to(
      it, "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t k = 0; k < data.lines.size(); ++k)
    fmt::format_to(it, "{}{}", 2 * (k + 1), (k + 1) % 16 == 0 ? '\n' : ' ');
  fmt::format_to(it, "\n        </DataArray>\n      </Lines>\n      <CellData>\n");
  for (const auto& a : data.line_data) append_array(out, a, data.lines.size(), "line");
  fmt::format_to(it, "      </CellData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n");
  return fmt::to_string(out);
}

void write_vtp(const std::filesystem::path& path, const VtkPolyData& data) {
  write_file_atomically(path, format_vtp(data));
}

std::string format_pvd(const std::vector<PvdEntry>& entries) {
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it,
                 "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" "
                 "byte_order=\"LittleEndian\">\n  <Collection>\n");
  for (const auto& e : entries)
    fmt::format_to(it, "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time,
                   escape_markup(e.file.generic_string()));
  fmt::format_to(it, "  </Collection>\n</VTKFile>\n");
  return fmt::to_string(out);
}

void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries) {
  write_file_atomically(path, format_pvd(entries));
}

}  // namespace rupture::io
