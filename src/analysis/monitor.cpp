#include "analysis/monitor.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <span>

#include "analysis/peak_fit.hpp"
#include "fbm/power_law.hpp"
#include "io/quantity.hpp"

namespace rupture::analysis {

namespace {

struct CubicAtCentre {
  double value = 0.0, slope = 0.0, slope_error = 0.0;
};

// Least-squares cubic through (x, y) evaluated at x = centre; slope per unit of x.
CubicAtCentre cubic_at(std::span<const double> x, std::span<const double> y, double centre, double half) {
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = (x[i] - centre) / half;
    const Eigen::Vector4d row(1.0, t, t * t, t * t * t);
    normal += row * row.transpose();
    rhs += row * y[i];
  }
  const Eigen::Matrix4d inverse = normal.inverse();
  const Eigen::Vector4d a = inverse * rhs;
  double residual = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = (x[i] - centre) / half;
    const double r = y[i] - (a(0) + t * (a(1) + t * (a(2) + t * a(3))));
    residual += r * r;
  }
  const double variance = x.size() > 4 ? residual / static_cast<double>(x.size() - 4) : 0.0;
  return {a(0), a(1) / half, std::sqrt(variance * inverse(1, 1)) / half};
}

}  // namespace

Monitor::Monitor(MonitorOptions options) : options_(options) {
  options_.window = std::max<std::size_t>(options_.window, 7);
}

std::optional<Warning> Monitor::add_point(double strain, double force, double energy) {
  strain_.push_back(strain);
  force_.push_back(force);
  energy_.push_back(energy);
  const std::size_t n = strain_.size(), w = options_.window;
  if (n < w) return std::nullopt;
  const std::size_t first = n - w, mid = first + w / 2;
  const double centre = strain_[mid];
  const double half = std::max(strain_[n - 1] - centre, centre - strain_[first]);
  if (!(half > 0.0)) return std::nullopt;
  const std::span<const double> xs(strain_.data() + first, w);
  const auto e = cubic_at(xs, std::span<const double>(energy_.data() + first, w), centre, half);
  const auto f = cubic_at(xs, std::span<const double>(force_.data() + first, w), centre, half);
  centre_.push_back(centre);
  rate_.push_back(e.slope);
  force_smooth_.push_back(f.value);
  energy_smooth_.push_back(e.value);
  rate_error_ = e.slope_error;
  const std::size_t k = rate_.size() - 1;
  if (rate_[k] > rate_[rate_top_]) {
    rate_top_ = k;
    below_ = 0;
  } else if (rate_[k] < (1.0 - options_.drop) * rate_[rate_top_]) {
    ++below_;
  } else {
    below_ = 0;
  }
  if (f.slope <= 0.0 && !warning_) {
    // Once the force has fallen for a while, a late confirmation would be no warning at all.
    if (force_smooth_[k] <
        (1.0 - options_.drop) * *std::max_element(force_smooth_.begin(), force_smooth_.end())) {
      force_peaked_ = true;
    }
  }
  if (warning_ || force_peaked_ || below_ < options_.confirm || f.slope <= 0.0 || rate_top_ == 0)
    return std::nullopt;
  // Confirmed: x_p and ℰ_max from a cubic fit to the ℰ history around its maximum.
  const auto fit = fit_peak(centre_, rate_, rate_error_, static_cast<double>(w));
  if (!fit.found) return std::nullopt;
  Warning warning;
  warning.sample = n - 1;
  warning.strain = strain;
  warning.force = force;
  warning.x_p = fit.x;
  warning.x_p_error = fit.x_error;
  warning.Erate_max = fit.value;
  warning.Erate_max_error = fit.value_error;
  using namespace fbm::power_law;
  const double x_p_low = fit.x - options_.sigmas * fit.x_error,
               x_p_high = fit.x + options_.sigmas * fit.x_error;
  // r(α) = x_c/x_p decreases with α.
  warning.x_c = {x_p_low * critical_to_precursor_ratio(options_.alpha_high),
                 x_p_high * critical_to_precursor_ratio(options_.alpha_low)};
  double ratio_low = 1e300, ratio_high = -1e300;
  for (int i = 0; i <= 200; ++i) {
    const double alpha = options_.alpha_low + (options_.alpha_high - options_.alpha_low) * i / 200.0;
    ratio_low = std::min(ratio_low, energy_ratio(alpha));
    ratio_high = std::max(ratio_high, energy_ratio(alpha));
  }
  const double rate_low = fit.value - options_.sigmas * fit.value_error;
  const double rate_high = fit.value + options_.sigmas * fit.value_error;
  warning.E_max = {ratio_low * x_p_low * rate_low, ratio_high * x_p_high * rate_high};
  warning.in_time = strain < warning.x_c.low;
  const double lag_rows = static_cast<double>(w / 2 + options_.confirm);
  warning.max_row_spacing = std::max(0.0, warning.x_c.low - warning.x_p) / lag_rows;
  warning_ = warning;
  return warning;
}

MonitorSummary Monitor::summary() const {
  MonitorSummary s;
  s.samples = strain_.size();
  s.warning = warning_;
  s.force_peaked_before_warning = force_peaked_;
  if (centre_.size() < 8) return s;
  const auto force_fit = fit_peak(centre_, force_smooth_, 0.0, 1.0);
  const auto energy_fit = fit_peak(centre_, energy_smooth_, 0.0, 1.0);
  if (force_fit.found) s.x_c = force_fit.x;
  if (energy_fit.found) s.E_max = energy_fit.value;
  if (warning_ && s.x_c) {
    s.lead = *s.x_c - warning_->strain;
    s.x_c_held = warning_->x_c.contains(*s.x_c);
  }
  if (warning_ && s.E_max) s.E_max_held = warning_->E_max.contains(*s.E_max);
  return s;
}

nlohmann::json to_json(const MonitorSummary& s, const std::string& strain_unit,
                       const std::string& energy_unit) {
  nlohmann::json j = {{"samples", s.samples}};
  if (s.warning) {
    const auto& w = *s.warning;
    const std::string rate_unit = io::unit_ratio(energy_unit, strain_unit);
    j["warning"] = {{"sample", w.sample},
                    {"strain", io::quantity(w.strain, strain_unit)},
                    {"x_p", io::quantity(w.x_p, w.x_p_error, strain_unit)},
                    {"Erate_max", io::quantity(w.Erate_max, w.Erate_max_error, rate_unit)},
                    {"x_c_predicted", io::quantity({w.x_c.low, w.x_c.high}, strain_unit)},
                    {"E_max_predicted", io::quantity({w.E_max.low, w.E_max.high}, energy_unit)},
                    {"in_time", w.in_time},
                    {"max_row_spacing_for_a_timely_warning", io::quantity(w.max_row_spacing, strain_unit)}};
  } else {
    j["warning"] = nullptr;
  }
  const auto optional = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  j["force_peaked_before_warning"] = s.force_peaked_before_warning;
  j["x_c_observed"] = io::quantity(s.x_c, strain_unit);
  j["E_max_observed"] = io::quantity(s.E_max, energy_unit);
  j["lead"] = io::quantity(s.lead, strain_unit);
  j["x_c_held"] = optional(s.x_c_held);
  j["E_max_held"] = optional(s.E_max_held);
  return j;
}

}  // namespace rupture::analysis
