#include "analysis/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>

#include "analysis/bootstrap.hpp"
#include "analysis/collapse.hpp"
#include "analysis/option_words.hpp"
#include "core/error.hpp"
#include "fbm/power_law.hpp"
#include "io/quantity.hpp"

namespace rupture::analysis {

namespace {

int odd_at_least(int w) { return w % 2 == 0 ? w + 1 : w; }

// Finds a column by the user's name or by rupture's default names; throws naming the options.
std::size_t pick_column(const io::CsvTable& table, const std::string& chosen,
                        std::initializer_list<const char*> defaults, const char* option) {
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
      throw InputError(
          fmt::format("{}:{}", table.source, table.line_of_row[row]),
          fmt::format("column {} ('{}'): '{}' is not a finite number", c + 1, table.header[c], values[row]),
          "remove the row or replace the value by a measured number");
    }
    values[row] *= scale;
  }
  return values;
}

// The column's unit: the option's, else the header's `name[unit]`; a header without one is taken as
// dimensionless, with a warning naming the option that sets it.
std::string unit_of(const io::CsvTable& table, std::size_t c, const std::string& override_unit,
                    const char* option, std::vector<std::string>& warnings) {
  if (!override_unit.empty()) return override_unit;
  const auto unit = io::column_unit(table.header[c]);
  if (!unit.empty()) return unit;
  warnings.push_back(
      fmt::format("{}: column '{}' names no unit (write it as {}[unit]); taken as 1 (dimensionless): "
                  "give {} if it has one",
                  table.source, table.header[c], table.header[c], option));
  return "1";
}

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
  const auto root =
      boost::math::tools::bisect([&](double a) { return critical_to_precursor_ratio(a) - ratio; }, lo, hi,
                                 boost::math::tools::eps_tolerance<double>(50), iterations);
  return 0.5 * (root.first + root.second);
}

}  // namespace

const FbmBand& power_law_band() {
  static const FbmBand band = [] {
    FbmBand b{1e300, -1e300, 1e300, -1e300};
    for (int k = 0; k <= 500; ++k) {
      const double alpha = 5.0 * k / 500.0;
      const double g = fbm::power_law::gamma(alpha), r = fbm::power_law::energy_ratio(alpha);
      b.gamma_low = std::min(b.gamma_low, g);
      b.gamma_high = std::max(b.gamma_high, g);
      b.energy_ratio_low = std::min(b.energy_ratio_low, r);
      b.energy_ratio_high = std::max(b.energy_ratio_high, r);
    }
    return b;
  }();
  return band;
}

namespace {

AlphaEstimate alpha_estimate(const DelayPosterior& delay, const Measured& x_p,
                             const std::optional<Measured>& gamma,
                             const std::optional<Measured>& energy_ratio) {
  AlphaEstimate a;
  a.alpha = alpha_from_ratio(1.0 + delay.mean / x_p.value);
  // Larger δ_x/x_p means smaller α (the ratio decreases with α).
  a.alpha_low = alpha_from_ratio(1.0 + delay.ci68_high / x_p.value);
  a.alpha_high = alpha_from_ratio(1.0 + delay.ci68_low / x_p.value);
  const FbmBand& band = power_law_band();
  a.gamma_band_low = band.gamma_low;
  a.gamma_band_high = band.gamma_high;
  a.energy_ratio_band_low = band.energy_ratio_low;
  a.energy_ratio_band_high = band.energy_ratio_high;
  // "In the band" allows the measurement's own 2-sigma uncertainty.
  if (gamma) {
    a.gamma_in_band = gamma->value + 2.0 * gamma->error >= a.gamma_band_low &&
                      gamma->value - 2.0 * gamma->error <= a.gamma_band_high;
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
  // A run's rows averaged over their interval, where the file has them and no column is named: single
  // samples alias the sample's ringing, and δ_x then moves with the step the rows start at
  // (docs/analysis.md, "Where the rows fall").
  const bool row_means = choice.strain.empty() && choice.force.empty() && choice.energy.empty() &&
                         table.find("strain_mean") && table.find("force_top_mean") &&
                         table.find("elastic_energy_mean");
  c.rows = choice.rows.value_or(row_means ? RowKind::interval_means : RowKind::instants);
  if (row_means) {
    c.strain = *table.find("strain_mean");
    c.force = *table.find("force_top_mean");
    c.energy = *table.find("elastic_energy_mean");
  } else {
    c.strain = pick_column(table, choice.strain, {"strain"}, "--strain");
    c.force = pick_column(table, choice.force, {"force", "force_top"}, "--force");
    c.energy = pick_column(table, choice.energy, {"elastic_energy"}, "--energy");
  }
  c.strain_unit = unit_of(table, c.strain, choice.strain_unit, "--strain-unit", c.warnings);
  c.force_unit = unit_of(table, c.force, choice.force_unit, "--force-unit", c.warnings);
  c.energy_unit = unit_of(table, c.energy, choice.energy_unit, "--energy-unit", c.warnings);
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
  curve.warnings = columns.warnings;
  curve.rows = columns.rows;
  return curve;
}

BreakLog select_breaks(const io::CsvTable& breaks, double scale,
                       std::optional<std::pair<double, double>> layer_heights) {
  BreakLog log;
  log.strain = scaled_column(breaks, breaks.require("strain"), scale);
  const auto y = breaks.find("y");
  if (layer_heights && y && layer_heights->second > layer_heights->first) {
    const auto [bottom, top] = *layer_heights;
    log.height = scaled_column(breaks, *y, 1.0);
    for (double& h : log.height) h = (h - bottom) / (top - bottom);
  }
  return log;
}

std::size_t minimum_rows(const AnalysisOptions& options) {
  // The filter's padding, the derivative window and a peak fit with room on both sides.
  return std::max<std::size_t>({minimum_samples(options.filter),
                                static_cast<std::size_t>(options.derivative_window),
                                4 * options.peak.min_side + 8, 16});
}

namespace {

// What one peak measurement needs besides the curves: the filter (its automatic choices already
// made), the derivative, the peak fits and where the loading phase ends.
struct PeakSearch {
  FilterSettings filter;
  int derivative_window = 7;
  PeakFitOptions peak;
  double collapse_fraction = 0.25;
  // A sharp collapse (sharp_collapse_onset) is sought within `collapse_width` samples (0: none) of
  // each measurement's own force peak, so that where the onset falls under the noise is part of a
  // replicate's spread. Where the data's measurement finds none, it takes `collapse_onset`, the one
  // its filter was chosen with (choose_filter_for_loading), rather than filter across the collapse.
  std::size_t collapse_width = 0;
  std::optional<std::size_t> collapse_onset;
  // Samples at either end that the fits leave out: a bootstrap window's padding, where the filter's
  // and the derivative's edge effects live.
  std::size_t margin_low = 0, margin_high = 0;
  // Whether ℰ's search steps past the filter's edge at the record's start (past_the_filters_edge):
  // the data's own measurement only. A replicate or the weaker filter's measurement that meets the
  // edge fails instead (a failed replicate; no smoothing shift), as before the step existed.
  bool past_filter_edge = false;
  PeakForm force_peak_form = PeakForm::smooth;
  std::string_view strain_unit;  // named in a failed fit's problem
};

struct PeakMeasurement {
  std::vector<double> filtered_force, filtered_energy, energy_rate;
  PeakFit force, energy, rate;
  double force_fit_error = 0.0, rate_fit_error = 0.0;  // fit_window_error of x_c and x_p
  std::size_t phase_end = 0;                           // last sample of the loading phase
  std::optional<std::size_t> collapse_onset;           // where the curves were split (sharp_collapse_onset)
};

// The cubic fit's own error at a maximum: a cubic over a peak that is not one leaves its stationary
// point off the true maximum by an amount that grows as the window's drop squared (measured on the
// exact curves of 26 shapes at 300-5000 rows, docs/analysis.md, "The strains' own intervals"). Halving
// the drop removes three quarters of it, so 4/3 of the shift between the two fits estimates it
// (Richardson); 0 where the narrower fit fails.
double fit_window_error(std::span<const double> x, std::span<const double> y, const PeakFit& fit,
                        const PeakFitOptions& options) {
  if (!fit.found) return 0.0;
  PeakFitOptions narrower = options;
  narrower.drop *= 0.5;
  const PeakFit narrow = fit_peak(x, y, 0.0, 1.0, narrower);
  return narrow.found ? (4.0 / 3.0) * (fit.x - narrow.x) : 0.0;
}

// The loading phase ends where the filtered force, after its maximum, first falls below
// `collapse_fraction` of it: after that the sample has come apart, and what E_e and ℰ do (the
// halves ringing, fragments flying) is no precursor. x_p and x_m are sought inside the phase, on
// either side of x_c: nothing assumes x_p < x_c.
std::size_t loading_phase_end(std::span<const double> filtered_force, std::size_t force_top,
                              double collapse_fraction) {
  const double level = collapse_fraction * filtered_force[force_top];
  for (std::size_t i = force_top + 1; i < filtered_force.size(); ++i) {
    if (filtered_force[i] < level) return i;
  }
  return filtered_force.size() - 1;
}

// The filtered force's largest sample under `filter`: where and how high.
struct FilteredTop {
  std::size_t index = 0;
  double value = 0.0;
};
FilteredTop filtered_force_top(std::span<const double> force, FilterSettings filter) {
  const auto filtered = apply_filter(filter, force);
  const auto top = std::max_element(filtered.begin(), filtered.end());
  return {static_cast<std::size_t>(top - filtered.begin()), *top};
}

// ℰ of a loading from rest rises from 0. Where it falls from the start of the search instead, and
// that start lies within the filter's edge of the filtered series' first sample, the edge is showing:
// the filtered E_e follows the padding pinned to the first noisy sample, and its slope can beat the
// true maximum (α = 7 at 1 % noise and 5,000 rows: 1.1 against 0.55). The search then starts at
// ℰ's first local minimum, sought within twice the filter's edge. Only the data's measurement
// takes this step (PeakSearch::past_filter_edge): taken in the weaker filter's measurement too, it
// measured smoothing shifts where there had been none and lost a curve on held-out 22
// (docs/analysis.md, "The filter's edge, fourth form").
std::size_t past_the_filters_edge(std::span<const double> rate, std::size_t first, std::size_t end,
                                  std::size_t edge) {
  if (first + 1 > end || rate[first + 1] >= rate[first]) return first;
  const std::size_t limit = std::min(end, first + 2 * edge);
  for (std::size_t i = first + 1; i < limit; ++i)
    if (rate[i + 1] >= rate[i]) return i;
  return first;
}

// Whether a maximum at x lies within the filter's edge before a collapse's onset, where the filtered
// loading follows its end's continuation rather than the rows.
bool within_edge_of_onset(double x, double onset_x, const FilterSettings& filter, double step) {
  return x > onset_x - static_cast<double>(edge_samples(filter)) * step;
}

// PeakForm::corner: where the cubic's x_c lies within the filter's edge of the collapse's onset, the
// filtered loading cannot follow a corner there (it rises to the onset, and the cubic across the corner
// lands on its shallower side: 1.3-1.9 % of x_c early on known answers with such a top), so x_c is the
// corner of two lines fitted to the unfiltered rows over that edge. The checks keep the filtered top's
// sample (`index`).
void fit_force_corner(std::span<const double> xs, std::span<const double> force, std::size_t onset,
                      std::size_t first, const FilterSettings& filter, PeakMeasurement& m) {
  const double spacing = xs.size() > 1 ? xs[1] - xs[0] : 1.0;
  if (!m.force.found || !within_edge_of_onset(m.force.x, xs[onset], filter, spacing)) return;
  const std::size_t edge = edge_samples(filter);
  const std::size_t low = std::max(first, onset > edge ? onset - edge : 0);
  if (onset < low + 6) return;  // fit_corner needs three samples on each side
  PeakFit corner = fit_corner(xs.subspan(low, onset - low + 1), force.subspan(low, onset - low + 1));
  if (!corner.found) return;
  corner.index = m.force.index;
  m.force = corner;
  m.force_fit_error = 0.0;
}

// Filter, derivative and the three maxima: the one measurement made on the data and on every
// bootstrap replicate.
PeakMeasurement measure_peaks(std::span<const double> xs, std::span<const double> force,
                              std::span<const double> energy, const PeakSearch& search) {
  PeakMeasurement m;
  FilterSettings filter = search.filter;
  m.filtered_force = apply_filter(filter, force);
  m.filtered_energy = apply_filter(filter, energy);
  const std::size_t first = std::min(search.margin_low, xs.size() - 1);
  const std::size_t last = xs.size() - 1 - std::min(search.margin_high, xs.size() - 1 - first);
  const auto inner = [&](std::span<const double> y, std::size_t end) {
    return y.subspan(first, end - first + 1);
  };
  const auto fit_force = [&] {
    m.force =
        fit_peak(inner(xs, last), inner(m.filtered_force, last), 0.0, 1.0, search.peak, search.strain_unit);
    m.force_fit_error =
        fit_window_error(inner(xs, last), inner(m.filtered_force, last), m.force, search.peak);
    m.force.index += first;
  };
  fit_force();
  std::optional<std::size_t> onset;
  if (m.force.found && search.collapse_width > 0)
    onset = sharp_collapse_onset(force, energy, m.force.index, search.collapse_fraction * m.force.value,
                                 search.collapse_width);
  if (!onset) onset = search.collapse_onset;
  m.collapse_onset = onset;
  if (onset) {
    filter_either_side(filter, force, *onset, m.filtered_force);
    filter_either_side(filter, energy, *onset, m.filtered_energy);
    fit_force();
    if (search.force_peak_form == PeakForm::corner) fit_force_corner(xs, force, *onset, first, filter, m);
  }
  const double step = xs.size() > 1 ? xs[1] - xs[0] : 1.0;
  m.energy_rate = savgol_filter(m.filtered_energy, search.derivative_window, 3, 1, step);
  m.phase_end = std::min(last, loading_phase_end(m.filtered_force, m.force.index, search.collapse_fraction));
  // E_e often peaks right at the collapse: its fit may reach min_side samples past the phase.
  const std::size_t energy_end = std::min(last, m.phase_end + search.peak.min_side);
  m.energy = fit_peak(inner(xs, energy_end), inner(m.filtered_energy, energy_end), 0.0, 1.0, search.peak,
                      search.strain_unit);
  // The derivative's first and last half-windows are one-sided polynomial extrapolations, whose
  // noise is several times the interior's: on a noisy curve they would win the maximum.
  const auto half = static_cast<std::size_t>(search.derivative_window / 2);
  const std::size_t inner_first = std::max(first, std::min(half, m.phase_end));
  // Before a sharp collapse ℰ's search stops short of the onset by the derivative's half window (a
  // cubic over the corner overshoots) and by the filter's edge (the loading's filtered end follows
  // its padding, as past_the_filters_edge says of the start).
  const std::size_t onset_margin = std::max(half, edge_samples(filter));
  const std::size_t loading_last =
      onset ? std::min(m.phase_end, *onset - std::min(onset_margin, *onset)) : m.phase_end;
  const std::size_t rate_end =
      std::max(inner_first, std::min(loading_last, xs.size() - 1 - std::min(half, xs.size() - 1)));
  const std::size_t edge = edge_samples(filter);
  const std::size_t rate_first = search.past_filter_edge
                                     ? past_the_filters_edge(m.energy_rate, inner_first, rate_end, edge)
                                     : inner_first;
  const auto rate_xs = xs.subspan(rate_first, rate_end - rate_first + 1);
  const auto rate_ys = std::span<const double>(m.energy_rate).subspan(rate_first, rate_end - rate_first + 1);
  m.rate = fit_peak(rate_xs, rate_ys, 0.0, 1.0, search.peak, search.strain_unit);
  m.rate_fit_error = fit_window_error(rate_xs, rate_ys, m.rate, search.peak);
  m.energy.index += first;
  m.rate.index += rate_first;
  return m;
}

// x_c and x_p are required; x_m may be missing (E_e still rising at the end of the phase), and
// then stays NaN in every replicate.
std::optional<PeakValues> peak_values(const PeakMeasurement& m, bool want_energy_peak) {
  if (!m.force.found || !m.rate.found || (want_energy_peak && !m.energy.found)) return std::nullopt;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return PeakValues{m.force.x,
                    m.force.value,
                    m.rate.x,
                    m.rate.value,
                    want_energy_peak ? m.energy.x : nan,
                    want_energy_peak ? m.energy.value : nan,
                    m.force_fit_error,
                    m.rate_fit_error};
}

// First row whose strain is below the one before: a curve that unloads and reloads is no single
// loading, and sorting it would splice the branches.
std::optional<std::size_t> first_strain_decrease(std::span<const double> strain) {
  for (std::size_t i = 1; i < strain.size(); ++i) {
    if (strain[i] < strain[i - 1]) return i;
  }
  return std::nullopt;
}

// Samples on either side of the peak fit windows that the bootstrap measures as well, so that the
// filter's and the derivative's edge effects stay outside the fits.
std::size_t bootstrap_padding(const PeakSearch& search, std::size_t n) {
  double length = search.derivative_window;
  if (search.filter.kind == FilterKind::butterworth) length = std::max(length, 4.0 / search.filter.cutoff);
  if (search.filter.kind == FilterKind::savitzky_golay)
    length = std::max<double>(length, 2 * search.filter.savgol_window);
  return std::min(n, static_cast<std::size_t>(std::ceil(length)) + 4 * search.peak.min_side);
}

std::vector<double> replicate_values(const std::vector<PeakValues>& replicates,
                                     double (*value)(const PeakValues&)) {
  std::vector<double> v;
  v.reserve(replicates.size());
  for (const auto& r : replicates) v.push_back(value(r));
  return v;
}

// 1.4826 median absolute deviation of a derived quantity over the replicates: Γ divides by δ_x,
// so a few replicates with δ_x near 0 would make a plain sd meaningless.
double robust_spread(const std::vector<PeakValues>& replicates, double (*value)(const PeakValues&)) {
  auto v = replicate_values(replicates, value);
  if (v.size() < 2) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  const double median = v[v.size() / 2];
  for (auto& x : v) x -= median;
  return robust_scale(v);
}

double gamma_of(const PeakValues& v) { return (v.x_m - v.x_c) / (v.x_c - v.x_p); }
double energy_ratio_of(const PeakValues& v) { return v.E_max / (v.x_p * v.Erate_max); }

// The replicates' δ values as a density on `bins` equal bins over their range (1/strain unit).
void sampling_density(const std::vector<double>& deltas, DelayPosterior& post, std::size_t bins = 81) {
  if (deltas.empty()) return;
  const auto [lo, hi] = std::minmax_element(deltas.begin(), deltas.end());
  const double width = *hi > *lo ? (*hi - *lo) / static_cast<double>(bins) : 1.0;
  post.delta.resize(bins);
  post.density.assign(bins, 0.0);
  for (std::size_t k = 0; k < bins; ++k) post.delta[k] = *lo + (static_cast<double>(k) + 0.5) * width;
  for (double d : deltas) {
    const auto k = std::min(bins - 1, static_cast<std::size_t>((d - *lo) / width));
    post.density[k] += 1.0 / (static_cast<double>(deltas.size()) * width);
  }
}

// The derivative's window follows the filter's smoothing length, at most 101 samples: after the
// low-pass the curve is smooth on that scale already, and the cost grows with the window.
int derivative_window_for(const FilterSettings& filter, int requested, std::size_t n) {
  if (requested > 0) return odd_at_least(requested);
  double length = 7.0;
  if (filter.kind == FilterKind::butterworth) length = 0.5 / filter.cutoff;
  if (filter.kind == FilterKind::savitzky_golay) length = filter.savgol_window;
  return odd_at_least(
      std::clamp(static_cast<int>(std::lround(length)), 7, std::clamp(static_cast<int>(n / 4), 7, 101)));
}

// One measurement with its bootstrap: the noise model over the span of the fits, the replicates,
// and the values measured on the data.
struct BootstrapRun {
  PeakValues values;
  BootstrapResult boot;
  NoiseModel noise;
  std::size_t low = 0, high = 0;  // bootstrap window (samples)
  std::size_t noise_high = 0;     // last sample the noise model was read on
};

std::optional<BootstrapRun> bootstrap_measurement(std::span<const double> xs, std::span<const double> force,
                                                  std::span<const double> energy, const PeakMeasurement& m,
                                                  const PeakSearch& search, const BootstrapOptions& options,
                                                  RowKind rows) {
  const bool have_energy_peak = m.energy.found;
  const auto values = peak_values(m, have_energy_peak);
  if (!values) return std::nullopt;
  const std::size_t n = xs.size();
  // The fits may wander by their own width in a replicate: the replicates search the fit windows
  // widened by that much on each side (the core) and filter the core plus a padding.
  double low_x = xs[n - 1], high_x = xs[0];
  for (const PeakFit* fit : {&m.force, &m.energy, &m.rate}) {
    if (!fit->found) continue;
    const double width = fit->window_high - fit->window_low;
    low_x = std::min(low_x, fit->window_low - width);
    high_x = std::max(high_x, fit->window_high + width);
  }
  const std::size_t pad = bootstrap_padding(search, n);
  const double step = xs[1] - xs[0];
  const auto index_of = [&](double x) {
    return static_cast<std::size_t>(
        std::clamp<double>(std::lround((x - xs[0]) / step), 0.0, static_cast<double>(n - 1)));
  };
  const std::size_t core_low = index_of(low_x),
                    core_high = std::max(core_low, std::min(index_of(high_x), m.phase_end));
  BootstrapRun run;
  run.values = *values;
  run.low = core_low > pad ? core_low - pad : 0;
  run.high = std::min(n - 1, core_high + pad);
  const std::size_t count = run.high - run.low + 1;
  // The noise is read on the loading only, up to a sharp collapse's onset where one was found: read
  // across it, the fall entered F's structure function as a walk and x_c's sd came out 4-6 times its
  // error on brittle curves with known answers. With the collapse outside the span, the outliers'
  // scale can follow the walk's growth along the loading (OutlierScale::local), and the walk's profile
  // is normalised over the same span (docs/analysis.md, "The bootstrap's noise read on the loading").
  // A walk on rows that are interval means is read with their own term (RowKind).
  run.noise_high =
      m.collapse_onset && *m.collapse_onset >= run.low + shortest_noise_span && *m.collapse_onset <= run.high
          ? *m.collapse_onset - 1
          : run.high;
  run.noise = estimate_noise(force, energy, run.low, run.noise_high, OutlierScale::local, rows);
  if (options.walk_profile) add_walk_profiles(run.noise, xs, force, run.low, run.noise_high);
  add_hidden_force_walk(run.noise, xs, force, energy, run.low, run.noise_high);
  const auto window_x = xs.subspan(run.low, count);
  PeakSearch replicate_search = search;
  replicate_search.past_filter_edge = false;
  replicate_search.margin_low = core_low - run.low;
  replicate_search.margin_high = run.high - core_high;
  replicate_search.collapse_onset.reset();
  const PeakMeasure measure = [&](std::span<const double> f, std::span<const double> e) {
    return peak_values(measure_peaks(window_x, f, e, replicate_search), have_energy_peak);
  };
  run.boot = bootstrap_peaks(std::span<const double>(m.filtered_force).subspan(run.low, count),
                             std::span<const double>(m.filtered_energy).subspan(run.low, count), run.noise,
                             measure, options);
  return run;
}

// Smoothing sensitivity: the same measurement with a weaker filter (cutoff ×√2, the derivative
// window following). Replicates of an already smoothed curve cannot show how far the smoothing
// itself moved a maximum; the shift under a weaker filter can (x_c and x_p; zero when it cannot be
// measured).
PeakValues smoothing_shift(std::span<const double> xs, std::span<const double> force,
                           std::span<const double> energy, const PeakSearch& search, const PeakValues& values,
                           int requested_derivative_window) {
  PeakValues shift{};
  if (search.filter.kind != FilterKind::butterworth) return shift;
  PeakSearch weaker = search;
  weaker.past_filter_edge = false;
  weaker.filter.cutoff = std::min(0.95, std::sqrt(2.0) * search.filter.cutoff);
  weaker.derivative_window = derivative_window_for(weaker.filter, requested_derivative_window, xs.size());
  if (const auto other = peak_values(measure_peaks(xs, force, energy, weaker), false)) {
    shift.x_c = other->x_c - values.x_c;
    shift.x_p = other->x_p - values.x_p;
  }
  return shift;
}

// δ_x of the fitted maxima as a DelayPosterior: the interval's numbers, each level's half-widths
// scaled about the estimate by the factors for the curve's kind of noise (delta_interval_scales), its sd
// by the 68 % factor, and the replicates' density centred on the estimate and widened as that sd was.
DelayPosterior delay_from_replicates(const BootstrapInterval& direct, std::vector<double> deltas,
                                     const IntervalScales& scales) {
  DelayPosterior delay;
  delay.mean = delay.map = delay.median = direct.estimate;
  delay.unscaled_sd = direct.sd;
  delay.sd = scales.level68 * direct.sd;
  const auto scaled = [&](double bound, double scale) {
    return direct.estimate + scale * (bound - direct.estimate);
  };
  delay.ci68_low = scaled(direct.ci68_low, scales.level68);
  delay.ci68_high = scaled(direct.ci68_high, scales.level68);
  // The 95 % interval never inside the 68 % one, whatever the two factors do to a skewed interval.
  delay.ci95_low = std::min(scaled(direct.ci95_low, scales.level95), delay.ci68_low);
  delay.ci95_high = std::max(scaled(direct.ci95_high, scales.level95), delay.ci68_high);
  std::vector<double> sorted = deltas;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
  const double widen = direct.spread > 0.0 ? delay.sd / direct.spread : 1.0;
  for (auto& d : deltas) d = direct.estimate + widen * (d - median);
  sampling_density(deltas, delay);
  return delay;
}

}  // namespace

namespace {

// Keeps the first reason a curve is rejected for.
void reject(AnalysisResult& r, std::string reason) {
  if (r.rejection.empty()) r.rejection = std::move(reason);
}

// The curve on a uniform strain grid: the strains and the two curves on it.
struct Grid {
  UniformCurves curves;
  std::vector<double> xs;
  std::size_t size() const { return xs.size(); }
  std::span<const double> force() const { return curves.y[0]; }
  std::span<const double> energy() const { return curves.y[1]; }
};

// 0–1. One loading on a uniform grid. A strain that goes back is rejected, naming the rows (data
// row numbers, 1-based): nullopt, the reason in r. Too few rows or distinct strains throw.
std::optional<Grid> uniform_grid(const Curve& curve, const AnalysisOptions& options, AnalysisResult& r) {
  const std::size_t needed = minimum_rows(options);
  if (curve.strain.size() < needed) {
    throw InputError(curve.source,
                     fmt::format("{} data rows, the analysis needs at least {}", curve.strain.size(), needed),
                     "give a longer curve (or a weaker filter: --filter none)");
  }
  if (const auto back = first_strain_decrease(curve.strain)) {
    r.resample.input_rows = curve.strain.size();
    r.rejection = fmt::format(
        "the strain decreases from data row {} ({:.6g} {}) to row {} ({:.6g} {}): the curve unloads and "
        "reloads; analyse one monotone loading branch (e.g. rows 1-{})",
        *back, curve.strain[*back - 1], curve.strain_unit, *back + 1, curve.strain[*back], curve.strain_unit,
        *back);
    return std::nullopt;
  }
  const std::span<const double> columns[] = {curve.force, curve.energy};
  Grid g{resample_uniform(curve.strain, columns, r.resample), {}};
  average_blocks(g.curves, options.max_samples, r.resample);
  if (g.curves.size() < needed) {
    throw InputError(
        curve.source,
        fmt::format("{} samples on the uniform grid ({} distinct strains), the analysis needs at least {}",
                    g.curves.size(), r.resample.input_rows - r.resample.duplicates_merged, needed),
        "give a curve with more distinct strain values");
  }
  g.xs.resize(g.curves.size());
  for (std::size_t i = 0; i < g.xs.size(); ++i) g.xs[i] = g.curves.x(i);
  r.x0 = g.curves.x0;
  r.step = g.curves.step;
  return g;
}

// The shares of the rise to the force peak that bound step 2's automatic filter (AnalysisOptions).
struct SmoothingShares {
  double random_walk_cap = 0.0;  // random_walk_smoothing_share
  double floor = 0.0;            // smoothing_floor_share
};

// Whether a curve carries noise: its third differences' noise (noise_from_differences, what the
// discrepancy rule reads) at least 10⁻⁵ of its largest magnitude. An exact curve's are its own third
// derivative, 10⁻⁸ of it at a few thousand rows; a DEM run's loading at rows every 100 steps, whose
// noise model reads almost none, 4-6·10⁻⁴.
bool carries_noise(std::span<const double> y) {
  double largest = 0.0;
  for (double v : y) largest = std::max(largest, std::abs(v));
  return noise_from_differences(y) >= 1e-5 * largest;
}

// The fewest samples from the first row to the force peak for the smoothing floor: at fewer, the
// floor's edge (an eighth of the rise) reaches from the collapse over ℰ's maximum (the study's runs
// at rows every 1,000 steps, a rise of ~40 rows, lost 14 of 29 accepted analyses).
constexpr double smoothing_floor_min_rise = 100.0;

// On a record cut by a collapse, where under the smoothing floor ℰ's maximum lies closer to F's than this
// share of the rise from the record's start to F's maximum, the floor is withdrawn: its edge, an eighth
// of the rise, then reaches from the precursor over the force peak into the collapse and pulls x_p
// there (held-out 31's dem-like curves of the power laws α = 7.4 and 9.1). A record that goes on past
// its peak has no cut to reach. 0.15 was chosen on held-out 31's per-curve files (docs/analysis.md,
// "The smoothing floor withdrawn where it reaches into a collapse").
constexpr double smoothing_floor_min_delay_share = 0.15;

// Whether the floor's filter reaches from ℰ's maximum over the force peak into a collapse (or either
// maximum was not found before it).
bool floor_reaches_into_collapse(const PeakMeasurement& m, double x0) {
  if (!m.collapse_onset) return false;
  if (!m.force.found || !m.rate.found) return true;
  return m.force.x - m.rate.x < smoothing_floor_min_delay_share * (m.force.x - x0);
}

// Step 2's bounds on the automatic choice, in samples of the rise from the first row to the maximum
// of F filtered with that choice.
// - The cap (random walk): on a bundle's increments the steps' noise can exceed all the slope's
//   variation, so the discrepancy rule accepts the floor of its search, a share of the whole record:
//   a curve recorded far past its peak is then averaged over most of the rise to it, which moves the
//   maxima of broad laws by up to 10 % of δ_x.
// - The floor (either curve's noise white): the rule keeps what stands above the noise of F and E_e,
//   but x_p is the maximum of ℰ, E_e's derivative, whose noise the same filter leaves far larger
//   (white noise of 0.2-1 % put δ_x's rms error at 12-22 %). A ringing sampled a few rows a period
//   (a run's F at rows every 100 steps) looks like signal to the rule, which then barely smooths.
//   On a pure walk the rule runs on the increments, E_e's own derivative, and keeps its choice.
void bound_smoothing_by_rise(const Grid& g, const SmoothingShares& shares, FilterSettings& filter,
                             AnalysisResult& r) {
  const bool capped = reads_random_walk(r) && shares.random_walk_cap > 0.0;
  const bool floored = shares.floor > 0.0 && !(r.force_walk && r.energy_walk);
  if (!capped && !floored) return;
  FilterSettings pilot = filter;
  const auto filtered = apply_filter(pilot, g.force());
  const auto rise =
      static_cast<double>(std::max_element(filtered.begin(), filtered.end()) - filtered.begin());
  if (rise <= 0.0) return;
  if (capped) limit_smoothing(filter, shares.random_walk_cap * rise);
  if (floored && rise >= smoothing_floor_min_rise &&
      (carries_noise(g.force()) || carries_noise(g.energy()))) {
    const FilterSettings chosen = filter;
    require_smoothing(filter, shares.floor * rise);
    r.smoothing_floor_applied =
        filter.cutoff != chosen.cutoff || filter.savgol_window != chosen.savgol_window;
  }
}

// The noise model that decides step 2's kind of noise, read on the whole record. Where the whole
// record's fit finds neither white noise nor a walk in either curve, it has taken all for the
// curve's own curvature; on a noisy curve that is wrong (held-out 15's broad log-normal bundles at
// 5,000 rows, recorded to about seven times x_c, were then read as white and barely smoothed;
// docs/analysis.md). The loading part, up to twice the raw force maximum, is then read instead; a
// curve without noise stays without.
// The rows are read as instants even where they are interval means: the kinds' thresholds and the
// filter rules were set on that reading.
NoiseModel noise_for_kind(const Grid& g) {
  const std::size_t n = g.size();
  const NoiseModel whole = estimate_noise(g.force(), g.energy(), 0, n - 1);
  const auto none = [](const NoiseComponents& c) { return c.white == 0.0 && c.walk == 0.0; };
  if (!none(whole.force) || !none(whole.energy)) return whole;
  const auto top =
      static_cast<std::size_t>(std::max_element(g.force().begin(), g.force().end()) - g.force().begin());
  return estimate_noise(g.force(), g.energy(), 0, std::min(n - 1, 2 * top));
}

// 2. One zero-phase filter for both curves, chosen from the noise. Where a random walk dominates
// the noise (finite bundles: every break is a step), the discrepancy principle runs on the
// increments, which are then the white part: on the curves themselves it would take the walk's
// low frequencies for signal and leave ℰ, the walk's derivative, unsmoothed. Under white noise the
// rule sees the curve's own shape. The rise to the force peak then bounds the choice: a cap under a
// walk, a floor under white noise (bound_smoothing_by_rise; a cap there only adds noise:
// docs/analysis.md).
//
// F and E_e can carry different kinds: on a DEM curve F's noise is white (elastic waves at the
// plates) and E_e's a walk (every break drops it). The walk's choice on F's increments, white
// noise differenced, then smooths both curves hard, which moves a sharp peak's maxima. A filter per
// curve, each chosen for its own kind, fixed that on curves with known answers but moved x_c by up to
// 12 % and lost acceptances on rupture's own scans (docs/analysis.md, "A filter per curve"), so
// such a curve is only warned of.
void choose_filter(const Grid& g, FilterSettings& filter, const SmoothingShares& shares, AnalysisResult& r) {
  const std::size_t n = g.size();
  const bool automatic = chooses_own_strength(filter);
  const NoiseModel noise = noise_for_kind(g);
  r.force_walk = random_walk_dominates(noise.force);
  r.energy_walk = random_walk_dominates(noise.energy);
  if (automatic && r.force_walk != r.energy_walk) {
    r.warnings.push_back(fmt::format(
        "the noise of F reads as {} and that of E_e as {}: one filter, chosen for the random walk, serves "
        "both and can move the maxima of a sharp peak (delta_x up to 40 % too large on such curves with "
        "known answers; docs/analysis.md, \"Known limits\")",
        r.force_walk ? "a random walk" : "white", r.energy_walk ? "a random walk" : "white"));
  }
  if (reads_random_walk(r)) {
    std::vector<double> force_steps(n - 1), energy_steps(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      force_steps[i] = g.force()[i + 1] - g.force()[i];
      energy_steps[i] = g.energy()[i + 1] - g.energy()[i];
    }
    const std::span<const double> steps[] = {force_steps, energy_steps};
    choose_shared_filter(filter, steps);
  } else {
    const std::span<const double> raw[] = {g.force(), g.energy()};
    choose_shared_filter(filter, raw);
  }
  r.smoothing_floor_applied = false;
  if (automatic) bound_smoothing_by_rise(g, shares, filter, r);
  r.filter = filter;
  r.force_noise = noise_from_differences(g.force());
  r.energy_noise = noise_from_differences(g.energy());
}

// 2'. A record that ends in a collapse the filter cannot follow (sharp_collapse_onset, sought with
// the whole record's filter): the automatic choice reads the noise and chooses the filter again on
// the loading alone, the rows up to the onset. On the whole record the discrepancy rule must follow
// the drop too and chooses a far weaker filter (known-answer Weibull curves cut at 1.35 x_c: cutoff
// 0.13-0.17 against 0.028 uncut). Returns the onset, which every measurement then splits at.
std::optional<std::size_t> choose_filter_for_loading(const Grid& g, FilterSettings& filter,
                                                     const SmoothingShares& shares, double collapse_fraction,
                                                     AnalysisResult& r) {
  const FilterSettings requested = filter;
  const std::size_t warnings = r.warnings.size();
  choose_filter(g, filter, shares, r);
  const FilteredTop top = filtered_force_top(g.force(), filter);
  const auto onset = sharp_collapse_onset(g.force(), g.energy(), top.index, collapse_fraction * top.value,
                                          collapse_width(top.index));
  // The loading's rows up to the onset, and for a walk their increments (one fewer), must each fill
  // the filter's padding.
  if (!onset || *onset < minimum_samples(filter) || !chooses_own_strength(requested)) return onset;
  Grid loading = g;
  for (auto& y : loading.curves.y) y.resize(*onset + 1);
  loading.xs.resize(*onset + 1);
  r.warnings.resize(warnings);  // the whole record's reading is replaced, warnings included
  filter = requested;
  choose_filter(loading, filter, shares, r);
  return onset;
}

// The peak search of step 4 and its measurement, under the filter step 2 chose.
struct FilteredPeaks {
  PeakSearch search;
  PeakMeasurement measurement;
};

// 2-4 with the smoothing floor at `floor` (a share of the rise; 0: the discrepancy rule alone).
FilteredPeaks filter_and_measure_at(const Grid& g, const AnalysisOptions& options, double floor,
                                    AnalysisResult& r) {
  FilterSettings filter = options.filter;
  const auto onset = choose_filter_for_loading(g, filter, {options.random_walk_smoothing_share, floor},
                                               options.acceptance.collapse_fraction, r);  // 2
  // 3. ℰ by the cubic Savitzky–Golay derivative; its window follows the filter's smoothing length.
  PeakSearch search{.filter = r.filter,
                    .derivative_window = derivative_window_for(r.filter, options.derivative_window, g.size()),
                    .peak = options.peak,
                    .collapse_fraction = options.acceptance.collapse_fraction,
                    .collapse_width = collapse_width(filtered_force_top(g.force(), r.filter).index),
                    .collapse_onset = onset,
                    .past_filter_edge = true,
                    .force_peak_form = options.force_peak_form,
                    .strain_unit = r.strain_unit};
  auto measurement = measure_peaks(g.xs, g.force(), g.energy(), search);  // 4
  return {std::move(search), std::move(measurement)};
}

// 2-4 with the smoothing floor where asked for; where under it ℰ's maximum lies too close to F's before a
// collapse (floor_reaches_into_collapse), again with the discrepancy rule's filter alone, warnings included.
FilteredPeaks filter_and_measure(const Grid& g, const AnalysisOptions& options, AnalysisResult& r) {
  const std::size_t curve_warnings = r.warnings.size();
  auto peaks = filter_and_measure_at(g, options, options.smoothing_floor_share, r);
  if (!r.smoothing_floor_applied || !floor_reaches_into_collapse(peaks.measurement, g.curves.x0))
    return peaks;
  r.warnings.resize(curve_warnings);
  peaks = filter_and_measure_at(g, options, 0.0, r);
  r.smoothing_floor_withdrawn = true;
  r.warnings.push_back(fmt::format(
      "the smoothing floor was withdrawn: under it the energy-rate maximum did not lie at least {:g} % of "
      "the rise before the force maximum (or one of them was not found), so its edge reached over the "
      "force peak into the collapse; the discrepancy rule's filter alone serves (docs/analysis.md, \"The "
      "smoothing floor withdrawn where it reaches into a collapse\")",
      100.0 * smoothing_floor_min_delay_share));
  return peaks;
}

// 4. The maxima found inside the loading phase, as values without errors: the bootstrap (step 6)
// supplies the errors where all three peaks are found.
void record_peaks(const PeakMeasurement& m, const Grid& g, AnalysisResult& r) {
  r.filtered_force = m.filtered_force;
  r.filtered_energy = m.filtered_energy;
  r.energy_rate = m.energy_rate;
  r.force_peak = m.force;
  r.energy_peak = m.energy;
  r.rate_peak = m.rate;
  r.loading_phase_end = g.xs[m.phase_end];
  if (m.collapse_onset) r.collapse_onset = g.xs[*m.collapse_onset];
  if (r.force_peak->found) {
    r.x_c = measured(r.force_peak->x, 0.0, r.strain_unit);
    r.F_c = measured(r.force_peak->value, 0.0, r.force_unit);
  }
  if (r.energy_peak->found) {
    r.x_m = measured(r.energy_peak->x, 0.0, r.strain_unit);
    r.E_max = measured(r.energy_peak->value, 0.0, r.energy_unit);
  }
  if (r.rate_peak->found) {
    r.x_p = measured(r.rate_peak->x, 0.0, r.strain_unit);
    r.Erate_max = measured(r.rate_peak->value, 0.0, energy_rate_unit(r));
  }
}

// 5. Acceptance of the peaks (before spending time on the uncertainty). `phase`: the samples of
// the loading phase.
void check_peaks(const Grid& g, std::size_t phase, std::optional<std::size_t> collapse_onset,
                 const AcceptanceRules& rules, AnalysisResult& r) {
  const std::size_t force_top = r.force_peak->index;
  const double F_top = r.filtered_force[force_top];
  // Competing maxima are sought over the whole curve (a second loading after a collapse makes x_c
  // ambiguous); the mechanism's count of maxima is the loading phase's, so that the ringing of the
  // separated halves is not taken for a slow destruction.
  const auto maxima = significant_maxima(r.filtered_force, 0.05 * std::abs(F_top));
  r.force_maxima = static_cast<int>(
      significant_maxima(std::span<const double>(r.filtered_force).first(phase), 0.05 * std::abs(F_top))
          .size());
  if (!r.force_peak->found) {
    reject(r, "force peak: " + r.force_peak->problem);
  } else if (prominence_of_maximum(r.filtered_force, force_top) < rules.min_prominence * std::abs(F_top)) {
    reject(r,
           fmt::format(
               "force peak not pronounced: it rises less than {:g} % of F_c above the curve on either side",
               100.0 * rules.min_prominence));
  } else {
    // The collapse's filtered start is held at the loading's end (filter_either_side): a maximum found
    // there, where a flat run ends, is the loading's last sample.
    const std::size_t held =
        collapse_onset ? held_collapse_samples(r.filter, *collapse_onset, r.filtered_force.size()) : 0;
    const auto loading_sample = [&](std::size_t k) {
      return held > 0 && k > *collapse_onset && k <= *collapse_onset + held ? *collapse_onset : k;
    };
    for (std::size_t index : maxima) {
      const std::size_t k = loading_sample(index);
      if (k != force_top && r.filtered_force[k] >= rules.competing_maximum * F_top) {
        reject(r,
               fmt::format(
                   "several force maxima of similar height (x = {:.6g} and x = {:.6g} {}): x_c is ambiguous",
                   g.xs[force_top], g.xs[k], r.strain_unit));
        break;
      }
    }
  }
  const std::span<const double> phase_rate = std::span<const double>(r.energy_rate).first(phase);
  if (!r.rate_peak->found && r.rate_peak->cut_short && r.collapse_onset) {
    reject(r, fmt::format(
                  "energy-rate peak: ℰ's search, which stops short of the collapse's onset (x = {:.6g} {}), "
                  "ends before its maximum can be fitted: either ℰ peaks at the collapse itself or the rows "
                  "are too coarse to hold the precursor apart from it (rows every fewer steps tell which)",
                  *r.collapse_onset, r.strain_unit));
  } else if (!r.rate_peak->found) {
    reject(r, "energy-rate peak: " + r.rate_peak->problem);
  } else if (prominence_of_maximum(phase_rate, r.rate_peak->index) <
             rules.min_prominence * std::abs(r.energy_rate[r.rate_peak->index])) {
    reject(r, fmt::format("energy-rate peak not pronounced: it rises less than {:g} % of ℰ_max above the "
                          "curve on either side",
                          100.0 * rules.min_prominence));
  }
}

// Whether the bootstrap window's white noise lies below quiet_white_noise_share of F_c and of E_max.
// Quiet needs both peaks: a curve without E_max was in no check of the reading.
bool is_quiet(const NoiseModel& noise, const AnalysisResult& r) {
  const auto below = [](double white, const std::optional<Measured>& peak) {
    return peak && white < quiet_white_noise_share * std::abs(peak->value);
  };
  return below(noise.force.white, r.F_c) && below(noise.energy.white, r.E_max);
}

// 6. Every number's uncertainty from the bootstrap's replicates, widened by the smoothing shift
// for the strains. Returns δ_x of the fitted maxima with its interval.
BootstrapInterval record_intervals(const Grid& g, const BootstrapRun& run, const PeakSearch& search,
                                   int requested_derivative_window, AnalysisResult& r) {
  const PeakValues& values = run.values;
  const auto& boot = run.boot;
  r.noise_model = run.noise;
  r.bootstrap_window_low = g.xs[run.low];
  r.bootstrap_window_high = g.xs[run.high];
  r.noise_span_high = g.xs[run.noise_high];
  r.bootstrap_replicates = boot.attempted;
  r.bootstrap_failed = boot.failed;
  // x_c within the filter's edge of a collapse's onset: the replicates' maxima are cut off there, so
  // their shift is the cut's, not the smoothing's, and half of it carried x_c (and δ_x) past the
  // onset. There they keep their fitted values, the half shift still counted in their sd.
  const bool x_c_at_cut =
      r.collapse_onset && within_edge_of_onset(r.force_peak->x, *r.collapse_onset, r.filter, r.step);
  const auto interval = [&](double estimate, double (*of)(const PeakValues&), double kept_bias = 0.0) {
    return bootstrap_interval(estimate, replicate_values(boot.replicates, of), kept_bias);
  };
  const auto x_c_of = [](const PeakValues& v) { return v.x_c; };
  const double x_c_cut_bias = x_c_at_cut ? interval(values.x_c, x_c_of).bias : 0.0;
  auto shift = smoothing_shift(g.xs, g.force(), g.energy(), search, values, requested_derivative_window);
  // A corner's x_c takes no filter: a weaker filter's shorter edge only moves its window, or its
  // measurement falls back to the cubic, and neither is a smoothing shift.
  if (r.force_peak->corner) shift.x_c = 0.0;
  // The fit's own error estimated on the data carries the data's noise too; the replicates' spread
  // of the same estimate is that noise's share, taken out in quadrature (0 where it explains all).
  const auto fit_error = [&](double on_data, double (*of)(const PeakValues&)) {
    const double noise = interval(on_data, of).spread;
    return std::sqrt(std::max(0.0, on_data * on_data - noise * noise));
  };
  r.smoothing_shift = {.x_c = shift.x_c, .x_p = shift.x_p};
  r.peak_fit_error = {
      .x_c = fit_error(values.x_c_fit_error, [](const PeakValues& v) { return v.x_c_fit_error; }),
      .x_p = fit_error(values.x_p_fit_error, [](const PeakValues& v) { return v.x_p_fit_error; })};
  const auto x_c = add_systematic(add_systematic(interval(values.x_c, x_c_of, x_c_cut_bias), shift.x_c),
                                  r.peak_fit_error.x_c);
  const auto F_c = interval(values.F_c, [](const PeakValues& v) { return v.F_c; });
  const auto x_p = add_systematic(
      add_systematic(interval(values.x_p, [](const PeakValues& v) { return v.x_p; }), shift.x_p),
      r.peak_fit_error.x_p);
  const auto Erate = interval(values.Erate_max, [](const PeakValues& v) { return v.Erate_max; });
  r.x_c = measured(x_c.estimate, x_c.sd, r.strain_unit);
  r.F_c = measured(F_c.estimate, F_c.sd, r.force_unit);
  r.x_p = measured(x_p.estimate, x_p.sd, r.strain_unit);
  r.Erate_max = measured(Erate.estimate, Erate.sd, energy_rate_unit(r));
  if (r.energy_peak->found) {
    const auto x_m = interval(values.x_m, [](const PeakValues& v) { return v.x_m; });
    const auto E_max = interval(values.E_max, [](const PeakValues& v) { return v.E_max; });
    r.x_m = measured(x_m.estimate, x_m.sd, r.strain_unit);
    r.E_max = measured(E_max.estimate, E_max.sd, r.energy_unit);
    const auto ratio = interval(energy_ratio_of(values), energy_ratio_of);  // bias-corrected like the rest
    r.A_r = measured(ratio.estimate, ratio.sd, "1");
  }
  // δ_x at the cut keeps x_c's shift uncorrected, as x_c does, and takes x_p's half: δ_x = x_c − x_p.
  const auto direct = add_systematic(
      interval(
          values.x_c - values.x_p, [](const PeakValues& v) { return v.x_c - v.x_p; }, x_c_cut_bias),
      shift.x_c - shift.x_p);
  r.quiet = is_quiet(run.noise, r);
  r.delta_x_direct = measured(direct.estimate, direct.sd, r.strain_unit);
  r.bootstrap_bias = {.x_c = x_c.bias, .x_p = x_p.bias, .delta_x = direct.bias};
  return direct;
}

// x_c's or x_p's intervals about the estimate, sized by their factors (critical_strain_scales,
// precursor_scales); unscaled where the options ask for the bootstrap's own. The reported sd becomes the
// 68 % interval's half-width, so that the ± beside the number says what its interval says.
// The 95 % interval is never inside the 68 % one, as for δ_x.
StrainInterval take_strain_interval(Measured& m, const IntervalScales& scales) {
  const double half68 = scales.level68 * m.error, half95 = std::max(1.96 * scales.level95 * m.error, half68);
  m.error = half68;
  return {.ci68_low = m.value - half68,
          .ci68_high = m.value + half68,
          .ci95_low = m.value - half95,
          .ci95_high = m.value + half95,
          .scales = scales};
}

// Marks the intervals of x_c, x_p and δ_x not calibrated, with a warning saying why where any of them
// took learned factors (calibrated or kept from a failed check; not the bootstrap's own): where the
// noise model read a ringing curve (ringing_read), or the smoothing floor acted.
void mark_intervals_uncalibrated(AnalysisResult& r, std::string why) {
  const auto learned = [](const IntervalScales& s) {
    return s.calibrated || s.level68 != 1.0 || s.level95 != 1.0;
  };
  bool had_learned_factors = learned(r.interval_scales);
  for (auto* interval : {&r.x_c_interval, &r.x_p_interval}) {
    if (!*interval) continue;
    had_learned_factors = had_learned_factors || learned((*interval)->scales);
    (*interval)->scales.calibrated = false;
  }
  r.interval_scales.calibrated = false;
  if (had_learned_factors) r.warnings.push_back(std::move(why));
}

// Which intervals of a record cut by a sharp collapse, sized by the factors of its cell (`closeness` and
// its noise kind), are calibrated; which are not here although their cell passed its check (another mark
// took it away, or its white level lies below the checked ones); and which are not, their cell having
// failed, with what that cell fell short by in brackets (said last: the brackets hold the shortfalls'
// own "; "). Read after every other mark: a ringing one says not.
std::string collapse_interval_status(const AnalysisResult& r, double closeness, bool delta_scaled) {
  const bool walk = scored_as_random_walk(r), near = is_near_collapse(closeness);
  std::vector<std::string> calibrated, withdrawn, failed, shortfalls;
  const auto sort = [&](const char* name, bool is_calibrated, const CollapseIntervalScales& cells) {
    const IntervalScales& cell = cells.for_curve(walk, near);
    if (is_calibrated) {
      calibrated.emplace_back(name);
    } else if (cell.calibrated) {
      withdrawn.emplace_back(name);
    } else {
      failed.emplace_back(name);
      if (!cell.shortfall.empty()) shortfalls.push_back(fmt::format("{}: {}", name, cell.shortfall));
    }
  };
  sort("x_c", r.x_c_interval && r.x_c_interval->scales.calibrated, collapse_critical_scales);
  sort("x_p", r.x_p_interval && r.x_p_interval->scales.calibrated, collapse_precursor_scales);
  if (delta_scaled) sort("delta_x", r.interval_scales.calibrated, collapse_delta_scales);
  std::vector<std::string> status;
  if (!calibrated.empty())
    status.push_back(
        fmt::format("calibrated{} (their cells passed {})",
                    withdrawn.empty() && failed.empty() ? std::string() : " for " + listed(calibrated),
                    collapse_factors_checked_on));
  if (!withdrawn.empty())
    status.push_back(fmt::format(
        "not calibrated here for {}, although their cells passed {}: another warning says why (a ringing, "
        "the smoothing floor, a white noise below the levels from which the white factors were checked)",
        listed(withdrawn), collapse_factors_checked_on));
  if (!failed.empty())
    status.push_back(fmt::format(
        "not calibrated for {}{}", listed(failed),
        shortfalls.empty() ? std::string()
                           : fmt::format(" [on {}'s curves with known answers in this curve's cell ({}), "
                                         "{}]",
                                         collapse_factors_checked_on, collapse_cell_words(walk, near),
                                         fmt::join(shortfalls, "; "))));
  return fmt::format("{}", fmt::join(status, "; "));
}

// The warning of a record cut by a sharp collapse: where the collapse lies, and whether its intervals
// took the factors of such curves (`cut_factors`, takes_collapse_factors, which needs a closeness) or
// are the bootstrap's own, and which of them are calibrated.
std::string collapse_warning(const AnalysisResult& r, bool cut_factors) {
  const auto closeness = collapse_closeness(r);
  const std::string where =
      closeness
          ? fmt::format(", {:.3g} % of x_c {} x_c: {}", 100.0 * std::abs(*closeness),
                        *closeness < 0.0 ? "before" : "after", is_near_collapse(*closeness) ? "near" : "far")
          : std::string();
  // δ_x's factors apply to the fitted maxima only (the l1 shift's interval is its posterior).
  const bool delta_scaled = r.delay_method == DelayMethod::fitted_maxima;
  const std::string intervals =
      cut_factors && closeness
          ? fmt::format(
                "the intervals of x_c, x_p{} take the factors of such curves by how close the collapse "
                "comes (near: less than {:g} % of x_c after it); {}",
                delta_scaled ? " and delta_x" : "", 100.0 * collapse_near_closeness,
                collapse_interval_status(r, *closeness, delta_scaled))
          : fmt::format(
                "the intervals of x_c, x_p{} are the bootstrap's own, not calibrated (the factors of "
                "such curves apply to a positive x_c under the default peak form with calibrated "
                "intervals and, on a walk, the walk's step profile)",
                delta_scaled ? " and delta_x" : "");
  return fmt::format(
      "the record ends in a collapse too sharp for the filter (from x = {:.6g} {}{}), filtered apart from "
      "the loading; {} (docs/analysis.md, \"Intervals of a curve cut by a collapse, by how close it "
      "comes\" and \"{}\")",
      *r.collapse_onset, r.strain_unit, where, intervals, collapse_check_section);
}

// The cases whose intervals no check has calibrated: a noise model that read a ringing curve, a filter
// the smoothing floor strengthened (its factors were learned without it), and, said last so that it can
// name what the others left calibrated, a record cut by a sharp collapse (whose factors, where
// `cut_factors` says they were applied, follow its closeness; calibrated in the cells that passed their
// check: collapse_delta_scales).
void mark_unchecked_cases(AnalysisResult& r, bool cut_factors) {
  if (r.smoothing_floor_applied)
    mark_intervals_uncalibrated(
        r,
        "the smoothing floor strengthened the filter: the interval factors were learned without it, so the "
        "intervals of x_c, x_p and delta_x are not calibrated (under it, held-out 31's white 3 % curves "
        "were covered 181 of 197 at 95 %, 182 needed; docs/analysis.md, \"The smoothing floor\")");
  if (ringing_read(r)) {
    const auto& f = r.noise_model.force;
    const auto& e = r.noise_model.energy;
    mark_intervals_uncalibrated(
        r, fmt::format("{} rings (its structure function falls with the lag, as a run's force does when rows "
                       "come faster than its slowest mode): {}; the intervals of x_c, x_p and delta_x are "
                       "not calibrated there (docs/analysis.md, \"What F's ringing does to the noise "
                       "model\"; rows averaged over at least the ringing's period avoid it)",
                       f.ringing_block > 0 ? "F" : "E_e",
                       f.walk_from_energy
                           ? std::string("its walk was taken from E_e's, each step F/E_e times E_e's")
                           : fmt::format("its walk was read on means of {} rows",
                                         f.ringing_block > 0 ? f.ringing_block : e.ringing_block)));
  }
  if (r.collapse_onset) r.warnings.push_back(collapse_warning(r, cut_factors));
}

// Whether a record cut by a sharp collapse takes the factors of such curves, which follow how close the
// collapse comes to the force peak: they were learned with calibrated intervals, a positive x_c, the
// default peak form and, on a walk, the walk's step profile; under others it keeps the bootstrap's own.
bool takes_collapse_factors(const AnalysisResult& r, const AnalysisOptions& options) {
  return options.calibrated_intervals && r.collapse_onset && collapse_closeness(r) &&
         options.force_peak_form == PeakForm::smooth &&
         (options.uncertainty.walk_profile || !scored_as_random_walk(r));
}

// 7. δ_x by the chosen method, then Γ and α, and the acceptance of the uncertainty.
void estimate_delay(const Grid& g, const BootstrapRun& run, const BootstrapInterval& direct,
                    const AnalysisOptions& options, AnalysisResult& r) {
  const auto& boot = run.boot;
  DelayPosterior delay;
  const bool walk_profile = options.uncertainty.walk_profile;
  // A record cut by a sharp collapse takes the factors of such curves where it can (collapse_scales),
  // else the bootstrap's own.
  const bool cut_factors = takes_collapse_factors(r, options);
  const auto factors = [&](IntervalScales uncut, const CollapseIntervalScales& cut,
                           std::optional<double> level) {
    if (!options.calibrated_intervals) return uncalibrated_scales;
    if (!r.collapse_onset) return uncut;
    return cut_factors ? collapse_scales(cut, r, level) : uncalibrated_scales;
  };
  r.x_c_interval = take_strain_interval(
      *r.x_c, factors(critical_scales(r, walk_profile), collapse_critical_scales, critical_noise_level(r)));
  r.x_p_interval = take_strain_interval(*r.x_p, factors(precursor_scales(r, walk_profile),
                                                        collapse_precursor_scales, precursor_noise_level(r)));
  if (force_walk_hidden(r)) {
    // Taken from E_e's, F's walk served δ_x on held-out 39's mixed curves but left x_c's intervals
    // too wide at 95 % and x_p's too narrow (docs/analysis.md, "F's walk taken from E_e's with the
    // breaks' own weights"); left out, it left x_c's far too narrow.
    const bool taken = r.noise_model.force.walk_read_as_zero;
    const bool x_c_marked = r.x_c_interval->scales.calibrated,
               x_p_marked = taken && r.x_p_interval->scales.calibrated;
    r.x_c_interval->scales.calibrated = false;
    if (taken) r.x_p_interval->scales.calibrated = false;
    if (x_c_marked || x_p_marked)
      r.warnings.push_back(fmt::format(
          "the noise model fits no random walk in F while it fits one in E_e (bootstrap window): {}; {} "
          "not calibrated (docs/analysis.md, \"Known limits\")",
          taken ? "F's walk was taken from E_e's, each step F/E_e times E_e's (on such curves with known "
                  "answers scored as a walk x_c's intervals covered 68.2 % and 97.6 % at 68 and 95 %, x_p's "
                  "59.6 % and 92.7 %)"
                : "x_c's interval leaves F's walk out (it covered 24-50 % at 68 % on such curves with known "
                  "answers)",
          x_c_marked && x_p_marked ? "the intervals of x_c and x_p are"
          : x_c_marked             ? "x_c's interval is"
                                   : "x_p's interval is"));
  }
  if (options.delay_method == DelayMethod::fitted_maxima) {
    r.interval_scales = factors(delay_scales(r, walk_profile), collapse_delta_scales, delay_noise_level(r));
    delay = delay_from_replicates(
        direct, replicate_values(boot.replicates, [](const PeakValues& v) { return v.x_c - v.x_p; }),
        r.interval_scales);
  } else {
    delay = infer_delay(g.curves.x0, g.curves.step, g.force(), r.filtered_force, r.energy_rate,
                        r.force_peak->index, options.delay);
    if (!(delay.scale_at_map > 0.0)) {
      reject(r,
             fmt::format(
                 "no positive scale c fits F ≈ c·ℰ(x − δ) (best c = {:.3g}): the force peak does not match "
                 "the energy-rate peak",
                 delay.scale_at_map));
    }
    if (delay.at_prior_bound) {
      reject(r,
             "δ_x undetermined: the posterior reaches the end of the admissible shifts (the data around the "
             "peaks is too short)");
    }
  }
  mark_unchecked_cases(r, cut_factors);
  r.delay = delay;
  r.delta_x = measured(delay.mean, delay.sd, r.strain_unit);
  if (delay.mean != 0.0 && r.energy_peak->found) {
    r.Gamma =
        measured((r.x_m->value - r.x_c->value) / delay.mean, robust_spread(boot.replicates, gamma_of), "1");
  }
  r.alpha = alpha_estimate(delay, *r.x_p, r.Gamma, r.A_r);
  const AcceptanceRules& rules = options.acceptance;
  if (boot.failed > rules.max_failed_replicates * boot.attempted) {
    reject(r,
           fmt::format(
               "the peaks are unstable under the curve's own noise: in {} of {} noise replicates a maximum "
               "was not found",
               boot.failed, boot.attempted));
  } else if (delay.unscaled_sd > rules.max_relative_delay_sd * std::abs(r.x_c->value - g.curves.x0)) {
    // The rule reads the sd before the interval factors: it was set on it, and the factors calibrate the
    // intervals, not whether the peaks are found.
    reject(r, fmt::format("δ_x too uncertain: sd {:.3g} {} (before the interval factors) exceeds {:g} of x_c",
                          delay.unscaled_sd, r.strain_unit, rules.max_relative_delay_sd));
  }
}

// 8. Mechanism features and class (where x_c was found).
void classify_mechanism(const Grid& g, const BreakLog& breaks, const MechanismRules& rules,
                        AnalysisResult& r) {
  const std::size_t n = g.size();
  const double x_c = r.x_c->value;
  const std::size_t force_top = r.force_peak->index;
  const double F_top = r.filtered_force[force_top];
  auto& f = r.features;
  if (r.strain_unit == "%") f.critical_strain_percent = x_c;
  if (r.strain_unit == "1") f.critical_strain_percent = 100.0 * x_c;
  if (r.energy_peak->found) {
    const std::size_t top = r.energy_peak->index;
    const double level = 0.9 * r.filtered_energy[top];
    std::size_t lo = top, hi = top;
    while (lo > 0 && r.filtered_energy[lo - 1] >= level) --lo;
    while (hi + 1 < n && r.filtered_energy[hi + 1] >= level) ++hi;
    f.energy_peak_width = (g.xs[hi] - g.xs[lo]) / x_c;
  }
  f.force_maxima = r.force_maxima;
  for (std::size_t i = force_top; i < n; ++i) {
    if (r.filtered_force[i] < 0.5 * F_top) {
      f.post_peak_decay = (g.xs[i] - x_c) / x_c;
      break;
    }
  }
  if (F_top > 0.0)
    f.loading_undulation = deepest_dip(std::span<const double>(r.filtered_force).first(force_top)) / F_top;
  // Breaks after the loading phase (fragments ringing, the extra pull after separation) say
  // nothing of how the sample failed.
  const BreakLog loading_breaks = breaks_until(breaks, r.loading_phase_end);
  f.break_spread = break_spread(loading_breaks.strain, x_c);
  f.crack = crack_features(loading_breaks, x_c);
  if (r.Gamma) f.gamma = r.Gamma->value;
  r.mechanism = classify(f, rules);
  // Ductile-like: x_c cannot be identified (paper section 5.2), so the curve is left out.
  // It is the first thing said of such a curve, whatever else failed.
  if (r.mechanism->mechanism == Mechanism::ductile)
    r.rejection = "ductile-like breaking, x_c not identifiable: " + r.mechanism->reason +
                  (r.rejection.empty() ? "" : "; also: " + r.rejection);
}

}  // namespace

std::string collapse_cell_words(bool random_walk, bool near) {
  return fmt::format("{} with a {} collapse", random_walk ? "a random walk" : "white noise",
                     near ? "near" : "far");
}

std::string calibrated_collapse_cells(const CollapseIntervalScales& cells) {
  std::vector<std::string> passed;
  for (const bool walk : {true, false})
    for (const bool near : {false, true})
      if (cells.for_curve(walk, near).calibrated) passed.push_back(collapse_cell_words(walk, near));
  return passed.empty() ? std::string("no kind of noise") : listed(passed);
}

AnalysisResult analyze_curve(const Curve& curve, AnalysisOptions options, const BreakLog& breaks) {
  AnalysisResult r;
  r.source = curve.source;
  r.strain_unit = curve.strain_unit;
  r.force_unit = curve.force_unit;
  r.energy_unit = curve.energy_unit;
  r.delay_method = options.delay_method;
  r.warnings = curve.warnings;
  r.rows = curve.rows;
  const std::optional<Grid> grid = uniform_grid(curve, options, r);  // 0–1
  if (!grid) return r;
  const Grid& g = *grid;
  const auto [search, measurement] = filter_and_measure(g, options, r);  // 2-4
  r.derivative_window = search.derivative_window;
  record_peaks(measurement, g, r);
  if (options.force_peak_form == PeakForm::corner && r.force_peak->found && !r.force_peak->corner)
    r.warnings.push_back(
        "force peak form corner asked for, but x_c is the cubic's over the filtered top: no collapse onset "
        "within the filter's edge of the force peak, or no corner at a maximum in the rows before it");
  check_peaks(g, measurement.phase_end + 1, measurement.collapse_onset, options.acceptance, r);  // 5
  // 6–7. A parametric bootstrap of the measurement (bootstrap.hpp) over the span of the three fits,
  // padded, gives every number's uncertainty and δ_x's. The walk's step profile serves the curves
  // read as a random walk, whose interval factors were learned with it; a curve read as white keeps
  // the stationary steps its white factors were learned with (docs/analysis.md, "Rule 4"). A quiet
  // curve read as white keeps them too and takes the walk's factors (scored_as_random_walk): so it
  // was scored on held-out 24.
  BootstrapOptions uncertainty = options.uncertainty;
  uncertainty.walk_profile = uncertainty.walk_profile && reads_random_walk(r);
  if (const auto run =
          bootstrap_measurement(g.xs, g.force(), g.energy(), measurement, search, uncertainty, r.rows)) {
    const auto direct = record_intervals(g, *run, search, options.derivative_window, r);
    estimate_delay(g, *run, direct, options, r);
  }
  if (r.x_c) classify_mechanism(g, breaks, options.mechanism, r);  // 8
  r.accepted = r.rejection.empty();
  return r;
}

std::string precursor_order(double ci95_low, double ci95_high) {
  if (ci95_low > 0.0) return "x_p comes before x_c (delta_x > 0 at 95 %)";
  if (ci95_high < 0.0) return "x_p comes after x_c (delta_x < 0 at 95 %)";
  return "the order of x_p and x_c is not resolved (the 95 % interval of delta_x includes 0)";
}

std::string energy_rate_unit(const AnalysisResult& result) {
  return io::unit_ratio(result.energy_unit, result.strain_unit);
}

const char* to_string(PeakForm form) { return word_of(peak_form_words, form).data(); }

const char* to_string(DelayMethod method) { return word_of(delay_method_words, method).data(); }

}  // namespace rupture::analysis
