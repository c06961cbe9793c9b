#include "analysis/peak_fit.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>

namespace rupture::analysis {

PeakFit fit_peak(std::span<const double> x, std::span<const double> y, double noise, double correlation,
                 const PeakFitOptions& options, std::string_view x_unit) {
  PeakFit fit;
  const auto strain = [&](double value) {
    return fmt::format("{:.6g}{}{}", value, x_unit.empty() ? "" : " ", x_unit);
  };
  const std::size_t n = y.size();
  if (n < 2 * options.min_side + 1) {
    fit.problem = fmt::format("only {} samples, a peak fit needs {}", n, 2 * options.min_side + 1);
    fit.cut_short = true;
    return fit;
  }
  const std::size_t top = static_cast<std::size_t>(std::max_element(y.begin(), y.end()) - y.begin());
  fit.index = top;
  if (top < options.min_side || top + options.min_side >= n) {
    fit.cut_short = top >= options.min_side;
    fit.problem = fmt::format("the maximum lies at the {} of the data (x = {})",
                              top < options.min_side ? "start" : "end", strain(x[top]));
    return fit;
  }
  const double level = y[top] - options.drop * std::abs(y[top]);
  std::size_t low = top, high = top;
  while (low > 0 && (y[low - 1] >= level || top - low < options.min_side)) --low;
  while (high + 1 < n && (y[high + 1] >= level || high - top < options.min_side)) ++high;
  fit.points = high - low + 1;
  fit.window_low = x[low];
  fit.window_high = x[high];
  // Cubic in t = (x - x_top) / half_width, so the normal equations stay well conditioned.
  const double centre = x[top];
  const double half_width = std::max(x[high] - centre, centre - x[low]);
  const auto count = static_cast<Eigen::Index>(fit.points);
  Eigen::MatrixXd design(count, 4);
  Eigen::VectorXd values(count);
  for (Eigen::Index r = 0; r < count; ++r) {
    const double t = (x[low + static_cast<std::size_t>(r)] - centre) / half_width;
    design.row(r) << 1.0, t, t * t, t * t * t;
    values(r) = y[low + static_cast<std::size_t>(r)];
  }
  const Eigen::Vector4d a = design.colPivHouseholderQr().solve(values);
  // Stationary points a1 + 2 a2 t + 3 a3 t^2 = 0 with negative curvature; take the one nearest t = 0.
  double best_t = 0.0;
  bool have = false;
  const auto consider = [&](double t) {
    if (2.0 * a(2) + 6.0 * a(3) * t < 0.0 && std::abs(t) <= 1.0 &&
        (!have || std::abs(t) < std::abs(best_t))) {
      best_t = t;
      have = true;
    }
  };
  if (std::abs(a(3)) < 1e-14 * (std::abs(a(1)) + std::abs(a(2)))) {
    if (a(2) != 0.0) consider(-a(1) / (2.0 * a(2)));
  } else {
    const double disc = a(2) * a(2) - 3.0 * a(1) * a(3);
    if (disc >= 0.0) {
      const double root = std::sqrt(disc);
      // Numerically stable pair of roots of 3 a3 t^2 + 2 a2 t + a1.
      const double q = -(a(2) + std::copysign(root, a(2)));
      if (q != 0.0) {
        consider(q / (3.0 * a(3)));
        consider(a(1) / q);
      }
    }
  }
  if (!have) {
    fit.problem = fmt::format("no maximum of the cubic fit within x = [{:.6g}, {}]", fit.window_low,
                              strain(fit.window_high));
    return fit;
  }
  const double t = best_t;
  fit.found = true;
  fit.x = centre + t * half_width;
  fit.value = a(0) + t * (a(1) + t * (a(2) + t * a(3)));
  // Covariance noise^2 * correlation * (D^T D)^-1; x* moves by -δp'(t*) / p''(t*).
  const Eigen::Matrix4d inverse = (design.transpose() * design).inverse();
  const double variance_scale = noise * noise * std::max(1.0, correlation);
  const Eigen::Vector4d slope_gradient(0.0, 1.0, 2.0 * t, 3.0 * t * t);
  const Eigen::Vector4d value_gradient(1.0, t, t * t, t * t * t);
  const double curvature = 2.0 * a(2) + 6.0 * a(3) * t;
  fit.x_error = half_width * std::sqrt(variance_scale * slope_gradient.dot(inverse * slope_gradient)) /
                std::abs(curvature);
  fit.value_error = std::sqrt(variance_scale * value_gradient.dot(inverse * value_gradient));
  return fit;
}

namespace {

struct CornerLines {
  double residual = 0.0;
  Eigen::Vector3d coefficients;  // c, a, b
};

CornerLines corner_lines(std::span<const double> x, std::span<const double> y, double k) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Eigen::Vector3d basis(1.0, std::min(x[i] - k, 0.0), std::max(x[i] - k, 0.0));
    normal += basis * basis.transpose();
    right += basis * y[i];
  }
  CornerLines lines;
  lines.coefficients = normal.ldlt().solve(right);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double fitted = lines.coefficients(0) + lines.coefficients(1) * std::min(x[i] - k, 0.0) +
                          lines.coefficients(2) * std::max(x[i] - k, 0.0);
    lines.residual += (y[i] - fitted) * (y[i] - fitted);
  }
  return lines;
}

}  // namespace

PeakFit fit_corner(std::span<const double> x, std::span<const double> y) {
  PeakFit fit;
  constexpr std::size_t side = 3, between = 8;
  if (x.size() < 2 * side + 1) {
    fit.problem = fmt::format("only {} samples, a corner fit needs {}", x.size(), 2 * side + 1);
    return fit;
  }
  fit.points = x.size();
  fit.window_low = x.front();
  fit.window_high = x.back();
  // The residual is smooth in k between samples: a scan at an eighth of the spacing, then Brent's
  // method within one scan step of the best.
  const std::size_t intervals = x.size() - 2 * side + 1;
  const double first = x[side - 1], last = x[x.size() - side];
  const double scan = (last - first) / static_cast<double>(intervals * between);
  double best_k = first, best_residual = corner_lines(x, y, first).residual;
  for (std::size_t i = 1; i <= intervals * between; ++i) {
    const double k = first + scan * static_cast<double>(i);
    const double residual = corner_lines(x, y, k).residual;
    if (residual < best_residual) {
      best_residual = residual;
      best_k = k;
    }
  }
  const auto refined = boost::math::tools::brent_find_minima(
      [&](double k) { return corner_lines(x, y, k).residual; }, std::max(first, best_k - scan),
      std::min(last, best_k + scan), 40);
  const double k = refined.second < best_residual ? refined.first : best_k;
  if (k - first < 0.5 * scan || last - k < 0.5 * scan) {
    fit.problem = "the corner lies at the end of the window";
    fit.cut_short = true;
    return fit;
  }
  const CornerLines lines = corner_lines(x, y, k);
  if (!(lines.coefficients(1) > 0.0 && lines.coefficients(2) < 0.0)) {
    fit.problem = "the two lines do not meet at a maximum";
    return fit;
  }
  fit.found = true;
  fit.corner = true;
  fit.x = k;
  fit.value = lines.coefficients(0);
  fit.left_slope = lines.coefficients(1);
  fit.right_slope = lines.coefficients(2);
  fit.index = static_cast<std::size_t>(std::lower_bound(x.begin(), x.end(), k) - x.begin());
  if (fit.index > 0 && k - x[fit.index - 1] < x[fit.index] - k) --fit.index;
  return fit;
}

std::vector<std::size_t> significant_maxima(std::span<const double> y, double min_prominence) {
  // Reduce the curve to its alternating extrema (plateaus count once), then measure each
  // maximum's prominence along that short list.
  struct Extremum {
    std::size_t index;
    double value;
    bool is_max;
  };
  std::vector<Extremum> extrema;
  const std::size_t n = y.size();
  if (n == 0) return {};
  int direction = 0;  // +1 rising, -1 falling
  extrema.push_back({0, y[0], false});
  for (std::size_t i = 1; i < n; ++i) {
    if (y[i] == y[i - 1]) continue;
    const int now = y[i] > y[i - 1] ? 1 : -1;
    if (direction == 0) {
      extrema.front().is_max = now < 0;
    } else if (now != direction) {
      extrema.push_back({i - 1, y[i - 1], direction > 0});
    }
    direction = now;
  }
  extrema.push_back({n - 1, y[n - 1], direction > 0});
  std::vector<std::size_t> result;
  for (std::size_t k = 0; k < extrema.size(); ++k) {
    if (!extrema[k].is_max) continue;
    const double height = extrema[k].value;
    // SciPy's definition: walk each way until a higher sample (or the end); the base is the higher
    // of the two lowest points met.
    double left_low = height, right_low = height;
    for (std::size_t j = k; j-- > 0 && extrema[j].value <= height;)
      left_low = std::min(left_low, extrema[j].value);
    for (std::size_t j = k + 1; j < extrema.size() && extrema[j].value <= height; ++j) {
      right_low = std::min(right_low, extrema[j].value);
    }
    const double base = std::max(left_low, right_low);
    if (height - base >= min_prominence) result.push_back(extrema[k].index);
  }
  return result;
}

}  // namespace rupture::analysis
