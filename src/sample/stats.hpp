// sample/stats: the numbers that describe any sample (generated or imported): counts, solid
// fraction, coordination, radius histogram, glued layers, and the largest overlap as a check.
#pragma once

#include <cstddef>
#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "sample/sample.hpp"

namespace rupture {

struct SampleStats {
  std::size_t particles = 0;
  std::size_t bonds = 0;
  double box_volume = 0.0;                         // mm^3
  double solid_fraction = 0.0;                     // 1: sphere volume / box volume
  double mean_coordination = 0.0;                  // 1: bonds per particle, 2 * bonds / particles
  std::size_t isolated = 0;                        // particles without any bond
  double r_min = 0.0, r_max = 0.0, r_mean = 0.0;   // mm
  std::vector<double> radius_bin_edges;            // mm, bins + 1 edges from r_min to r_max
  std::vector<std::size_t> radius_histogram;       // particles per bin
  std::size_t bottom_layer = 0, top_layer = 0;     // particles glued to the bottom / top plate
  double bottom_layer_y = 0.0, top_layer_y = 0.0;  // mm: mean height of each glued layer (pull axis y)
  double max_overlap = 0.0;  // mm: largest r_i + r_j - d over all pairs (0 if none overlap)
  double total_mass = 0.0;   // g
};

SampleStats compute_stats(const Sample& sample, std::size_t histogram_bins = 8);

// JSON with the keys particles, bonds, solid_fraction, mean_coordination, ...; sizes and the mass
// as quantities {"value", "unit"} (io/quantity.hpp).
nlohmann::json to_json(const SampleStats& stats);

}  // namespace rupture
