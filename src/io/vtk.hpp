// io/vtk: VTK XML files for ParaView: PolyData (.vtp) with points, lines and named per-point and
// per-line arrays, and collections (.pvd) that list (time, file) pairs for animations.
// Owns: the file layout: the XML header with each array's data appended in binary, compressed
// with zlib (what ParaView reads fastest and stores smallest), written atomically; reading such a
// file back (and the ASCII layout of older rupture files). Not: what the arrays mean.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/vec3.hpp"

namespace rupture::io {

// One named data array: `components` values per point (or line), Float64 or Int64.
struct VtkArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::int64_t>> values;
};

struct VtkPolyData {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 2>> lines;  // point indices
  std::vector<VtkArray> point_data;                 // each sized points * components
  std::vector<VtkArray> line_data;                  // each sized lines * components
  std::vector<std::string> comments;                // provenance, written as XML comments

  // The array of that name (nullptr if none); `values` as doubles whatever the stored type.
  const VtkArray* point_array(std::string_view name) const;
  const VtkArray* line_array(std::string_view name) const;
};
std::vector<double> as_doubles(const VtkArray& array);

// The .vtp document (binary appended, zlib); throws std::invalid_argument when an array's size
// does not match.
std::string format_vtp(const VtkPolyData& data);
void write_vtp(const std::filesystem::path& path, const VtkPolyData& data);

// A .vtp's points, two-point lines and arrays: appended raw data (zlib-compressed or not, 32- or
// 64-bit headers) or ASCII; Float32/64 and integer arrays. Comments are not read. Throws
// InputError naming `source` and what does not fit.
VtkPolyData parse_vtp(std::string_view text, const std::string& source);
VtkPolyData read_vtp(const std::filesystem::path& path);

struct PvdEntry {
  double time = 0.0;           // s
  std::filesystem::path file;  // written as given (relative to the .pvd is what ParaView expects)
};
std::string format_pvd(const std::vector<PvdEntry>& entries);
void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries);

}  // namespace rupture::io
