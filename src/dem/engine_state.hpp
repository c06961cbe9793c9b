// dem/engine_state: the engine's evolving state as plain arrays, for checkpoints. With the same
// sample and Params it fixes every later step bit for bit. That includes what only fixes the order of
// floating-point sums: each particle's link order (breaks permute it), the neighbour list with its
// slice capacities, and the positions the list was built at (they decide the next rebuild).
// Constants (masses, anchors, bond constants, storage order) are rebuilt from the sample. The
// neighbour list's adaptive skin is not kept: a resumed engine starts at Params::skin, the narrowest,
// which only makes its next rebuild come sooner (forces do not depend on the skin).
// Owns: the field list. Not: the file format (loading/checkpoint) or the checks on restore
// (System::restore_state).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dem/params.hpp"

namespace rupture::dem {

// Seconds spent in each stage since construction (for profiles and `rupture bench`).
struct StageTimes {
  double neighbours = 0.0;  // list builds
  double integrate = 0.0;   // first half-kick and drift
  double forces = 0.0;      // the force pass, which also finishes the step's second half-kick
  double plates = 0.0;      // plate forces
  double breaks = 0.0;      // applying the flagged breaks
};

struct EngineState {
  std::uint64_t step = 0;
  double time = 0.0;  // s
  PlateMotion top;
  std::array<double, 3> plate_force{};                    // N, per Plate
  double plate_work = 0.0, released = 0.0, damped = 0.0;  // mJ
  std::uint64_t neighbour_rebuilds = 0;
  bool forces_stale = false;
  StageTimes stage_times;                        // s, carried over so reports cover the whole run
  std::vector<std::uint32_t> sample_of_storage;  // the storage order it was saved in (checked)
  std::vector<double> x, y, z;                   // mm
  std::vector<double> vx, vy, vz;                // mm/s
  std::vector<double> fx, fy, fz;                // N: velocity Verlet's first half-kick needs them
  std::vector<double> xb, yb, zb;                // mm: positions at the last neighbour-list build
  std::vector<double> damped_per_particle;       // mJ
  std::vector<std::uint8_t> intact;              // per bond: 1 intact, 0 broken
  std::vector<std::uint32_t> link_count;         // per particle: intact links at the slice start
  std::vector<std::uint32_t> link_bond;          // per link slot: its bond (slot order = sum order)
  std::vector<std::uint32_t> nb_start;           // n + 1: neighbour slice starts (capacities)
  std::vector<std::uint32_t> nb_count;           // per particle: used part of its slice
  std::vector<std::uint32_t> nb;                 // neighbour slices, unused slots zero
};

}  // namespace rupture::dem
