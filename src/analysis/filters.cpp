#include "analysis/filters.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <numeric>

namespace rupture::analysis {

namespace {

double factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f *= i;
  return f;
}

double median_in_place(std::vector<double>& v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  double m = *mid;
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), mid));
  return m;
}

double mean_square_difference(std::span<const double> a, std::span<const double> b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum / static_cast<double>(a.size());
}

int odd_at_least(int w) { return w % 2 == 0 ? w + 1 : w; }

// Filters with the current settings (no automatic choice).
std::vector<double> filter_with(const FilterSettings& s, std::span<const double> y) {
  switch (s.kind) {
    case FilterKind::butterworth: {
      const auto sections = butterworth_lowpass(s.butterworth_order, s.cutoff);
      return sosfiltfilt(sections, y);
    }
    case FilterKind::savitzky_golay:
      return savgol_filter(y, s.savgol_window, s.savgol_order);
    case FilterKind::none:
      break;
  }
  return {y.begin(), y.end()};
}

// Automatic strength for one curve; returns the chosen cutoff (Butterworth) or window (SG).
double choose_strength(const FilterSettings& base, std::span<const double> y) {
  const double sigma = noise_from_differences(y);
  const double bound = (1.0 + base.discrepancy) * sigma * sigma;
  FilterSettings s = base;
  const auto acceptable = [&](double strength) {
    if (s.kind == FilterKind::butterworth)
      s.cutoff = strength;
    else
      s.savgol_window = static_cast<int>(strength);
    return mean_square_difference(y, filter_with(s, y)) <= bound;
  };
  const double n = static_cast<double>(y.size());
  if (base.kind == FilterKind::butterworth) {
    // Cutoffs from 0.95 (almost no smoothing) down to a period of n/4 samples.
    double mild = 0.95, strong = std::min(0.95, 8.0 / n);
    if (acceptable(strong)) return strong;
    if (!acceptable(mild)) return mild;
    for (int iteration = 0; iteration < 30; ++iteration) {
      const double mid = std::sqrt(mild * strong);
      (acceptable(mid) ? mild : strong) = mid;
    }
    return mild;
  }
  // Savitzky–Golay windows from the smallest useful one up to a quarter of the curve, at most
  // max_auto_savgol_window (the cost is samples x window per trial).
  int mild = odd_at_least(base.savgol_order + 2);
  int strong = std::max(mild, std::min(max_auto_savgol_window, odd_at_least(static_cast<int>(n / 4) - 1)));
  if (acceptable(strong)) return strong;
  if (!acceptable(mild)) return mild;
  while (strong - mild > 2) {
    const int mid = odd_at_least((mild + strong) / 2 - 1);
    if (mid <= mild || mid >= strong) break;
    (acceptable(mid) ? mild : strong) = mid;
  }
  return mild;
}

}  // namespace

std::vector<double> savgol_coefficients(int window, int order, int deriv, double position) {
  assert(order < window && deriv <= order && deriv >= 0);
  // Scaled abscissa keeps the Vandermonde matrix well conditioned for long windows.
  const double scale = std::max(1.0, 0.5 * (window - 1));
  Eigen::MatrixXd vandermonde(window, order + 1);
  for (int j = 0; j < window; ++j) {
    const double t = (j - position) / scale;
    double power = 1.0;
    for (int k = 0; k <= order; ++k, power *= t) vandermonde(j, k) = power;
  }
  // Row `deriv` of the pseudo-inverse R⁻¹Qᵀ (thin QR, V full column rank) maps data to the
  // polynomial coefficient of t^deriv: that row is Q·R⁻ᵀe_deriv. Only the thin factors are formed,
  // O(window·order²); the full pseudo-inverse costs O(window²), which long filter edges cannot afford.
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(vandermonde);
  const Eigen::MatrixXd upper = qr.matrixQR().topRows(order + 1).triangularView<Eigen::Upper>();
  Eigen::VectorXd row = Eigen::VectorXd::Unit(order + 1, deriv);
  upper.transpose().triangularView<Eigen::Lower>().solveInPlace(row);
  Eigen::VectorXd padded = Eigen::VectorXd::Zero(window);
  padded.head(order + 1) = row;
  const Eigen::VectorXd pseudo_inverse_row = qr.householderQ() * padded;
  const double factor = factorial(deriv) / std::pow(scale, deriv);
  std::vector<double> weights(static_cast<std::size_t>(window));
  for (int j = 0; j < window; ++j) weights[static_cast<std::size_t>(j)] = factor * pseudo_inverse_row(j);
  return weights;
}

std::vector<double> savgol_filter(std::span<const double> y, int window, int order, int deriv, double delta) {
  assert(window % 2 == 1 && static_cast<std::size_t>(window) <= y.size());
  const std::size_t n = y.size(), w = static_cast<std::size_t>(window), half = w / 2;
  const double unit = std::pow(delta, -deriv);
  std::vector<double> out(n);
  const auto centre = savgol_coefficients(window, order, deriv, static_cast<double>(half));
  for (std::size_t i = half; i + half < n; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < w; ++j) sum += centre[j] * y[i - half + j];
    out[i] = sum * unit;
  }
  // Edges: the polynomial fitted to the first (last) window, evaluated at each edge sample.
  for (std::size_t i = 0; i < half; ++i) {
    const auto head = savgol_coefficients(window, order, deriv, static_cast<double>(i));
    const auto tail = savgol_coefficients(window, order, deriv, static_cast<double>(w - half + i));
    double sum_head = 0.0, sum_tail = 0.0;
    for (std::size_t j = 0; j < w; ++j) {
      sum_head += head[j] * y[j];
      sum_tail += tail[j] * y[n - w + j];
    }
    out[i] = sum_head * unit;
    out[n - half + i] = sum_tail * unit;
  }
  return out;
}

std::vector<Biquad> butterworth_lowpass(int order, double cutoff) {
  assert(order >= 1 && cutoff > 0.0 && cutoff < 1.0);
  using complex = std::complex<double>;
  constexpr double pi = 3.14159265358979323846;
  // Analogue prototype poles -exp(i pi m / 2N), m = -N+1, -N+3, ..., N-1, pre-warped for fs = 2.
  const double warped = 4.0 * std::tan(pi * cutoff / 2.0);
  std::vector<complex> poles;
  complex denominator = 1.0;
  for (int m = -order + 1; m <= order - 1; m += 2) {
    const complex analogue = -warped * std::exp(complex(0.0, pi * m / (2.0 * order)));
    denominator *= 4.0 - analogue;
    poles.push_back((4.0 + analogue) / (4.0 - analogue));  // bilinear transform, fs = 2
  }
  const double gain = std::pow(warped, order) * (1.0 / denominator).real();
  // Zeros all at z = -1; pair each pole with its conjugate (poles with Im > 0), real pole alone.
  std::vector<Biquad> sections;
  for (const auto& p : poles) {
    if (p.imag() > 1e-14) sections.push_back({1.0, 2.0, 1.0, -2.0 * p.real(), std::norm(p)});
  }
  if (order % 2 == 1) {
    const auto real_pole = std::min_element(poles.begin(), poles.end(), [](complex a, complex b) {
      return std::abs(a.imag()) < std::abs(b.imag());
    });
    sections.insert(sections.begin(), {1.0, 1.0, 0.0, -real_pole->real(), 0.0});
  }
  sections.front().b0 *= gain;
  sections.front().b1 *= gain;
  sections.front().b2 *= gain;
  return sections;
}

std::size_t sosfiltfilt_padding(std::span<const Biquad> sections) {
  std::size_t first_order_b = 0, first_order_a = 0;
  for (const auto& s : sections) {
    first_order_b += s.b2 == 0.0;
    first_order_a += s.a2 == 0.0;
  }
  return 3 * (2 * sections.size() + 1 - std::min(first_order_b, first_order_a));
}

namespace {

// Runs the cascade over `x` in place, starting each section from its steady state for a constant
// input x[0] (SciPy's sosfilt_zi scaled by the first sample).
void cascade_in_place(std::span<const Biquad> sections, std::vector<double>& x) {
  double input_level = x.front();
  for (const auto& s : sections) {
    // lfilter_zi: solve (I - A^T) z = b[1:] - a[1:] b0 for the steady state of a unit step.
    const double B0 = s.b1 - s.a1 * s.b0, B1 = s.b2 - s.a2 * s.b0;
    double z0 = (B0 + B1) / (1.0 + s.a1 + s.a2) * input_level;
    double z1 = (B1 - s.a2 * (B0 + B1) / (1.0 + s.a1 + s.a2)) * input_level;
    for (double& value : x) {
      const double in = value;
      const double out = s.b0 * in + z0;
      z0 = s.b1 * in - s.a1 * out + z1;
      z1 = s.b2 * in - s.a2 * out;
      value = out;
    }
    input_level *= (s.b0 + s.b1 + s.b2) / (1.0 + s.a1 + s.a2);
  }
}

}  // namespace

std::vector<double> sosfiltfilt(std::span<const Biquad> sections, std::span<const double> y) {
  const std::size_t n = y.size(), pad = sosfiltfilt_padding(sections);
  assert(n > pad);
  std::vector<double> ext(n + 2 * pad);
  for (std::size_t i = 0; i < pad; ++i) {
    ext[i] = 2.0 * y[0] - y[pad - i];
    ext[pad + n + i] = 2.0 * y[n - 1] - y[n - 2 - i];
  }
  std::copy(y.begin(), y.end(), ext.begin() + static_cast<std::ptrdiff_t>(pad));
  cascade_in_place(sections, ext);
  std::reverse(ext.begin(), ext.end());
  cascade_in_place(sections, ext);
  std::reverse(ext.begin(), ext.end());
  return {ext.begin() + static_cast<std::ptrdiff_t>(pad), ext.begin() + static_cast<std::ptrdiff_t>(pad + n)};
}

double noise_from_differences(std::span<const double> y) {
  if (y.size() < 4) return 0.0;
  std::vector<double> third(y.size() - 3);
  for (std::size_t i = 0; i + 3 < y.size(); ++i) {
    const double d = y[i + 3] - 3.0 * y[i + 2] + 3.0 * y[i + 1] - y[i];
    third[i] = d * d;
  }
  // Mean square (so noise that varies along the curve counts as the residual's mean square does),
  // without the largest 0.5 % (steps, e.g. a sudden force drop); 0.956 is the Gaussian mean square
  // kept by that trimming.
  const auto kept = third.size() - third.size() / 200;
  std::nth_element(third.begin(), third.begin() + static_cast<std::ptrdiff_t>(kept - 1), third.end());
  double sum = 0.0;
  for (std::size_t i = 0; i < kept; ++i) sum += third[i];
  return std::sqrt(sum / static_cast<double>(kept) / (20.0 * 0.956));
}

double robust_scale(std::span<const double> residual) {
  std::vector<double> magnitude(residual.size());
  std::transform(residual.begin(), residual.end(), magnitude.begin(), [](double r) { return std::abs(r); });
  return 1.482602218505602 * median_in_place(magnitude);
}

double correlation_length(std::span<const double> residual) {
  const std::size_t n = residual.size();
  if (n < 20) return 1.0;
  const double mean = std::accumulate(residual.begin(), residual.end(), 0.0) / static_cast<double>(n);
  double variance = 0.0;
  for (double r : residual) variance += (r - mean) * (r - mean);
  variance /= static_cast<double>(n);
  if (variance <= 0.0) return 1.0;
  // Long curves: each lag's sum runs over every stride-th sample (at most 10^5 terms) and at most
  // 1000 lags are summed, so the cost stays ~10^8 operations for any length.
  const std::size_t stride = std::max<std::size_t>(1, n / 100000);
  double length = 1.0;
  for (std::size_t lag = 1; lag <= std::min<std::size_t>(n / 10, 1000); ++lag) {
    double sum = 0.0;
    std::size_t terms = 0;
    for (std::size_t i = 0; i + lag < n; i += stride, ++terms)
      sum += (residual[i] - mean) * (residual[i + lag] - mean);
    const double rho = sum / (static_cast<double>(terms) * variance);
    if (rho <= 0.05) break;
    length += 2.0 * rho;
  }
  return length;
}

std::vector<double> apply_filter(FilterSettings& settings, std::span<const double> y) {
  const std::span<const double> curves[] = {y};
  choose_shared_filter(settings, curves);
  return filter_with(settings, y);
}

std::vector<double> filter_continuing_end(const FilterSettings& settings, std::span<const double> y) {
  assert(!chooses_own_strength(settings));
  FilterSettings chosen = settings;
  const std::size_t edge = edge_samples(settings), n = y.size();
  if (edge < 3 || n < 2 * edge) return apply_filter(chosen, y);
  // The tangent at the last sample of the least-squares quadratic through the last three edges (Savitzky–
  // Golay weights of order 2): its value and slope there.
  const std::size_t span = std::min(n, 3 * edge);
  const auto window = static_cast<int>(span);
  const auto value_weights = savgol_coefficients(window, 2, 0, window - 1.0);
  const auto slope_weights = savgol_coefficients(window, 2, 1, window - 1.0);
  double end_value = 0.0, slope = 0.0;
  for (std::size_t j = 0; j < span; ++j) {
    end_value += value_weights[j] * y[n - span + j];
    slope += slope_weights[j] * y[n - span + j];
  }
  std::vector<double> continued(y.begin(), y.end());
  continued.reserve(n + 2 * edge);
  for (std::size_t i = 1; i <= 2 * edge; ++i) continued.push_back(end_value + slope * static_cast<double>(i));
  auto filtered = apply_filter(chosen, continued);
  filtered.resize(n);
  return filtered;
}

bool chooses_own_strength(const FilterSettings& settings) {
  return (settings.kind == FilterKind::butterworth && settings.cutoff <= 0.0) ||
         (settings.kind == FilterKind::savitzky_golay && settings.savgol_window <= 0);
}

void choose_shared_filter(FilterSettings& settings, std::span<const std::span<const double>> curves) {
  if (!chooses_own_strength(settings)) return;
  if (settings.kind == FilterKind::butterworth) {
    double cutoff = 1.0;
    for (auto y : curves) cutoff = std::min(cutoff, choose_strength(settings, y));
    settings.cutoff = cutoff;
  } else {
    int window = 0;
    for (auto y : curves) window = std::max(window, static_cast<int>(choose_strength(settings, y)));
    settings.savgol_window = window;
  }
}

void limit_smoothing(FilterSettings& settings, double longest_period) {
  if (settings.kind == FilterKind::butterworth)
    settings.cutoff = std::max(settings.cutoff, std::min(0.95, 2.0 / longest_period));
  else if (settings.kind == FilterKind::savitzky_golay)
    settings.savgol_window =
        std::max(odd_at_least(settings.savgol_order + 2),
                 std::min(settings.savgol_window, odd_at_least(static_cast<int>(longest_period) - 1)));
}

void require_smoothing(FilterSettings& settings, double shortest_period) {
  if (shortest_period <= 0.0) return;
  if (settings.kind == FilterKind::butterworth)
    settings.cutoff = std::min(settings.cutoff, std::min(0.95, 2.0 / shortest_period));
  else if (settings.kind == FilterKind::savitzky_golay)
    settings.savgol_window = std::max(
        settings.savgol_window,
        std::min(max_auto_savgol_window, odd_at_least(static_cast<int>(std::ceil(shortest_period)))));
}

std::size_t edge_samples(const FilterSettings& settings) {
  switch (settings.kind) {
    case FilterKind::butterworth:
      return settings.cutoff > 0.0 ? static_cast<std::size_t>(std::ceil(1.0 / settings.cutoff)) : 0;
    case FilterKind::savitzky_golay:
      return static_cast<std::size_t>(std::max(settings.savgol_window, 0) / 2);
    case FilterKind::none:
      break;
  }
  return 0;
}

std::size_t minimum_samples(const FilterSettings& settings) {
  switch (settings.kind) {
    case FilterKind::butterworth: {
      const std::size_t sections = static_cast<std::size_t>(settings.butterworth_order + 1) / 2;
      const std::size_t first_order = static_cast<std::size_t>(settings.butterworth_order % 2);
      return 3 * (2 * sections + 1 - first_order) + 1;
    }
    case FilterKind::savitzky_golay:
      return static_cast<std::size_t>(
          std::max(settings.savgol_window, odd_at_least(settings.savgol_order + 2)));
    case FilterKind::none:
      break;
  }
  return 1;
}

const char* to_string(FilterKind kind) {
  switch (kind) {
    case FilterKind::butterworth:
      return "butterworth";
    case FilterKind::savitzky_golay:
      return "savitzky_golay";
    case FilterKind::none:
      return "none";
  }
  return "?";
}

}  // namespace rupture::analysis
