// analysis/resample: turns measured samples (any order, repeated or unevenly spaced strains) into
// curves on one uniform strain grid, and says what it did. Not: filtering.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rupture::analysis {

struct ResampleReport {
  std::size_t input_rows = 0;
  bool was_sorted = true;             // strain non-decreasing in the input order
  std::size_t duplicates_merged = 0;  // rows whose strain repeated an earlier one (values averaged)
  bool was_uniform = true;            // spacing equal to within 1e-6 of the mean step
  bool resampled = false;             // linear interpolation onto a uniform grid was needed
  bool on_lattice = false;            // that grid is the spacing most rows share (their rows kept)
  std::size_t output_rows = 0;
  std::size_t block_average = 1;  // samples averaged into one (average_blocks)
  double step = 0.0;              // grid spacing, strain units
};

// Curves sampled on x = x0 + i * step.
struct UniformCurves {
  double x0 = 0.0, step = 0.0;
  std::vector<std::vector<double>> y;  // y[curve][i]
  std::size_t size() const { return y.empty() ? 0 : y.front().size(); }
  double x(std::size_t i) const { return x0 + static_cast<double>(i) * step; }
};

// Sorts by strain (stable), averages rows with equal strain, and when the spacing is not uniform
// interpolates linearly onto a uniform grid: the lattice of the spacing at least half the rows share
// (those rows kept as they are), else a grid over the same range with as many points as distinct
// strains. `curves` are columns aligned with `strain`. Needs at least two distinct strains.
UniformCurves resample_uniform(std::span<const double> strain,
                               std::span<const std::span<const double>> curves, ResampleReport& report);

// Averages blocks of k consecutive samples, k the smallest that leaves at most `max_samples`
// (a trailing partial block is dropped): a curve sampled far more densely than its features needs
// no more samples than that, and every later stage (filter choice, bootstrap) scales with them.
// White noise shrinks by √k in the average, and the noise model measures it there.
void average_blocks(UniformCurves& curves, std::size_t max_samples, ResampleReport& report);

}  // namespace rupture::analysis
