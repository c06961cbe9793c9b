#include "io/vtk.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <charconv>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/markup.hpp"

namespace rupture::io {

namespace {

// Uncompressed bytes per zlib block (VTK's reader decompresses block by block).
constexpr std::size_t block_bytes = 1 << 16;

std::size_t array_size(const VtkArray& a) {
  return std::visit([](const auto& v) { return v.size(); }, a.values);
}

template <class T>
void put_raw(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // little-endian hosts only (the header says so)
  out.append(bytes, sizeof(T));
}

// The appended section: each array's bytes as VTK's zlib layout expects them, a header of
// UInt64s (blocks, block size, last block's size, each block's compressed size) and the blocks.
class AppendedData {
 public:
  // Appends `bytes` and returns its offset in the section.
  std::size_t add(std::string_view bytes) {
    const std::size_t offset = data_.size();
    const std::size_t blocks = (bytes.size() + block_bytes - 1) / block_bytes;
    std::string header, compressed;
    put_raw<std::uint64_t>(header, blocks);
    put_raw<std::uint64_t>(header, block_bytes);
    put_raw<std::uint64_t>(header, bytes.size() % block_bytes);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::string_view block = bytes.substr(b * block_bytes, block_bytes);
      uLongf size = compressBound(static_cast<uLong>(block.size()));
      std::string out(size, '\0');
      if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(block.data()),
                    static_cast<uLong>(block.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
        throw std::runtime_error("zlib could not compress a VTK array");
      put_raw<std::uint64_t>(header, size);
      compressed.append(out.data(), size);
    }
    data_ += header;
    data_ += compressed;
    return offset;
  }
  const std::string& bytes() const { return data_; }

 private:
  std::string data_;
};

template <class T>
std::string_view raw_bytes(const std::vector<T>& values) {
  return {reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T)};
}

void append_array(fmt::memory_buffer& out, AppendedData& appended, const VtkArray& a, std::size_t tuples,
                  const char* where) {
  if (a.components < 1 || array_size(a) != tuples * static_cast<std::size_t>(a.components))
    throw std::invalid_argument(fmt::format("VTK {} array '{}' holds {} values, expected {} x {}", where,
                                            a.name, array_size(a), tuples, a.components));
  const bool is_float = std::holds_alternative<std::vector<double>>(a.values);
  const std::size_t offset = std::visit([&](const auto& v) { return appended.add(raw_bytes(v)); }, a.values);
  fmt::format_to(std::back_inserter(out),
                 "        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                 "offset=\"{}\"/>\n",
                 is_float ? "Float64" : "Int64", escape_markup(a.name), a.components, offset);
}

const VtkArray* find_array(const std::vector<VtkArray>& arrays, std::string_view name) {
  for (const auto& a : arrays)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace

const VtkArray* VtkPolyData::point_array(std::string_view name) const { return find_array(point_data, name); }
const VtkArray* VtkPolyData::line_array(std::string_view name) const { return find_array(line_data, name); }

std::vector<double> as_doubles(const VtkArray& array) {
  return std::visit([](const auto& v) { return std::vector<double>(v.begin(), v.end()); }, array.values);
}

std::string format_vtp(const VtkPolyData& data) {
  AppendedData appended;
  fmt::memory_buffer out;
  auto it = std::back_inserter(out);
  fmt::format_to(it, "<?xml version=\"1.0\"?>\n");
  for (const auto& comment : data.comments) {
    std::string safe = comment;
    for (std::size_t p; (p = safe.find("--")) != std::string::npos;) safe.replace(p, 2, "- -");
    fmt::format_to(it, "<!-- {} -->\n", safe);
  }
  fmt::format_to(it,
                 "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n");
  fmt::format_to(it,
                 "  <PolyData>\n    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" "
                 "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
                 data.points.size(), data.lines.size());
  std::vector<double> coordinates;
  coordinates.reserve(3 * data.points.size());
  for (const Vec3& p : data.points) coordinates.insert(coordinates.end(), {p.x, p.y, p.z});
  fmt::format_to(it, "      <Points>\n");
  append_array(out, appended, {"Points", 3, std::move(coordinates)}, data.points.size(), "point");
  fmt::format_to(it, "      </Points>\n      <PointData>\n");
  for (const auto& a : data.point_data) append_array(out, appended, a, data.points.size(), "point");
  std::vector<std::int64_t> connectivity, offsets;
  connectivity.reserve(2 * data.lines.size());
  offsets.reserve(data.lines.size());
  for (const auto& line : data.lines) {
    if (line[0] >= data.points.size() || line[1] >= data.points.size())
      throw std::invalid_argument(
          fmt::format("VTK line ({}, {}) refers past the {} points", line[0], line[1], data.points.size()));
    connectivity.insert(connectivity.end(), {line[0], line[1]});
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  fmt::format_to(it, "      </PointData>\n      <Lines>\n");
  append_array(out, appended, {"connectivity", 1, std::move(connectivity)}, 2 * data.lines.size(), "line");
  append_array(out, appended, {"offsets", 1, std::move(offsets)}, data.lines.size(), "line");
  fmt::format_to(it, "      </Lines>\n      <CellData>\n");
  for (const auto& a : data.line_data) append_array(out, appended, a, data.lines.size(), "line");
  fmt::format_to(it,
                 "      </CellData>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _");
  std::string text = fmt::to_string(out);
  text += appended.bytes();
  text += "\n  </AppendedData>\n</VTKFile>\n";
  return text;
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
