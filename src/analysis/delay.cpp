#include "analysis/delay.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "analysis/filters.hpp"

namespace rupture::analysis {

namespace {

// Weighted median of `values` with positive `weights` (expected linear time, quickselect).
double weighted_median(std::vector<std::pair<double, double>>& items) {
  double total = 0.0;
  for (const auto& item : items) total += item.second;
  double below = 0.0;  // weight already known to lie below the current range
  auto first = items.begin(), last = items.end();
  while (last - first > 1) {
    auto mid = first + (last - first) / 2;
    std::nth_element(first, mid, last, [](const auto& a, const auto& b) { return a.first < b.first; });
    double lower = below;
    for (auto it = first; it != mid; ++it) lower += it->second;
    if (lower + mid->second < 0.5 * total) {
      below = lower + mid->second;
      first = mid + 1;
    } else if (lower > 0.5 * total) {
      last = mid;
    } else {
      return mid->first;
    }
  }
  return first->first;
}

// The exact weighted median, found quickly when a guess is close: one pass sums the weight below a
// band around the guess and collects the items inside it; if the median falls in the band only the
// band is sorted, otherwise the full selection runs. The answer never depends on the guess.
class WeightedMedian {
 public:
  double operator()(std::vector<std::pair<double, double>>& items) {
    double total = 0.0;
    for (const auto& item : items) total += item.second;
    if (have_guess_) {
      const double low = guess_ - band_, high = guess_ + band_;
      double below = 0.0;
      band_items_.clear();
      for (const auto& item : items) {
        if (item.first < low)
          below += item.second;
        else if (item.first <= high)
          band_items_.push_back(item);
      }
      double inside = 0.0;
      for (const auto& item : band_items_) inside += item.second;
      if (below < 0.5 * total && below + inside >= 0.5 * total) {
        std::sort(band_items_.begin(), band_items_.end());
        double cumulative = below;
        for (const auto& item : band_items_) {
          cumulative += item.second;
          if (cumulative >= 0.5 * total) return remember(item.first);
        }
      }
    }
    return remember(weighted_median(items));
  }

 private:
  double remember(double value) {
    // The next δ's median is usually within a few times the last change.
    band_ = have_guess_ ? std::max(4.0 * std::abs(value - guess_), 1e-9 * std::abs(value))
                        : 1e-3 * std::abs(value);
    guess_ = value;
    have_guess_ = true;
    return value;
  }
  bool have_guess_ = false;
  double guess_ = 0.0, band_ = 0.0;
  std::vector<std::pair<double, double>> band_items_;
};

class Misfit {
 public:
  Misfit(std::span<const double> force, std::span<const double> rate, double step, std::size_t low,
         std::size_t high)
      : force_(force), rate_(rate), step_(step), low_(low), high_(high) {
    items_.reserve(high - low + 1);
  }

  // Σ|F_i − c ℰ(x_i − δ)| with the l1-optimal c; `scale` receives c.
  double operator()(double delta, double& scale) {
    // x_i − δ falls between samples j = i − k − 1 and j + 1 at the same fraction t for every i.
    const double shift = delta / step_;
    const double whole = std::ceil(shift);
    const double t = whole - shift;  // in [0, 1)
    const auto k = static_cast<std::ptrdiff_t>(whole);
    items_.clear();
    shifted_.resize(high_ - low_ + 1);
    for (std::size_t i = low_; i <= high_; ++i) {
      const auto j = std::clamp<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(i) - k, 0,
                                                static_cast<std::ptrdiff_t>(rate_.size()) - 2);
      const auto ju = static_cast<std::size_t>(j);
      const double r = rate_[ju] + t * (rate_[ju + 1] - rate_[ju]);
      shifted_[i - low_] = r;
      if (r != 0.0) items_.emplace_back(force_[i] / r, std::abs(r));
    }
    scale = items_.empty() ? 0.0 : median_(items_);
    double sum = 0.0;
    for (std::size_t i = low_; i <= high_; ++i) sum += std::abs(force_[i] - scale * shifted_[i - low_]);
    return sum;
  }

 private:
  std::span<const double> force_, rate_;
  double step_;
  std::size_t low_, high_;
  std::vector<std::pair<double, double>> items_;
  std::vector<double> shifted_;
  WeightedMedian median_;
};

double quantile(const std::vector<double>& grid, const std::vector<double>& cdf, double p) {
  const auto it = std::lower_bound(cdf.begin(), cdf.end(), p);
  if (it == cdf.begin()) return grid.front();
  if (it == cdf.end()) return grid.back();
  const std::size_t k = static_cast<std::size_t>(it - cdf.begin());
  const double span = cdf[k] - cdf[k - 1];
  const double t = span > 0.0 ? (p - cdf[k - 1]) / span : 0.0;
  return grid[k - 1] + t * (grid[k] - grid[k - 1]);
}

// The summation window (the force peak down to 1 − window_drop of its height), the force noise in
// it and the prior's range of shifts, into `post`; returns the window's first and last sample.
std::pair<std::size_t, std::size_t> set_up_window(double x0, double step, std::span<const double> force_raw,
                                                  std::span<const double> force_filtered,
                                                  std::size_t force_peak, const DelayOptions& options,
                                                  DelayPosterior& post) {
  const std::size_t n = force_raw.size();
  const double level = force_filtered[force_peak] * (1.0 - options.window_drop);
  std::size_t low = force_peak, high = force_peak;
  while (low > 0 && force_filtered[low - 1] >= level) --low;
  while (high + 1 < n && force_filtered[high + 1] >= level) ++high;
  post.window_low = x0 + static_cast<double>(low) * step;
  post.window_high = x0 + static_cast<double>(high) * step;
  post.window_samples = high - low + 1;

  // Noise: robust scale and correlation length of the force residual in the window.
  std::vector<double> residual(high - low + 1);
  for (std::size_t i = low; i <= high; ++i) residual[i - low] = force_raw[i] - force_filtered[i];
  post.noise_sigma = options.noise_sigma > 0.0 ? options.noise_sigma : robust_scale(residual);
  post.correlation = correlation_length(residual);
  constexpr double sqrt_half_pi = 1.2533141373155003;
  // A floor keeps noise-free (analytic) curves finite: 1e-12 of the peak force.
  post.misfit_scale = std::max(sqrt_half_pi * post.noise_sigma, 1e-12 * std::abs(force_filtered[force_peak]));

  // Prior: every shift for which ℰ(x_i − δ) stays inside the data, at most the strain to the peak.
  const double x_peak = x0 + static_cast<double>(force_peak) * step;
  const double x_end = x0 + static_cast<double>(n - 1) * step;
  if (options.prior_high > options.prior_low) {
    post.prior_low = options.prior_low;
    post.prior_high = options.prior_high;
  } else {
    post.prior_high = std::min(post.window_low - x0, x_peak - x0);
    post.prior_low = std::max(post.window_high - x_end, -(x_peak - x0));
  }
  post.prior_low = std::max(post.prior_low, post.window_high - x_end);
  post.prior_high = std::min(post.prior_high, post.window_low - x0);
  return {low, high};
}

// The log posterior −Σ|F_i − c ℰ(x_i − δ)| / temperature on a grid: a coarse scan of the whole
// prior, then zooms (401-point grids) onto the region holding the posterior mass (log density
// within 30 of the maximum) until it spans at least 40 grid points; then the final grid of
// `grid_points` over that region.
void zoomed_log_posterior(const Misfit& prototype, double temperature, const DelayPosterior& post,
                          std::size_t grid_points, std::vector<double>& grid,
                          std::vector<double>& log_density) {
  // Grid points are independent: each thread has its own Misfit buffers, and every value is
  // computed the same way whatever the thread count.
  const auto evaluate = [&](double a, double b, std::size_t points) {
    grid.resize(points);
    log_density.resize(points);
    for (std::size_t k = 0; k < points; ++k)
      grid[k] = a + (b - a) * static_cast<double>(k) / static_cast<double>(points - 1);
#pragma omp parallel
    {
      Misfit misfit = prototype;
#pragma omp for schedule(static)
      for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(points); ++k) {
        double scale;
        log_density[static_cast<std::size_t>(k)] =
            -misfit(grid[static_cast<std::size_t>(k)], scale) / temperature;
      }
    }
  };
  constexpr std::size_t coarse = 401;
  evaluate(post.prior_low, post.prior_high, coarse);
  for (int zoom = 0; zoom < 12; ++zoom) {
    const double top = *std::max_element(log_density.begin(), log_density.end());
    std::size_t first = 0, last = grid.size() - 1;
    while (log_density[first] < top - 30.0) ++first;
    while (log_density[last] < top - 30.0) --last;
    const double a = grid[first > 0 ? first - 1 : 0];
    const double b = grid[std::min(last + 1, grid.size() - 1)];
    const bool resolved = last - first >= 40 || (b - a) < 1e-13 * (post.prior_high - post.prior_low);
    if (resolved || zoom == 11) {
      evaluate(a, b, grid_points);
      return;
    }
    evaluate(a, b, coarse);
  }
}

// Normalises the density on the grid (trapezoid rule) into `post` and summarises it: mean, sd, MAP,
// median, the 68 % and 95 % intervals and whether the mass piles up at an end of the prior.
void summarise(const std::vector<double>& grid, const std::vector<double>& log_density,
               DelayPosterior& post) {
  const double top = *std::max_element(log_density.begin(), log_density.end());
  post.delta = grid;
  post.density.resize(grid.size());
  for (std::size_t k = 0; k < grid.size(); ++k) post.density[k] = std::exp(log_density[k] - top);
  std::vector<double> cdf(grid.size(), 0.0);
  for (std::size_t k = 1; k < grid.size(); ++k) {
    cdf[k] = cdf[k - 1] + 0.5 * (post.density[k] + post.density[k - 1]) * (grid[k] - grid[k - 1]);
  }
  const double mass = cdf.back();
  if (mass > 0.0) {
    for (auto& d : post.density) d /= mass;
    for (auto& c : cdf) c /= mass;
  }
  double mean = 0.0, second = 0.0;
  for (std::size_t k = 1; k < grid.size(); ++k) {
    const double h = grid[k] - grid[k - 1];
    mean += 0.5 * h * (grid[k] * post.density[k] + grid[k - 1] * post.density[k - 1]);
    second +=
        0.5 * h * (grid[k] * grid[k] * post.density[k] + grid[k - 1] * grid[k - 1] * post.density[k - 1]);
  }
  const std::size_t best = static_cast<std::size_t>(std::max_element(log_density.begin(), log_density.end()) -
                                                    log_density.begin());
  post.map = grid[best];
  post.mean = mass > 0.0 ? mean : post.map;
  post.sd = post.unscaled_sd = mass > 0.0 ? std::sqrt(std::max(0.0, second - mean * mean)) : 0.0;
  post.median = quantile(grid, cdf, 0.5);
  post.ci68_low = quantile(grid, cdf, 0.15865525393145707);
  post.ci68_high = quantile(grid, cdf, 0.8413447460685429);
  post.ci95_low = quantile(grid, cdf, 0.025);
  post.ci95_high = quantile(grid, cdf, 0.975);
  const double tolerance = 1e-9 * (post.prior_high - post.prior_low);
  post.at_prior_bound =
      (grid.front() <= post.prior_low + tolerance && post.density.front() > 1e-3 * post.density[best]) ||
      (grid.back() >= post.prior_high - tolerance && post.density.back() > 1e-3 * post.density[best]);
}

}  // namespace

DelayPosterior infer_delay(double x0, double step, std::span<const double> force_raw,
                           std::span<const double> force_filtered, std::span<const double> energy_rate,
                           std::size_t force_peak, const DelayOptions& options) {
  assert(force_raw.size() >= 2 && force_filtered.size() == force_raw.size() &&
         energy_rate.size() == force_raw.size() && force_peak < force_raw.size());
  DelayPosterior post;
  const auto [low, high] = set_up_window(x0, step, force_raw, force_filtered, force_peak, options, post);
  Misfit misfit(force_raw, energy_rate, step, low, high);
  std::vector<double> grid, log_density;
  zoomed_log_posterior(misfit, post.misfit_scale * post.correlation, post, options.grid_points, grid,
                       log_density);
  summarise(grid, log_density, post);
  misfit(post.map, post.scale_at_map);
  return post;
}

}  // namespace rupture::analysis
