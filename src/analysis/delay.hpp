// analysis/delay: the Bayesian estimate of the delay δ_x = x_c − x_p between the energy-rate and the
// force maxima (paper eqs. 25–27). Not: finding the peaks themselves (peak_fit) or filtering.
//
// Model: around the force peak F(x_i) ≈ c·ℰ(x_i − δ) (the paper writes ℰ(x + δ); with that sign δ
// would be x_p − x_c, so we shift ℰ forward to make δ = x_c − x_p positive for the FBM).
// Posterior σ(δ) ∝ f(δ) exp(−Σ_i |F_i − c(δ) ℰ(x_i − δ)| / (s τ)), where
//   - F_i are the unfiltered (resampled) forces at the samples where the filtered force is within
//     `window_drop` of its maximum, ℰ is the filtered energy rate, linearly interpolated;
//   - c(δ) is the l1-optimal scale for each δ (a weighted median of F_i/ℰ_i with weights |ℰ_i|),
//     i.e. the profile posterior over c;
//   - s = sqrt(π/2)·σ̂ with σ̂ the robust scale of the force residual (raw − filtered) in the
//     window: for Gaussian noise this makes the l1 posterior's width equal to the l1 estimator's
//     sampling spread (sandwich calibration; the naive Laplace scale σ̂·sqrt(2/π) gives intervals
//     too narrow by sqrt(π/2)); τ ≥ 1 is the residual's correlation length, so oversampled
//     (correlated) data does not count as independent evidence;
//   - f is uniform on [prior_low, prior_high], by default as wide as the data allows on both
//     sides of zero, so negative δ is always admissible and positivity is a finding.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rupture::analysis {

struct DelayOptions {
  double window_drop = 0.2;                  // misfit summed where F_filtered >= (1 - window_drop) F_max
  std::size_t grid_points = 2001;            // points of the final posterior grid
  double prior_low = 0.0, prior_high = 0.0;  // strain units; equal values = automatic
  double noise_sigma = 0.0;                  // force noise σ; 0 = estimate from the residual
};

struct DelayPosterior {
  std::vector<double> delta, density;  // grid (strain units) and normalised density (1/strain unit)
  double map = 0.0, mean = 0.0, median = 0.0;
  // sd: one standard deviation as reported, scaled as the 68 % interval is (half its width where it is
  // symmetric); unscaled_sd: the same before any interval factor, which the acceptance rule reads.
  double sd = 0.0, unscaled_sd = 0.0;
  double ci68_low = 0.0, ci68_high = 0.0, ci95_low = 0.0, ci95_high = 0.0;  // equal-tailed
  double prior_low = 0.0, prior_high = 0.0;
  double noise_sigma = 0.0, misfit_scale = 0.0, correlation = 1.0;  // σ̂, s, τ
  double scale_at_map = 0.0;                                        // c(δ_MAP)
  double window_low = 0.0, window_high = 0.0;                       // strain range of the misfit sum
  std::size_t window_samples = 0;
  bool at_prior_bound = false;  // posterior mass reaches an end of the prior range
};

// x_i = x0 + i·step for all three curves. `force_peak` is the index of the filtered force maximum.
DelayPosterior infer_delay(double x0, double step, std::span<const double> force_raw,
                           std::span<const double> force_filtered, std::span<const double> energy_rate,
                           std::size_t force_peak, const DelayOptions& options = {});

}  // namespace rupture::analysis
