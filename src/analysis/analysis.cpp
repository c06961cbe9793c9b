#include "analysis/analysis.hpp"

#include <algorithm>
#include <cmath>

#include <boost/math/tools/roots.hpp>
#include <fmt/format.h>

#include "core/error.hpp"
#include "fbm/power_law.hpp"

namespace rupture::analysis {

namespace {

int odd_at_least(int w) { return w % 2 == 0 ? w + 1 : w; }

// Finds a column by the user's name or by rupture's default names; throws naming the options.
std::size_t pick_column(const io::CsvTable& table, const std::string& chosen, std::initializer_list<const char*> defaults,
                        const char* option) {
  if (!chosen.empty()) return table.require(chosen);
  for (const char* name : defaults) {
    if (auto c = table.find(name)) return *c;
  }
  std::string available;
  for (const auto& h : table.header) available += (available.empty() ? "" : ", ") + h;
  throw InputError(table.source, fmt::format("no column '{}'", *defaults.begin()),
                   fmt::format("name the column with {} (the header has: {})", option, available));
}

std::vector<double> scaled_column(const io::CsvTable& table, std::size_t c, double scale) {
  std::vector<double> values = table.columns[c];
  for (std::size_t row = 0; row < values.size(); ++row) {
    if (!std::isfinite(values[row])) {
      throw InputError(fmt::format("{}:{}", table.source, table.line_of_row[row]),
                       fmt::format("column {} ('{}'): '{}' is not a finite number", c + 1, table.header[c], values[row]),
                       "remove the row or replace the value by a measured number");
    }
    values[row] *= scale;
  }
  return values;
}

std::string unit_of(const io::CsvTable& table, std::size_t c, const std::string& override_unit) {
  if (!override_unit.empty()) return override_unit;
  const auto unit = io::column_unit(table.header[c]);
  return unit.empty() ? "1" : unit;
}

// Unit of a quotient, e.g. "mJ" / "%" -> "mJ/%"; a dimensionless denominator drops out.
std::string unit_ratio(const std::string& numerator, const std::string& denominator) {
  if (denominator == "1") return numerator;
  return numerator + "/" + (denominator.find('/') != std::string::npos ? "(" + denominator + ")" : denominator);
}

std::string per_strain(const std::string& unit, const std::string& strain_unit) { return unit_ratio(unit, strain_unit); }

// Height of the global maximum above the higher of the lowest points on either side.
double prominence_of_maximum(std::span<const double> y, std::size_t top) {
  const double left = *std::min_element(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(top) + 1);
  const double right = *std::min_element(y.begin() + static_cast<std::ptrdiff_t>(top), y.end());
  return y[top] - std::max(left, right);
}

Measured measured(double value, double error, std::string unit) { return {value, error, std::move(unit)}; }

// α with critical_to_precursor_ratio(α) = ratio (eq. 18), for ratios the power law can give.
std::optional<double> alpha_from_ratio(double ratio) {
  using fbm::power_law::critical_to_precursor_ratio;
  const double lo = -0.999, hi = 1e3;
  const double f_lo = critical_to_precursor_ratio(lo) - ratio, f_hi = critical_to_precursor_ratio(hi) - ratio;
  if (!(f_lo > 0.0 && f_hi < 0.0)) return std::nullopt;
  std::uintmax_t iterations = 200;
  const auto root = boost::math::tools::bisect([&](double a) { return critical_to_precursor_ratio(a) - ratio; }, lo, hi,
                                               boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (root.first + root.second);
}

AlphaEstimate alpha_estimate(const DelayPosterior& delay, const Measured& x_p, const std::optional<Measured>& gamma,
                             const std::optional<Measured>& energy_ratio) {
  AlphaEstimate a;
  a.alpha = alpha_from_ratio(1.0 + delay.mean / x_p.value);
  // Larger δ_x/x_p means smaller α (the ratio decreases with α).
  a.alpha_low = alpha_from_ratio(1.0 + delay.ci68_high / x_p.value);
  a.alpha_high = alpha_from_ratio(1.0 + delay.ci68_low / x_p.value);
  a.gamma_band_low = a.energy_ratio_band_low = 1e300;
  a.gamma_band_high = a.energy_ratio_band_high = -1e300;
  for (int k = 0; k <= 500; ++k) {
    const double alpha = 5.0 * k / 500.0;
    const double g = fbm::power_law::gamma(alpha), r = fbm::power_law::energy_ratio(alpha);
    a.gamma_band_low = std::min(a.gamma_band_low, g);
    a.gamma_band_high = std::max(a.gamma_band_high, g);
    a.energy_ratio_band_low = std::min(a.energy_ratio_band_low, r);
    a.energy_ratio_band_high = std::max(a.energy_ratio_band_high, r);
  }
  // "In the band" allows the measurement's own 2-sigma uncertainty.
  if (gamma) {
    a.gamma_in_band = gamma->value + 2.0 * gamma->error >= a.gamma_band_low && gamma->value - 2.0 * gamma->error <= a.gamma_band_high;
  }
  if (energy_ratio) {
    a.energy_ratio_in_band = energy_ratio->value + 2.0 * energy_ratio->error >= a.energy_ratio_band_low &&
                             energy_ratio->value - 2.0 * energy_ratio->error <= a.energy_ratio_band_high;
  }
  return a;
}

}  // namespace

CurveColumns find_curve_columns(const io::CsvTable& table, const ColumnChoice& choice) {
  CurveColumns c;
  c.strain = pick_column(table, choice.strain, {"strain"}, "--strain");
  c.force = pick_column(table, choice.force, {"force", "force_top"}, "--force");
  c.energy = pick_column(table, choice.energy, {"elastic_energy"}, "--energy");
  c.strain_unit = unit_of(table, c.strain, choice.strain_unit);
  c.force_unit = unit_of(table, c.force, choice.force_unit);
  c.energy_unit = unit_of(table, c.energy, choice.energy_unit);
  return c;
}

Curve select_curve(const io::CsvTable& table, const ColumnChoice& choice) {
  const auto columns = find_curve_columns(table, choice);
  Curve curve;
  curve.source = table.source;
  curve.strain = scaled_column(table, columns.strain, choice.strain_scale);
  curve.force = scaled_column(table, columns.force, choice.force_scale);
  curve.energy = scaled_column(table, columns.energy, choice.energy_scale);
  curve.strain_unit = columns.strain_unit;
  curve.force_unit = columns.force_unit;
  curve.energy_unit = columns.energy_unit;
  curve.strain_column = table.header[columns.strain];
  curve.force_column = table.header[columns.force];
  curve.energy_column = table.header[columns.energy];
  return curve;
}

std::vector<double> select_break_strains(const io::CsvTable& breaks, double scale) {
  return scaled_column(breaks, breaks.require("strain"), scale);
}

std::size_t minimum_rows(const AnalysisOptions& options) {
  // The filter's padding, the derivative window and a peak fit with room on both sides.
  return std::max<std::size_t>({minimum_samples(options.filter), static_cast<std::size_t>(options.derivative_window),
                                4 * options.peak.min_side + 8, 16});
}

AnalysisResult analyze_curve(const Curve& curve, AnalysisOptions options, const std::vector<double>& break_strains) {
  AnalysisResult r;
  r.source = curve.source;
  r.strain_unit = curve.strain_unit;
  r.force_unit = curve.force_unit;
  r.energy_unit = curve.energy_unit;
  const std::size_t needed = minimum_rows(options);
  if (curve.strain.size() < needed) {
    throw InputError(curve.source, fmt::format("{} data rows, the analysis needs at least {}", curve.strain.size(), needed),
                     "give a longer curve (or a weaker filter: --filter none)");
  }
  // 1. Uniform grid.
  const std::span<const double> columns[] = {curve.force, curve.energy};
  UniformCurves grid = resample_uniform(curve.strain, columns, r.resample);
  if (grid.size() < needed) {
    throw InputError(curve.source, fmt::format("{} distinct strains, the analysis needs at least {}", grid.size(), needed),
                     "give a curve with more distinct strain values");
  }
  const std::size_t n = grid.size();
  r.x0 = grid.x0;
  r.step = grid.step;
  std::vector<double> xs(n);
  for (std::size_t i = 0; i < n; ++i) xs[i] = grid.x(i);
  const auto& force = grid.y[0];
  const auto& energy = grid.y[1];

  // 2. One zero-phase filter for both curves.
  const std::span<const double> raw[] = {force, energy};
  choose_shared_filter(options.filter, raw);
  r.filter = options.filter;
  r.filtered_force = apply_filter(r.filter, force);
  r.filtered_energy = apply_filter(r.filter, energy);
  r.force_noise = noise_from_differences(force);
  r.energy_noise = noise_from_differences(energy);

  // 3. ℰ by the cubic Savitzky–Golay derivative; its window follows the filter's smoothing length.
  int window = options.derivative_window;
  if (window <= 0) {
    double length = 7.0;
    if (r.filter.kind == FilterKind::butterworth) length = 0.5 / r.filter.cutoff;
    if (r.filter.kind == FilterKind::savitzky_golay) length = r.filter.savgol_window;
    // At most 101 samples: after the low-pass the curve is smooth on that scale already, and the
    // cost of the derivative grows with its window.
    window = odd_at_least(std::clamp(static_cast<int>(std::lround(length)), 7, std::clamp(static_cast<int>(n / 4), 7, 101)));
  }
  r.derivative_window = odd_at_least(window);
  r.energy_rate = savgol_filter(r.filtered_energy, r.derivative_window, 3, 1, grid.step);

  // 4. Maxima by cubic fits. Noise of each curve: σ̂ and the correlation length of raw − filtered;
  // ℰ's noise is that of the derivative weights applied to E_e's noise, correlated over its window.
  std::vector<double> residual(n);
  for (std::size_t i = 0; i < n; ++i) residual[i] = force[i] - r.filtered_force[i];
  const double force_correlation = correlation_length(residual);
  for (std::size_t i = 0; i < n; ++i) residual[i] = energy[i] - r.filtered_energy[i];
  const double energy_correlation = correlation_length(residual);
  const auto weights = savgol_coefficients(r.derivative_window, 3, 1, r.derivative_window / 2);
  double weight_norm = 0.0;
  for (double w : weights) weight_norm += w * w;
  const double rate_noise = r.energy_noise * std::sqrt(weight_norm) / grid.step;

  r.force_peak = fit_peak(xs, r.filtered_force, r.force_noise, force_correlation, options.peak);
  r.energy_peak = fit_peak(xs, r.filtered_energy, r.energy_noise, energy_correlation, options.peak);
  r.rate_peak = fit_peak(xs, r.energy_rate, rate_noise, std::max<double>(r.derivative_window, energy_correlation), options.peak);
  const std::string rate_unit = per_strain(curve.energy_unit, curve.strain_unit);
  if (r.force_peak->found) {
    r.x_c = measured(r.force_peak->x, r.force_peak->x_error, curve.strain_unit);
    r.F_c = measured(r.force_peak->value, r.force_peak->value_error, curve.force_unit);
  }
  if (r.energy_peak->found) {
    r.x_m = measured(r.energy_peak->x, r.energy_peak->x_error, curve.strain_unit);
    r.E_max = measured(r.energy_peak->value, r.energy_peak->value_error, curve.energy_unit);
  }
  if (r.rate_peak->found) {
    r.x_p = measured(r.rate_peak->x, r.rate_peak->x_error, curve.strain_unit);
    r.Erate_max = measured(r.rate_peak->value, r.rate_peak->value_error, rate_unit);
  }

  // 6a. Acceptance of the peaks (before spending time on the posterior).
  const auto reject = [&](std::string reason) {
    if (r.rejection.empty()) r.rejection = std::move(reason);
  };
  const std::size_t force_top = r.force_peak->index;
  const double F_top = r.filtered_force[force_top];
  const auto maxima = significant_maxima(r.filtered_force, 0.05 * std::abs(F_top));
  r.force_maxima = static_cast<int>(maxima.size());
  if (!r.force_peak->found) {
    reject("force peak: " + r.force_peak->problem);
  } else if (prominence_of_maximum(r.filtered_force, force_top) < options.acceptance.min_prominence * std::abs(F_top)) {
    reject(fmt::format("force peak not pronounced: it rises less than {:g} % of F_c above the curve on either side",
                       100.0 * options.acceptance.min_prominence));
  } else {
    for (std::size_t k : maxima) {
      if (k != force_top && r.filtered_force[k] >= options.acceptance.competing_maximum * F_top) {
        reject(fmt::format("several force maxima of similar height (x = {:.6g} and x = {:.6g} {}): x_c is ambiguous",
                           xs[force_top], xs[k], curve.strain_unit));
        break;
      }
    }
  }
  if (!r.rate_peak->found) {
    reject("energy-rate peak: " + r.rate_peak->problem);
  } else if (prominence_of_maximum(r.energy_rate, r.rate_peak->index) <
             options.acceptance.min_prominence * std::abs(r.energy_rate[r.rate_peak->index])) {
    reject(fmt::format("energy-rate peak not pronounced: it rises less than {:g} % of ℰ_max above the curve on either side",
                       100.0 * options.acceptance.min_prominence));
  }

  // 4-5. δ_x, Γ, A_r, α.
  if (r.x_c && r.x_p) {
    r.delay = infer_delay(grid.x0, grid.step, force, r.filtered_force, r.energy_rate, force_top, options.delay);
    r.delta_x = measured(r.delay->mean, r.delay->sd, curve.strain_unit);
    r.delta_x_direct = measured(r.x_c->value - r.x_p->value, std::hypot(r.x_c->error, r.x_p->error), curve.strain_unit);
    const double delta = r.delay->mean;
    if (r.x_m && delta != 0.0) {
      const double g = (r.x_m->value - r.x_c->value) / delta;
      const double error = std::sqrt((r.x_m->error * r.x_m->error + r.x_c->error * r.x_c->error) / (delta * delta) +
                                     g * g * r.delay->sd * r.delay->sd / (delta * delta));
      r.Gamma = measured(g, error, "1");
    }
    if (r.E_max) {
      const double ratio = r.E_max->value / (r.x_p->value * r.Erate_max->value);
      const auto rel = [](const Measured& m) { return m.value != 0.0 ? m.error / m.value : 0.0; };
      const double error = std::abs(ratio) * std::hypot(rel(*r.E_max), rel(*r.x_p), rel(*r.Erate_max));
      r.A_r = measured(ratio, error, "1");
    }
    r.alpha = alpha_estimate(*r.delay, *r.x_p, r.Gamma, r.A_r);
    if (r.delay->at_prior_bound) {
      reject("δ_x undetermined: the posterior reaches the end of the admissible shifts (the data around the peaks is too short)");
    } else if (r.delay->sd > options.acceptance.max_relative_delay_sd * std::abs(r.x_c->value - grid.x0)) {
      reject(fmt::format("δ_x too uncertain: sd {:.3g} {} exceeds {:g} of x_c", r.delay->sd, curve.strain_unit,
                         options.acceptance.max_relative_delay_sd));
    }
  }

  // 7. Mechanism features and class.
  if (r.x_c) {
    const double x_c = r.x_c->value;
    auto& f = r.features;
    if (curve.strain_unit == "%") f.critical_strain_percent = x_c;
    if (curve.strain_unit == "1") f.critical_strain_percent = 100.0 * x_c;
    if (r.energy_peak->found) {
      const std::size_t top = r.energy_peak->index;
      const double level = 0.9 * r.filtered_energy[top];
      std::size_t lo = top, hi = top;
      while (lo > 0 && r.filtered_energy[lo - 1] >= level) --lo;
      while (hi + 1 < n && r.filtered_energy[hi + 1] >= level) ++hi;
      f.energy_peak_width = (xs[hi] - xs[lo]) / x_c;
    }
    f.force_maxima = r.force_maxima;
    for (std::size_t i = force_top; i < n; ++i) {
      if (r.filtered_force[i] < 0.5 * F_top) {
        f.post_peak_decay = (xs[i] - x_c) / x_c;
        break;
      }
    }
    f.break_spread = break_spread(break_strains, x_c);
    if (r.Gamma) f.gamma = r.Gamma->value;
    r.mechanism = classify(f, options.mechanism);
  }
  r.accepted = r.rejection.empty();
  return r;
}

namespace {

nlohmann::json to_json(const Measured& m) { return {{"value", m.value}, {"error", m.error}, {"unit", m.unit}}; }

template <class T>
nlohmann::json optional_json(const std::optional<T>& v) {
  if (!v) return nullptr;
  if constexpr (std::is_same_v<T, Measured>) return to_json(*v);
  else return *v;
}

nlohmann::json peak_json(const std::optional<PeakFit>& fit, const std::string& unit) {
  if (!fit) return nullptr;
  nlohmann::json j = {{"found", fit->found}, {"window", {fit->window_low, fit->window_high}}, {"window_unit", unit},
                      {"points", fit->points}};
  if (!fit->found) j["problem"] = fit->problem;
  return j;
}

}  // namespace

nlohmann::json to_json(const AnalysisResult& r) {
  nlohmann::json j;
  j["source"] = r.source;
  j["accepted"] = r.accepted;
  j["rejection"] = r.accepted ? nlohmann::json(nullptr) : nlohmann::json(r.rejection);
  j["units"] = {{"strain", r.strain_unit}, {"force", r.force_unit}, {"energy", r.energy_unit}};
  j["resample"] = {{"input_rows", r.resample.input_rows},
                   {"was_sorted", r.resample.was_sorted},
                   {"duplicates_merged", r.resample.duplicates_merged},
                   {"was_uniform", r.resample.was_uniform},
                   {"resampled", r.resample.resampled},
                   {"output_rows", r.resample.output_rows},
                   {"step", {{"value", r.resample.step}, {"unit", r.strain_unit}}}};
  nlohmann::json filter = {{"kind", to_string(r.filter.kind)}, {"applied_to", {"force", "elastic_energy"}},
                           {"zero_phase", true}, {"discrepancy", r.filter.discrepancy}};
  if (r.filter.kind == FilterKind::butterworth) {
    filter["order"] = r.filter.butterworth_order;
    filter["cutoff_nyquist"] = r.filter.cutoff;
    filter["cutoff_per_strain"] = {{"value", r.filter.cutoff / (2.0 * r.step)}, {"unit", unit_ratio("1", r.strain_unit)}};
    filter["method"] = "forward-backward second-order sections, odd padding (sosfiltfilt)";
  } else if (r.filter.kind == FilterKind::savitzky_golay) {
    filter["window_samples"] = r.filter.savgol_window;
    filter["polynomial_order"] = r.filter.savgol_order;
  }
  j["filter"] = filter;
  j["derivative"] = {{"method", "Savitzky-Golay, cubic"}, {"window_samples", r.derivative_window}};
  j["noise"] = {{"force", {{"value", r.force_noise}, {"unit", r.force_unit}}},
                {"elastic_energy", {{"value", r.energy_noise}, {"unit", r.energy_unit}}},
                {"estimator", "rms of third differences / sqrt(20), largest 0.5 % trimmed"}};
  j["x_c"] = optional_json(r.x_c);
  j["F_c"] = optional_json(r.F_c);
  j["x_m"] = optional_json(r.x_m);
  j["E_max"] = optional_json(r.E_max);
  j["x_p"] = optional_json(r.x_p);
  j["Erate_max"] = optional_json(r.Erate_max);
  j["peak_fits"] = {{"force", peak_json(r.force_peak, r.strain_unit)},
                    {"elastic_energy", peak_json(r.energy_peak, r.strain_unit)},
                    {"energy_rate", peak_json(r.rate_peak, r.strain_unit)},
                    {"method", "cubic least squares around the largest sample; stationary point"}};
  if (r.delay) {
    const auto& d = *r.delay;
    j["delta_x"] = {{"value", d.mean}, {"error", d.sd}, {"unit", r.strain_unit},
                    {"map", d.map}, {"mean", d.mean}, {"median", d.median}, {"sd", d.sd},
                    {"ci68", {d.ci68_low, d.ci68_high}}, {"ci95", {d.ci95_low, d.ci95_high}},
                    {"prior", {{"kind", "uniform"}, {"range", {d.prior_low, d.prior_high}}}},
                    {"model", "F(x) = c * Erate(x - delta_x), l1 misfit, c l1-optimal per delta_x (weighted median)"},
                    {"misfit_window", {d.window_low, d.window_high}}, {"misfit_samples", d.window_samples},
                    {"force_noise_sigma", {{"value", d.noise_sigma}, {"unit", r.force_unit}}},
                    {"misfit_scale", {{"value", d.misfit_scale}, {"unit", r.force_unit}}},
                    {"correlation_length_samples", d.correlation},
                    {"scale_at_map", {{"value", d.scale_at_map}, {"unit", unit_ratio(r.force_unit, per_strain(r.energy_unit, r.strain_unit))}}},
                    {"at_prior_bound", d.at_prior_bound},
                    {"posterior", {{"delta", d.delta}, {"density", d.density},
                                   {"delta_unit", r.strain_unit}, {"density_unit", unit_ratio("1", r.strain_unit)}}}};
  } else {
    j["delta_x"] = nullptr;
  }
  j["delta_x_direct"] = optional_json(r.delta_x_direct);
  j["Gamma"] = optional_json(r.Gamma);
  j["A_r"] = optional_json(r.A_r);
  j["alpha"] = {{"from_delta_over_x_p", optional_json(r.alpha.alpha)},
                {"ci68", {optional_json(r.alpha.alpha_low), optional_json(r.alpha.alpha_high)}},
                {"fbm_band", {0.0, 5.0}},
                {"Gamma_band", {r.alpha.gamma_band_low, r.alpha.gamma_band_high}},
                {"A_r_band", {r.alpha.energy_ratio_band_low, r.alpha.energy_ratio_band_high}},
                {"Gamma_in_band", optional_json(r.alpha.gamma_in_band)},
                {"A_r_in_band", optional_json(r.alpha.energy_ratio_in_band)}};
  if (r.mechanism) {
    const auto& f = r.features;
    j["mechanism"] = {{"class", to_string(r.mechanism->mechanism)}, {"reason", r.mechanism->reason},
                      {"features", {{"critical_strain_percent", optional_json(f.critical_strain_percent)},
                                    {"energy_peak_width_over_x_c", optional_json(f.energy_peak_width)},
                                    {"significant_force_maxima", f.force_maxima},
                                    {"break_spread_over_x_c", optional_json(f.break_spread)},
                                    {"post_peak_decay_over_x_c", optional_json(f.post_peak_decay)},
                                    {"Gamma", optional_json(f.gamma)}}}};
  } else {
    j["mechanism"] = nullptr;
  }
  return j;
}

}  // namespace rupture::analysis
