#include "analysis/resample.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <optional>

namespace rupture::analysis {

namespace {

struct Lattice {
  double x0 = 0.0, step = 0.0;
  std::size_t points = 0;
};

// The lattice most rows share: where at least half the spacings equal their median to 1e-6, the grid
// of that spacing through the first such row, from its first point in range to its last. A run's
// curve is such a table (a row every N steps, a smooth start and a stop row off the lattice):
// on this grid its even rows are kept as they are. A grid of as many points over the whole range
// falls between the rows at fractions that drift along the curve, and interpolated white noise
// shrinks (to 71 % midway) and correlates, so the noise model read it too low and the analysis lost
// accuracy (δ_x rms error 33-84 % against 7-21 % on known-answer curves written as a run writes
// them; docs/analysis.md, "On DEM runs").
std::optional<Lattice> lattice_of(std::span<const double> xs) {
  std::vector<double> spacing(xs.size() - 1);
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) spacing[i] = xs[i + 1] - xs[i];
  std::vector<double> sorted = spacing;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double step = *middle;
  const auto even = [&](double d) { return std::abs(d - step) <= 1e-6 * step; };
  const auto count = static_cast<std::size_t>(std::count_if(spacing.begin(), spacing.end(), even));
  if (step <= 0.0 || 2 * count < spacing.size()) return std::nullopt;
  const double anchor =
      xs[static_cast<std::size_t>(std::find_if(spacing.begin(), spacing.end(), even) - spacing.begin())];
  const double first = std::ceil((xs.front() - anchor) / step - 1e-6);
  const double last = std::floor((xs.back() - anchor) / step + 1e-6);
  const double points = last - first + 1.0;
  // A lattice far denser or sparser than the rows (a curve of close pairs, say, whose small gap is
  // the median) is no grid for them.
  const auto rows = static_cast<double>(xs.size());
  if (points < std::max(2.0, 0.5 * rows) || points > 2.0 * rows) return std::nullopt;
  return Lattice{anchor + first * step, step, static_cast<std::size_t>(points)};
}

}  // namespace

UniformCurves resample_uniform(std::span<const double> strain,
                               std::span<const std::span<const double>> curves, ResampleReport& report) {
  const std::size_t n = strain.size();
  report = ResampleReport{};
  report.input_rows = n;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  report.was_sorted = std::is_sorted(strain.begin(), strain.end());
  if (!report.was_sorted) {
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return strain[a] < strain[b]; });
  }
  // Merge equal strains by averaging.
  std::vector<double> xs;
  std::vector<std::vector<double>> ys(curves.size());
  xs.reserve(n);
  for (auto& y : ys) y.reserve(n);
  for (std::size_t k = 0; k < n;) {
    std::size_t end = k + 1;
    while (end < n && strain[order[end]] == strain[order[k]]) ++end;
    xs.push_back(strain[order[k]]);
    for (std::size_t c = 0; c < curves.size(); ++c) {
      double sum = 0.0;
      for (std::size_t j = k; j < end; ++j) sum += curves[c][order[j]];
      ys[c].push_back(sum / static_cast<double>(end - k));
    }
    report.duplicates_merged += end - k - 1;
    k = end;
  }
  const std::size_t m = xs.size();
  assert(m >= 2);
  const double step = (xs.back() - xs.front()) / static_cast<double>(m - 1);
  for (std::size_t i = 1; i < m && report.was_uniform; ++i) {
    report.was_uniform = std::abs((xs[i] - xs[i - 1]) - step) <= 1e-6 * step;
  }
  UniformCurves out;
  if (report.was_uniform) {
    out.x0 = xs.front();
    out.step = report.step = step;
    report.output_rows = m;
    out.y = std::move(ys);
    return out;
  }
  report.resampled = true;
  const std::optional<Lattice> lattice = lattice_of(xs);
  report.on_lattice = lattice.has_value();
  const Lattice grid = lattice.value_or(Lattice{xs.front(), step, m});
  out.x0 = grid.x0;
  out.step = report.step = grid.step;
  report.output_rows = grid.points;
  out.y.assign(curves.size(), std::vector<double>(grid.points));
  std::size_t segment = 0;
  for (std::size_t i = 0; i < grid.points; ++i) {
    const double x = lattice ? std::min(out.x(i), xs.back()) : i + 1 == m ? xs.back() : out.x(i);
    while (segment + 2 < m && xs[segment + 1] < x) ++segment;
    const double t = (x - xs[segment]) / (xs[segment + 1] - xs[segment]);
    for (std::size_t c = 0; c < curves.size(); ++c) {
      out.y[c][i] = ys[c][segment] + t * (ys[c][segment + 1] - ys[c][segment]);
    }
  }
  return out;
}

void average_blocks(UniformCurves& curves, std::size_t max_samples, ResampleReport& report) {
  const std::size_t n = curves.size();
  if (max_samples < 2 || n <= max_samples) return;
  const std::size_t k = (n + max_samples - 1) / max_samples;
  const std::size_t m = n / k;
  for (auto& y : curves.y) {
    for (std::size_t b = 0; b < m; ++b) {
      double sum = 0.0;
      for (std::size_t j = b * k; j < (b + 1) * k; ++j) sum += y[j];
      y[b] = sum / static_cast<double>(k);
    }
    y.resize(m);
  }
  curves.x0 += 0.5 * static_cast<double>(k - 1) * curves.step;
  curves.step *= static_cast<double>(k);
  report.block_average = k;
  report.output_rows = m;
  report.step = curves.step;
}

}  // namespace rupture::analysis
