#include "analysis/resample.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace rupture::analysis {

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
  out.x0 = xs.front();
  out.step = step;
  report.step = step;
  report.output_rows = m;
  if (report.was_uniform) {
    out.y = std::move(ys);
    return out;
  }
  report.resampled = true;
  out.y.assign(curves.size(), std::vector<double>(m));
  std::size_t segment = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const double x = i + 1 == m ? xs.back() : out.x(i);
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
