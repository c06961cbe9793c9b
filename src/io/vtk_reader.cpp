// Reading a .vtp back (io/vtk.hpp): a scanner for the few elements a PolyData file has, not a
// general XML parser. Written here rather than taken from VTK because VTK's C++ library is a large
// dependency for reading the files rupture itself writes (and its older ASCII ones).
#include <fmt/format.h>
#include <zlib.h>

#include <bit>
#include <cstring>
#include <map>
#include <optional>

#include "core/error.hpp"
#include "core/tokens.hpp"
#include "io/atomic_file.hpp"
#include "io/vtk.hpp"

namespace rupture::io {

namespace {

static_assert(std::endian::native == std::endian::little, "VTK files are read as little-endian");

// The largest uncompressed block size a file may declare (VTK writes 32 kB, rupture 64 kB).
constexpr std::uint64_t max_block_bytes = std::uint64_t(1) << 30;

// One tag: its name ("/X" for a closing one) and attributes, and where it ends in the text.
struct Tag {
  std::string name;
  std::map<std::string, std::string, std::less<>> attributes;
  bool self_closing = false;
  std::size_t end = 0;  // just past '>'
};

// An attribute value with the five XML entities (what io/markup writes) replaced.
std::string unescape(std::string_view text) {
  static constexpr std::pair<std::string_view, char> entities[] = {
      {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&#39;", '\''}, {"&amp;", '&'}};
  std::string out;
  for (std::size_t k = 0; k < text.size();) {
    bool replaced = false;
    for (const auto& [entity, c] : entities) {
      if (text.compare(k, entity.size(), entity) == 0) {
        out += c;
        k += entity.size();
        replaced = true;
        break;
      }
    }
    if (!replaced) out += text[k++];
  }
  return out;
}

class VtpReader {
 public:
  VtpReader(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  VtkPolyData read() {
    const std::size_t appended_tag = text_.find("<AppendedData");
    header_ = text_.substr(0, appended_tag);
    if (appended_tag != std::string_view::npos) {
      const std::size_t marker = text_.find('_', appended_tag);
      if (marker == std::string_view::npos) fail("<AppendedData> has no '_' before its data", "");
      appended_ = text_.substr(marker + 1);
    }
    VtkPolyData data;
    std::string section;  // Points, PointData, Lines or CellData
    std::vector<std::int64_t> connectivity, offsets;
    for (std::size_t at = 0; (at = header_.find('<', at)) != std::string_view::npos;) {
      if (header_.compare(at, 4, "<!--") == 0 || header_.compare(at, 2, "<?") == 0) {
        at = header_.find('>', at);
        continue;
      }
      const Tag tag = read_tag(at);
      at = tag.end;
      if (tag.name == "VTKFile") read_file_attributes(tag);
      if (tag.name == "Points" || tag.name == "PointData" || tag.name == "Lines" || tag.name == "CellData")
        section = tag.self_closing ? "" : tag.name;
      if (tag.name.front() == '/' && tag.name.substr(1) == section) section.clear();
      if (tag.name != "DataArray") continue;
      VtkArray array = read_array(tag);
      if (section == "Points" && array.components == 3) {
        const auto xyz = as_doubles(array);
        for (std::size_t k = 0; k + 2 < xyz.size(); k += 3)
          data.points.push_back({xyz[k], xyz[k + 1], xyz[k + 2]});
      } else if (section == "PointData") {
        data.point_data.push_back(std::move(array));
      } else if (section == "CellData") {
        data.line_data.push_back(std::move(array));
      } else if (section == "Lines" && array.name == "connectivity") {
        connectivity = integers(array);
      } else if (section == "Lines" && array.name == "offsets") {
        offsets = integers(array);
      }
    }
    data.lines = two_point_lines(connectivity, offsets, data.points.size());
    return data;
  }

 private:
  [[noreturn]] void fail(const std::string& problem, const std::string& name) const {
    throw InputError(source_, name.empty() ? problem : fmt::format("DataArray '{}': {}", name, problem),
                     "give a .vtp written by rupture or by VTK (XML PolyData)");
  }

  Tag read_tag(std::size_t at) const {
    const std::size_t close = header_.find('>', at);
    if (close == std::string_view::npos) fail(fmt::format("a tag at byte {} is not closed", at), "");
    std::string_view inside = header_.substr(at + 1, close - at - 1);
    Tag tag;
    tag.end = close + 1;
    if (!inside.empty() && inside.back() == '/') {
      tag.self_closing = true;
      inside.remove_suffix(1);
    }
    const std::size_t name_end = std::min(inside.find_first_of(" \t\r\n"), inside.size());
    tag.name = std::string(inside.substr(0, name_end));
    for (std::size_t p = name_end; (p = inside.find('=', p)) != std::string_view::npos;) {
      const std::size_t name_start = inside.find_last_of(" \t\r\n", p) + 1;
      const std::size_t open = inside.find_first_of("\"'", p);
      const std::size_t end = open == std::string_view::npos ? open : inside.find(inside[open], open + 1);
      if (end == std::string_view::npos)
        fail(fmt::format("an attribute of <{}> is not quoted", tag.name), "");
      tag.attributes.emplace(std::string(inside.substr(name_start, p - name_start)),
                             unescape(inside.substr(open + 1, end - open - 1)));
      p = end + 1;
    }
    if (tag.name.empty()) fail(fmt::format("an empty tag at byte {}", at), "");
    return tag;
  }

  void read_file_attributes(const Tag& tag) {
    const auto attribute = [&](std::string_view key) {
      const auto it = tag.attributes.find(key);
      return it == tag.attributes.end() ? std::string() : it->second;
    };
    if (const std::string order = attribute("byte_order"); !order.empty() && order != "LittleEndian")
      fail(fmt::format("byte_order {} is not read (LittleEndian only)", order), "");
    wide_header_ = attribute("header_type") == "UInt64";
    const std::string compressor = attribute("compressor");
    if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
      fail(fmt::format("compressor {} is not read (zlib or none only)", compressor), "");
    compressed_ = !compressor.empty();
  }

  VtkArray read_array(const Tag& tag) const {
    const auto attribute = [&](std::string_view key, std::string fallback) {
      const auto it = tag.attributes.find(key);
      return it == tag.attributes.end() ? fallback : it->second;
    };
    VtkArray array;
    array.name = attribute("Name", "");
    array.components = std::atoi(attribute("NumberOfComponents", "1").c_str());
    if (array.components < 1) fail("NumberOfComponents is not a positive number", array.name);
    const std::string type = attribute("type", ""), format = attribute("format", "ascii");
    const bool floating = type == "Float64" || type == "Float32";
    if (format == "ascii") {
      const std::size_t end = header_.find("</DataArray>", tag.end);
      if (end == std::string_view::npos) fail("no </DataArray>", array.name);
      const std::string_view numbers = header_.substr(tag.end, end - tag.end);
      if (floating)
        array.values = parse_numbers<double>(numbers, array.name);
      else
        array.values = parse_numbers<std::int64_t>(numbers, array.name);
      return array;
    }
    if (format != "appended")
      fail(fmt::format("format {} is not read (appended or ascii)", format), array.name);
    const std::string bytes =
        appended_bytes(std::strtoull(attribute("offset", "0").c_str(), nullptr, 10), array.name);
    if (type == "Float64")
      array.values = from_bytes<double, double>(bytes, array.name);
    else if (type == "Float32")
      array.values = from_bytes<float, double>(bytes, array.name);
    else if (type == "Int64")
      array.values = from_bytes<std::int64_t, std::int64_t>(bytes, array.name);
    else if (type == "UInt64")
      array.values = from_bytes<std::uint64_t, std::int64_t>(bytes, array.name);
    else if (type == "Int32")
      array.values = from_bytes<std::int32_t, std::int64_t>(bytes, array.name);
    else if (type == "UInt32")
      array.values = from_bytes<std::uint32_t, std::int64_t>(bytes, array.name);
    else if (type == "UInt8")
      array.values = from_bytes<std::uint8_t, std::int64_t>(bytes, array.name);
    else
      fail(fmt::format("type {} is not read", type), array.name);
    return array;
  }

  template <class T>
  std::vector<T> parse_numbers(std::string_view text, const std::string& name) const {
    std::vector<T> values;
    for (const std::string_view word : tokens::words(text)) {
      const auto value = tokens::number<T>(word);
      if (!value) fail(fmt::format("'{}' is not a number", excerpt(word, 20)), name);
      values.push_back(*value);
    }
    return values;
  }

  // An unsigned header entry (32 or 64 bits) at `at` of the appended section.
  std::uint64_t header_entry(std::size_t at, const std::string& name) const {
    const std::size_t width = wide_header_ ? 8 : 4;
    if (at + width > appended_.size()) fail("its data runs past the end of the file", name);
    std::uint64_t value = 0;
    if (wide_header_) {
      std::memcpy(&value, appended_.data() + at, 8);
    } else {
      std::uint32_t narrow = 0;
      std::memcpy(&narrow, appended_.data() + at, 4);
      value = narrow;
    }
    return value;
  }

  std::string appended_bytes(std::uint64_t offset, const std::string& name) const {
    const std::size_t width = wide_header_ ? 8 : 4;
    if (!compressed_) {
      const std::uint64_t size = header_entry(offset, name);
      if (size > appended_.size() || offset + width + size > appended_.size())
        fail("its data runs past the end of the file", name);
      return std::string(appended_.substr(offset + width, size));
    }
    const std::uint64_t blocks = header_entry(offset, name), block = header_entry(offset + width, name),
                        last = header_entry(offset + 2 * width, name);
    // A damaged header must not make the reader allocate without bound: each block's compressed
    // size is in the file, and zlib expands by at most about 1032x.
    if (blocks > appended_.size() / width || block == 0 || block > max_block_bytes || last > block)
      fail("its compression header is damaged", name);
    std::size_t at = offset + (3 + blocks) * width;
    std::string bytes;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::uint64_t compressed = header_entry(offset + (3 + b) * width, name);
      const std::uint64_t expected = (b + 1 == blocks && last != 0) ? last : block;
      if (compressed > appended_.size() || expected > 1032 * (compressed + 64))
        fail(fmt::format("block {} is damaged", b), name);
      if (at + compressed > appended_.size()) fail("its data runs past the end of the file", name);
      std::string out(expected, '\0');
      uLongf size = static_cast<uLongf>(expected);
      if (uncompress(reinterpret_cast<Bytef*>(out.data()), &size,
                     reinterpret_cast<const Bytef*>(appended_.data() + at),
                     static_cast<uLong>(compressed)) != Z_OK ||
          size != expected)
        fail(fmt::format("block {} does not decompress to {} bytes", b, expected), name);
      bytes += out;
      at += compressed;
    }
    return bytes;
  }

  template <class Stored, class Value>
  std::vector<Value> from_bytes(const std::string& bytes, const std::string& name) const {
    if (bytes.size() % sizeof(Stored) != 0) fail("its byte count is not a whole number of values", name);
    std::vector<Value> values(bytes.size() / sizeof(Stored));
    for (std::size_t k = 0; k < values.size(); ++k) {
      Stored v;
      std::memcpy(&v, bytes.data() + k * sizeof(Stored), sizeof(Stored));
      values[k] = static_cast<Value>(v);
    }
    return values;
  }

  std::vector<std::int64_t> integers(const VtkArray& array) const {
    if (const auto* v = std::get_if<std::vector<std::int64_t>>(&array.values)) return *v;
    fail("is not an integer array", array.name);
  }

  std::vector<std::array<std::uint32_t, 2>> two_point_lines(const std::vector<std::int64_t>& connectivity,
                                                            const std::vector<std::int64_t>& offsets,
                                                            std::size_t points) const {
    std::vector<std::array<std::uint32_t, 2>> lines;
    std::int64_t start = 0;
    for (const std::int64_t end : offsets) {
      if (end != start + 2 || std::size_t(end) > connectivity.size())
        fail("lines other than two-point lines are not read", "offsets");
      const std::int64_t a = connectivity[std::size_t(start)], b = connectivity[std::size_t(start) + 1];
      if (a < 0 || b < 0 || std::size_t(a) >= points || std::size_t(b) >= points)
        fail(fmt::format("line ({}, {}) refers past the {} points", a, b, points), "connectivity");
      lines.push_back({std::uint32_t(a), std::uint32_t(b)});
      start = end;
    }
    return lines;
  }

  std::string_view text_, header_, appended_;
  const std::string& source_;
  bool wide_header_ = false, compressed_ = false;
};

}  // namespace

VtkPolyData parse_vtp(std::string_view text, const std::string& source) {
  return VtpReader(text, source).read();
}

VtkPolyData read_vtp(const std::filesystem::path& path) { return parse_vtp(read_file(path), path.string()); }

}  // namespace rupture::io
