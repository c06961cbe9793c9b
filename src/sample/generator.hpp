// sample/generator: dense random bonded packings in a box (GenGeo-style insertion), their initial
// bonds, glued layers and cache-friendly storage order. The algorithm and its known bias are
// described in docs/sample.md. Not: file formats (sample/formats), statistics (sample/stats).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/random.hpp"
#include "sample/sample.hpp"

namespace rupture {

// Radii from a log-normal distribution (ln r ~ Normal(ln median, sigma)) truncated to [r_min, r_max],
// drawn by inverting the truncated CDF so every draw lies inside the bounds.
class TruncatedLogNormal {
 public:
  // Throws InputError (naming the option) unless 0 < r_min < r_max, median > 0 and sigma > 0.
  TruncatedLogNormal(double r_min, double r_max, double median, double sigma);
  double cdf(double r) const;       // P(R <= r) of the truncated distribution
  double quantile(double u) const;  // u in [0, 1] -> radius in [r_min, r_max]
  double draw(Rng& rng) const { return quantile(rng.uniform01()); }

 private:
  double r_min_, r_max_, log_median_, sigma_, cdf_low_, cdf_high_;
};

struct PackingParams {
  Vec3 size{80.0, 25.0, 5.0};  // mm: width (x) x height (y, loading) x depth (z); box starts at 0
  double r_min = 0.2;          // mm: smallest radius
  double r_max = 0.6;          // mm: largest radius
  double r_median = 0.5;       // mm: median of the (untruncated) log-normal
  double r_sigma = 0.3;        // 1: standard deviation of ln r
  // Bond pairs whose surface gap is below bond_tolerance * (r_i + r_j) / 2 (1, relative to the mean
  // radius of the pair).
  double bond_tolerance = 0.7;
  // Stopping rules are rates, so that a larger box packs to the same density: phase 1 (drawn radii)
  // ends with the first block of `draw_block` draws in which fewer than min_drawn_rate of them found a
  // place; phase 2 (gap filling) ends with the first block of `fill_block` random positions in which
  // fewer than min_fill_rate of them admitted a sphere.
  std::uint32_t attempts_per_draw = 200;  // random positions tried for one drawn radius
  std::uint32_t draw_block = 100;
  double min_drawn_rate = 0.05;  // 1
  std::uint32_t fill_block = 2000;
  double min_fill_rate = 0.08;       // 1
  double density = default_density;  // g/mm^3, stored in the sample
};

// What the generator did, for reports and for the tests of its promises.
struct GenerationReport {
  std::size_t drawn_placed = 0;  // particles from phase 1 (radius drawn, then placed)
  std::size_t gap_filled = 0;    // particles from phase 2 (radius set by the gap)
  std::size_t draws = 0;         // radii drawn in phase 1 (placed + discarded)
  // Phase-1 radii up to (not including) the first discarded draw, in draw order: exactly the first
  // draws of the log-normal stream, so they follow the requested distribution without any bias.
  std::vector<double> radii_before_first_discard;
  std::uint64_t positions_tried = 0;  // random positions tried in both phases
  double solid_fraction_drawn = 0.0;  // 1: solid fraction when phase 1 ended
};

// Throws InputError naming the bad parameter (sizes, radii, tolerance) with the fix.
void validate(const PackingParams& params);

// Generates a packing, sorts it along a space-filling curve (id = storage index), bonds it with
// make_bonds() and marks glued layers with assign_glued_layers(). Deterministic in (params, seed).
Sample generate_sample(const PackingParams& params, std::uint64_t seed, GenerationReport* report = nullptr);

// Replaces sample.bonds by every pair whose surface gap d - r_i - r_j is below
// tolerance * (r_i + r_j) / 2; rest length = initial centre distance. Sorted by (i, j), i < j.
void make_bonds(Sample& sample, double tolerance);

// Glue rule: a particle belongs to the bottom (top) layer when its surface is within `depth` mm of
// the face y = box.lower.y (y = box.upper.y); a particle within reach of both goes to the nearer face.
// default_glue_depth() is the sample's smallest radius, so the rule needs no parameter and gives the
// same layers whatever format the sample came from.
double default_glue_depth(const Sample& sample);
void assign_glued_layers(Sample& sample, double depth);
void assign_glued_layers(Sample& sample);

// Reorders particles along a Morton (Z-order) curve of grid cells of width `cell_size` mm, so that
// neighbours in space are neighbours in memory; bonds are remapped and re-sorted. Ids move with
// their particles.
void sort_spatially(Sample& sample, double cell_size);

}  // namespace rupture
