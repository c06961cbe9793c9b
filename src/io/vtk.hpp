// io/vtk: VTK XML files for ParaView: PolyData (.vtp) with points, lines and named per-point and
// per-line arrays, and collections (.pvd) that list (time, file) pairs for animations.
// Owns: the file layout only (ASCII XML, written atomically). Not: what the arrays mean.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
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
};

// The .vtp document; throws std::invalid_argument when an array's size does not match.
std::string format_vtp(const VtkPolyData& data);
void write_vtp(const std::filesystem::path& path, const VtkPolyData& data);

struct PvdEntry {
  double time = 0.0;           // s
  std::filesystem::path file;  // written as given (relative to the .pvd is what ParaView expects)
};
std::string format_pvd(const std::vector<PvdEntry>& entries);
void write_pvd(const std::filesystem::path& path, const std::vector<PvdEntry>& entries);

}  // namespace rupture::io
