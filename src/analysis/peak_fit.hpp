// analysis/peak_fit: where a noisy maximum is — a cubic least-squares fit around the largest sample
// and its stationary point (paper section 4, Figure 4) — and how many significant maxima a curve
// has. Not: filtering (the input is usually already filtered) or acceptance decisions.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rupture::analysis {

struct PeakFitOptions {
  // The fit window is the contiguous run of samples around the largest one with
  // y >= y_max - drop * |y_max|, so it follows the width of the peak; at least `min_side` samples
  // on each side of the maximum.
  double drop = 0.05;
  std::size_t min_side = 3;
};

struct PeakFit {
  bool found = false;
  std::string problem;                         // why not found
  double x = 0.0, value = 0.0;                 // stationary point of the cubic and the cubic's value there
  double x_error = 0.0, value_error = 0.0;     // 1-sigma, from the fit's covariance (see fit_peak)
  double window_low = 0.0, window_high = 0.0;  // strain range of the fit
  std::size_t points = 0;                      // samples in the fit
  std::size_t index = 0;                       // index of the largest sample
  bool cut_short = false;  // not found because the data ends too soon: too few samples, or the largest
                           // within min_side of the end
  bool corner = false;     // x and value from fit_corner, not the cubic
  double left_slope = 0.0, right_slope = 0.0;  // fit_corner: the two lines' slopes (y per x)
};

// Fits a cubic to (x, y) around the largest y. `noise` is the per-sample standard deviation of the
// unfiltered data and `correlation` its correlation length in samples (filters::correlation_length):
// the errors are those of a least-squares fit to data with that noise, inflated by the correlation
// length (consecutive samples are not independent). x must be increasing; `x_unit` names its unit in
// the problem's text.
PeakFit fit_peak(std::span<const double> x, std::span<const double> y, double noise, double correlation,
                 const PeakFitOptions& options = {}, std::string_view x_unit = {});

// Fits a corner to (x, y): the continuous two-line least-squares fit y = c + a min(x - k, 0) +
// b max(x - k, 0), its corner k sought over the interior (at least three samples on each side).
// Found where the left line rises and the right one falls, the corner inside the scanned range (at
// either end of it one line would rest on three samples): x = k, value = c, index the sample nearest k,
// the slopes a and b, `corner` set. For a maximum where the curve turns at an angle, which a cubic over it
// puts on the shallower side (docs/analysis.md, "Known answers with a DEM-like top").
PeakFit fit_corner(std::span<const double> x, std::span<const double> y);

// Indices of the local maxima of y whose topographic prominence (height above the higher of the
// two lowest points separating it from any higher sample, or from the ends) is at least
// `min_prominence`, in increasing index order.
std::vector<std::size_t> significant_maxima(std::span<const double> y, double min_prominence);

}  // namespace rupture::analysis
