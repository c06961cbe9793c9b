// sample/sample: the bonded packing a DEM run starts from, as every sample format loads it.
// Owns: particles (stable id, position, radius, glued group), bonds with rest lengths, the box.
// Not: dynamics state (dem/), how samples are made (sample/generator) or stored (sample/formats).
// Coordinates: x across the width, y along the loading direction (height), z through the depth.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/vec3.hpp"

namespace rupture {

inline constexpr double default_density = 2.5e-4;  // g/mm^3, as in the paper

// Which plate, if any, a particle is glued to.
enum class ParticleGroup : std::uint8_t { free = 0, bottom = 1, top = 2 };

// An initial bond between particles i < j (storage indices into Sample's arrays).
struct Bond {
  std::uint32_t i = 0, j = 0;
  double rest_length = 0.0;  // mm: the initial centre distance r0
};

struct Box {
  Vec3 lower, upper;  // mm
  Vec3 size() const { return upper - lower; }
};

struct Sample {
  Box box;
  std::vector<std::int64_t> id;      // stable ids, written in every output
  std::vector<Vec3> position;        // mm
  std::vector<double> radius;        // mm
  std::vector<ParticleGroup> group;  // glued layer membership
  std::vector<Bond> bonds;           // sorted by (i, j), i < j
  double density = default_density;  // g/mm^3; a run config may override it
  // Free-text provenance (tool version, generator inputs, source file), one entry per line; carried
  // through rupture's own format as comment lines, so every sample file says how it was made.
  std::vector<std::string> provenance;

  std::size_t size() const { return position.size(); }
};

}  // namespace rupture
