// analysis/filters: the zero-phase low-pass filters applied to loading curves, the Savitzky–Golay
// derivative, and the noise statistics that choose their strength. Not: resampling or peak logic.
// Both filters follow SciPy's conventions exactly (savgol_filter mode='interp'; butter + sosfiltfilt
// with padtype='odd' and the default pad length) so that tests compare against SciPy's output.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace rupture::analysis {

// --- Savitzky–Golay ---------------------------------------------------------------------------
// Weights w[j], j = 0..window-1, such that sum_j w[j] y[j] is the `deriv`-th derivative (per sample
// spacing) at window position `position` of the degree-`order` least-squares polynomial through
// the window. Requires order < window and deriv <= order.
std::vector<double> savgol_coefficients(int window, int order, int deriv, double position);

// The Savitzky–Golay filter of `y` (sample spacing `delta`): interior points use the centred
// weights, the first and last window/2 points the polynomial fitted to the first/last window
// (SciPy's mode='interp'). window must be odd and <= y.size().
std::vector<double> savgol_filter(std::span<const double> y, int window, int order, int deriv = 0,
                                  double delta = 1.0);

// --- Butterworth, second-order sections ---------------------------------------------------------
// One biquad, a0 = 1: y = b0 x + z0, z0 = b1 x - a1 y + z1, z1 = b2 x - a2 y (direct form II transposed).
struct Biquad {
  double b0, b1, b2, a1, a2;
};

// Digital Butterworth low-pass of `order` with cutoff `cutoff` in units of the Nyquist frequency
// (0 < cutoff < 1), designed as SciPy's butter(order, cutoff, output='sos') does (bilinear transform
// with pre-warping; overall gain in the first section).
std::vector<Biquad> butterworth_lowpass(int order, double cutoff);

// Samples added at each end by sosfiltfilt's odd extension (SciPy's default padlen).
std::size_t sosfiltfilt_padding(std::span<const Biquad> sections);

// Forward-backward (zero-phase) filtering as SciPy's sosfiltfilt: odd extension by
// sosfiltfilt_padding() samples, steady-state initial conditions scaled by the first sample.
// Requires y.size() > sosfiltfilt_padding(sections).
std::vector<double> sosfiltfilt(std::span<const Biquad> sections, std::span<const double> y);

// --- noise --------------------------------------------------------------------------------------
// Root-mean-square level of white noise on a smooth curve, from the third differences (which
// cancel any quadratic trend): sigma^2 = mean(Δ³y^2) / 20, the largest 0.5 % left out so that a
// few steps (a sudden drop) do not count as noise.
double noise_from_differences(std::span<const double> y);

// Robust scale of a residual: 1.4826 * median|r| (the standard deviation for Gaussian noise).
double robust_scale(std::span<const double> residual);

// Integrated autocorrelation length of a residual, 1 + 2 sum_k rho_k summed while rho_k > 0.05
// (at most min(n/10, 1000) lags), at least 1: the number of consecutive samples that carry one independent
// sample's worth of information. Used to keep likelihoods and fit errors honest on oversampled data.
double correlation_length(std::span<const double> residual);

// --- the configurable smoothing stage ----------------------------------------------------------
enum class FilterKind { butterworth, savitzky_golay, none };

// Largest Savitzky–Golay smoothing window the automatic choice tries (samples).
inline constexpr int max_auto_savgol_window = 501;

struct FilterSettings {
  FilterKind kind = FilterKind::butterworth;
  int butterworth_order = 4;
  double cutoff = 0.0;    // Nyquist units; 0 = choose from the noise level
  int savgol_window = 0;  // samples (odd); 0 = choose from the noise level
  int savgol_order = 3;
  double discrepancy = 0.1;  // auto choice: allowed excess of the residual variance over sigma^2
};

// Applies the filter. For an automatic setting, picks the strongest smoothing whose residual
// variance mean((y - filtered)^2) stays within (1 + discrepancy) sigma^2 of the noise variance
// estimated by noise_from_differences (Morozov's discrepancy principle): stronger smoothing would
// start to eat the signal. The chosen cutoff/window is written back into `settings`.
std::vector<double> apply_filter(FilterSettings& settings, std::span<const double> y);

// The automatic choice for several curves that must share one filter: the strongest of the
// per-curve choices, so that the noisiest curve sets it (a smooth curve, e.g. E_e beside a noisy F,
// would otherwise leave F unsmoothed; a low-pass that suits F's features suits E_e's, which are no
// narrower). Fills in `settings`.
void choose_shared_filter(FilterSettings& settings, std::span<const std::span<const double>> curves);

// Whether the settings leave the strength to the automatic choice (no cutoff or window given).
bool chooses_own_strength(const FilterSettings& settings);

// The filter of a piece cut short at its end (the loading before a sharp collapse, analysis.cpp): the
// piece is continued past its last sample, for twice edge_samples() samples, by the tangent at its
// end of the least-squares quadratic through its last three edges (the whole piece where it is
// shorter), and filtered with that continuation. The plain padding, an odd extension about the last
// sample, pins the filtered end to that one noisy sample and flips the curve's bend beyond it; a
// straight line through the last edge starts above a concave end and rises at the slope of its
// middle, so a top cut just past its maximum peaked at the cut. At a cut a few percent past the force
// peak that edge reaches x_c and x_p (docs/analysis.md, "The loading's cut end", "x_c of a loading
// cut by a collapse"). Where the filter has an edge of fewer than 3 samples or the piece is shorter
// than twice its edge, the plain filter. The settings' strength must be chosen (not automatic).
std::vector<double> filter_continuing_end(const FilterSettings& settings, std::span<const double> y);

// Caps the smoothing so that the filter averages over no more than `longest_period` samples (a
// Butterworth cutoff of at least 2/longest_period Nyquist units, at most 0.95; a Savitzky–Golay
// window of at most longest_period samples). Used after an automatic choice, whose own floor is a
// share of the whole curve: a curve recorded far past its peak would otherwise be smoothed over a
// width set by how long it was recorded, not by its features.
void limit_smoothing(FilterSettings& settings, double longest_period);

// Raises the smoothing so that the filter averages over at least `shortest_period` samples (a
// Butterworth cutoff of at most 2/shortest_period Nyquist units; a Savitzky–Golay window of at least
// shortest_period samples, at most max_auto_savgol_window). Used after an automatic choice whose rule
// reads the noise of the curves where a derivative of them is measured (analysis.cpp, step 2).
void require_smoothing(FilterSettings& settings, double shortest_period);

// Samples at each end of the data where the filter's output still carries its edge: a
// Butterworth's response to the padding pinned to the first (last) noisy sample decays over about
// 1/cutoff samples; Savitzky–Golay's end polynomial spans half its window; none has no edge. The
// peak search uses it to bound how far an edge transient of ℰ is followed (analysis.cpp).
std::size_t edge_samples(const FilterSettings& settings);

// Minimum number of samples the filter needs.
std::size_t minimum_samples(const FilterSettings& settings);

const char* to_string(FilterKind kind);

}  // namespace rupture::analysis
