// sample/checks: the plausibility of a sample, whoever made it: every number finite and in a
// physical range, bonds between distinct existing particles, no two particles (nearly) on top of
// each other, glued layers on both plates with the top above the bottom. Not: reading files
// (sample/formats) or the engine's own consistency checks (dem/).
#pragma once

#include <string>

#include "sample/sample.hpp"

namespace rupture {

// g/mm^3: from aerogel (1e-6) with margin to twice osmium; a density in t/mm^3 (1e-9 times the
// value in g/mm^3) falls below it.
inline constexpr double min_plausible_density = 1e-7, max_plausible_density = 5e-2;
// mm: particle radii (a micron to a metre) and coordinates (within a kilometre of the origin).
inline constexpr double min_plausible_radius = 1e-6, max_plausible_radius = 1e3,
                        max_plausible_coordinate = 1e6;
// Two particles whose centres are closer than this part of their summed radii are taken as a
// duplicate or a broken export: bonded packings overlap by a few percent at most.
inline constexpr double max_overlap_fraction = 0.5;

// The most particles a sample may have: a run keeps about 500 bytes per particle (docs/
// performance.md), so 5e7 particles need some 25 GB. Generators refuse larger requests with the
// estimate instead of failing to allocate.
inline constexpr double max_particles = 5e7;
inline constexpr double run_bytes_per_particle = 500.0;

// Throws InputError naming `source`, the particle ids or bond, and the fix.
void check_sample(const Sample& sample, const std::string& source);

}  // namespace rupture
