// analysis/analysis_json: an AnalysisResult as analysis.json writes it (every quantity with its
// unit; docs/formats.md).
#include <type_traits>

#include "analysis/analysis.hpp"
#include "analysis/option_words.hpp"
#include "io/quantity.hpp"

namespace rupture::analysis {

namespace {

nlohmann::json to_json(const Measured& m) { return io::quantity(m.value, m.error, m.unit); }

template <class T>
nlohmann::json optional_json(const std::optional<T>& v) {
  if (!v) return nullptr;
  if constexpr (std::is_same_v<T, Measured>)
    return to_json(*v);
  else
    return *v;
}

nlohmann::json peak_json(const std::optional<PeakFit>& fit, const std::string& unit) {
  if (!fit) return nullptr;
  nlohmann::json j = {{"found", fit->found},
                      {"window", io::quantity({fit->window_low, fit->window_high}, unit)},
                      {"points", fit->points},
                      {"form", fit->corner ? "corner" : "cubic"}};
  if (!fit->found) j["problem"] = fit->problem;
  return j;
}

}  // namespace

namespace {

// The filter actually used, with its settings.
nlohmann::json filter_json(const AnalysisResult& r) {
  nlohmann::json filter = {
      {"kind", to_string(r.filter.kind)},
      {"applied_to", {"force", "elastic_energy"}},
      {"zero_phase", true},
      {"discrepancy", r.filter.discrepancy},
      {"noise_read", {{"force", noise_name(r.force_walk)}, {"elastic_energy", noise_name(r.energy_walk)}}},
      {"smoothing_floor_applied", r.smoothing_floor_applied},
      {"smoothing_floor_withdrawn", r.smoothing_floor_withdrawn}};
  if (r.filter.kind == FilterKind::butterworth) {
    filter["order"] = r.filter.butterworth_order;
    filter["cutoff_nyquist"] = r.filter.cutoff;
    filter["cutoff_per_strain"] =
        io::quantity(r.filter.cutoff / (2.0 * r.step), io::unit_ratio("1", r.strain_unit));
    filter["method"] = "forward-backward second-order sections, odd padding (sosfiltfilt)";
  } else if (r.filter.kind == FilterKind::savitzky_golay) {
    filter["window_samples"] = r.filter.savgol_window;
    filter["polynomial_order"] = r.filter.savgol_order;
  }
  return filter;
}

// The factors an interval was sized by, the noise kind that chose them (quiet: the walk's, whatever
// the whole record reads), and whether they are calibrated (passed a held-out check) or 1 for want
// of one.
nlohmann::json scales_json(const IntervalScales& scales, const AnalysisResult& r) {
  return {{"noise", noise_kind(r)},
          {"quiet", r.quiet},
          {"ci68", scales.level68},
          {"ci95", scales.level95},
          {"calibrated", scales.calibrated}};
}

// x_c or x_p: value and sd, with the intervals and their factors where the bootstrap ran.
nlohmann::json strain_json(const std::optional<Measured>& m, const std::optional<StrainInterval>& interval,
                           const AnalysisResult& r) {
  nlohmann::json j = optional_json(m);
  if (!m || !interval) return j;
  j["ci68"] = {interval->ci68_low, interval->ci68_high};
  j["ci95"] = {interval->ci95_low, interval->ci95_high};
  j["interval_scales"] = scales_json(interval->scales, r);
  return j;
}

// δ_x with its method, intervals and distribution (null when not estimated).
nlohmann::json delay_json(const AnalysisResult& r) {
  if (!r.delay) return nullptr;
  const auto& d = *r.delay;
  nlohmann::json delta = {{"value", d.mean},
                          {"error", d.sd},
                          {"unit", r.strain_unit},
                          {"method", to_string(r.delay_method)},
                          {"map", d.map},
                          {"mean", d.mean},
                          {"median", d.median},
                          {"sd", d.sd},
                          {"unscaled_sd", d.unscaled_sd},
                          {"ci68", {d.ci68_low, d.ci68_high}},
                          {"ci95", {d.ci95_low, d.ci95_high}}};
  const nlohmann::json density = {{"delta", io::quantity(d.delta, r.strain_unit)},
                                  {"density", io::quantity(d.density, io::unit_ratio("1", r.strain_unit))}};
  if (r.delay_method == DelayMethod::fitted_maxima) {
    delta["model"] =
        "x_c - x_p of the cubic peak fits; intervals: basic parametric bootstrap of the curve's noise, each "
        "level's half-widths scaled by interval_scales (calibrated per kind of noise; 1, the bootstrap's "
        "own, on a random walk with a stationary step: docs/analysis.md, Calibration); sd scaled by the 68 % "
        "factor, unscaled_sd before it";
    delta["interval_scales"] = scales_json(r.interval_scales, r);
    delta["bias"] = r.bootstrap_bias.delta_x;
    delta["sampling_distribution"] = density;
  } else {
    delta["model"] = "F(x) = c * Erate(x - delta_x), l1 misfit, c l1-optimal per delta_x (weighted median)";
    delta["prior"] = {{"kind", "uniform"},
                      {"range", io::quantity({d.prior_low, d.prior_high}, r.strain_unit)}};
    delta["misfit_window"] = io::quantity({d.window_low, d.window_high}, r.strain_unit);
    delta["misfit_samples"] = d.window_samples;
    delta["force_noise_sigma"] = io::quantity(d.noise_sigma, r.force_unit);
    delta["misfit_scale"] = io::quantity(d.misfit_scale, r.force_unit);
    delta["correlation_length_samples"] = d.correlation;
    delta["scale_at_map"] = io::quantity(d.scale_at_map, io::unit_ratio(r.force_unit, energy_rate_unit(r)));
    delta["at_prior_bound"] = d.at_prior_bound;
    delta["posterior"] = density;
  }
  return delta;
}

// How the uncertainties were found: the bootstrap's window, replicates and fitted noise model.
nlohmann::json uncertainty_json(const AnalysisResult& r) {
  const auto noise_json = [](const NoiseComponents& c, const std::string& unit) {
    return nlohmann::json{{"white_sd", io::quantity(c.white, unit)},
                          {"walk_step_sd", io::quantity(c.walk, unit)},
                          {"ringing_block", io::quantity(static_cast<double>(c.ringing_block), "samples")},
                          {"walk_from_energy", c.walk_from_energy},
                          {"walk_read_as_zero", c.walk_read_as_zero}};
  };
  return {{"method",
           "parametric bootstrap: white + random-walk noise fitted to the residual, redrawn on the "
           "filtered curves, every replicate filtered, differentiated and fitted again"},
          {"replicates", r.bootstrap_replicates},
          {"failed_replicates", r.bootstrap_failed},
          {"window", io::quantity({r.bootstrap_window_low, r.bootstrap_window_high}, r.strain_unit)},
          {"systematic",
           {{"method",
             "added to the sd of x_c and x_p in quadrature: the maxima's shift under a filter of cutoff x "
             "sqrt(2), "
             "and the cubic peak fits' own error (4/3 of the shift to a fit over half the drop) beyond its "
             "noise"},
            {"x_c",
             {{"smoothing_shift", io::quantity(r.smoothing_shift.x_c, r.strain_unit)},
              {"peak_fit", io::quantity(r.peak_fit_error.x_c, r.strain_unit)}}},
            {"x_p",
             {{"smoothing_shift", io::quantity(r.smoothing_shift.x_p, r.strain_unit)},
              {"peak_fit", io::quantity(r.peak_fit_error.x_p, r.strain_unit)}}}}},
          {"noise",
           {{"read_over", io::quantity({r.bootstrap_window_low, r.noise_span_high}, r.strain_unit)},
            {"force", noise_json(r.noise_model.force, r.force_unit)},
            {"elastic_energy", noise_json(r.noise_model.energy, r.energy_unit)},
            {"correlation", r.noise_model.correlation}}}};
}

// The breaking class with its reason and features (null when x_c was not found).
nlohmann::json mechanism_json(const AnalysisResult& r) {
  if (!r.mechanism) return nullptr;
  const auto& f = r.features;
  nlohmann::json crack = nullptr;
  if (f.crack)
    crack = {{"height_over_l0", f.crack->height},
             {"distance_to_plate_over_l0", f.crack->to_plate},
             {"localisation", f.crack->localisation},
             {"planes", f.crack->planes}};
  // A rejected curve carries no class (a ductile-like one is rejected for being ductile-like).
  return {{"class", r.accepted ? nlohmann::json(to_string(r.mechanism->mechanism)) : nlohmann::json(nullptr)},
          {"features_say", to_string(r.mechanism->mechanism)},
          {"reason", r.mechanism->reason},
          {"features",
           {{"critical_strain", io::quantity(f.critical_strain_percent, "%")},
            {"energy_peak_width_over_x_c", optional_json(f.energy_peak_width)},
            {"significant_force_maxima", f.force_maxima},
            {"break_spread_over_x_c", optional_json(f.break_spread)},
            {"post_peak_decay_over_x_c", optional_json(f.post_peak_decay)},
            {"loading_undulation_over_F_c", optional_json(f.loading_undulation)},
            {"crack", crack},
            {"Gamma", optional_json(f.gamma)}}}};
}

}  // namespace

nlohmann::json to_json(const AnalysisResult& r) {
  nlohmann::json j;
  j["source"] = r.source;
  j["accepted"] = r.accepted;
  j["rejection"] = r.accepted ? nlohmann::json(nullptr) : nlohmann::json(r.rejection);
  j["warnings"] = r.warnings;
  j["resample"] = {{"input_rows", r.resample.input_rows},
                   {"was_sorted", r.resample.was_sorted},
                   {"duplicates_merged", r.resample.duplicates_merged},
                   {"was_uniform", r.resample.was_uniform},
                   {"resampled", r.resample.resampled},
                   {"on_lattice", r.resample.on_lattice},
                   {"output_rows", r.resample.output_rows},
                   {"block_average", r.resample.block_average},
                   {"rows", word_of(row_kind_words, r.rows)},
                   {"step", io::quantity(r.resample.step, r.strain_unit)}};
  j["filter"] = filter_json(r);
  j["derivative"] = {{"method", "Savitzky-Golay, cubic"}, {"window_samples", r.derivative_window}};
  // The curves the maxima were sought on, on the uniform grid x_i = x0 + i * step: what a figure
  // draws, without running the analysis again (empty when the curve was rejected before filtering).
  j["curves"] = {{"x0", io::quantity(r.x0, r.strain_unit)},
                 {"step", io::quantity(r.step, r.strain_unit)},
                 {"filtered_force", io::quantity(r.filtered_force, r.force_unit)},
                 {"filtered_elastic_energy", io::quantity(r.filtered_energy, r.energy_unit)},
                 {"energy_rate", io::quantity(r.energy_rate, energy_rate_unit(r))}};
  j["noise"] = {{"force", io::quantity(r.force_noise, r.force_unit)},
                {"elastic_energy", io::quantity(r.energy_noise, r.energy_unit)},
                {"estimator", "rms of third differences / sqrt(20), largest 0.5 % trimmed"}};
  j["x_c"] = strain_json(r.x_c, r.x_c_interval, r);
  j["F_c"] = optional_json(r.F_c);
  j["x_m"] = optional_json(r.x_m);
  j["E_max"] = optional_json(r.E_max);
  j["x_p"] = strain_json(r.x_p, r.x_p_interval, r);
  j["Erate_max"] = optional_json(r.Erate_max);
  j["peak_fits"] = {
      {"force", peak_json(r.force_peak, r.strain_unit)},
      {"elastic_energy", peak_json(r.energy_peak, r.strain_unit)},
      {"energy_rate", peak_json(r.rate_peak, r.strain_unit)},
      {"method",
       "cubic least squares around the largest sample; stationary point (the force's, with "
       "force_peak_form = corner at a collapse: the corner of two lines on the unfiltered rows)"}};
  j["delta_x"] = delay_json(r);
  // The levels x_p's and δ_x's white factors followed (shares of the peaks), so a reader sees why an
  // interval is or is not calibrated.
  if (const auto level = precursor_noise_level(r); level && j["x_p"].contains("interval_scales"))
    j["x_p"]["interval_scales"]["energy_white_share"] = *level;
  if (const auto level = critical_noise_level(r); level && j["x_c"].contains("interval_scales"))
    j["x_c"]["interval_scales"]["force_white_share"] = *level;
  if (const auto level = delay_noise_level(r);
      level && j["delta_x"].is_object() && j["delta_x"].contains("interval_scales"))
    j["delta_x"]["interval_scales"]["white_share"] = *level;
  j["delta_x_direct"] = optional_json(r.delta_x_direct);
  j["loading_phase_end"] = io::quantity(r.loading_phase_end, r.strain_unit);
  j["collapse_onset"] =
      r.collapse_onset ? io::quantity(*r.collapse_onset, r.strain_unit) : nlohmann::json(nullptr);
  // How close the collapse comes to the force peak, which chose the intervals' factors there.
  const auto closeness = collapse_closeness(r);
  j["collapse_closeness"] = closeness ? io::quantity(*closeness, "1") : nlohmann::json(nullptr);
  j["uncertainty"] = uncertainty_json(r);
  j["Gamma"] = optional_json(r.Gamma);
  j["A_r"] = optional_json(r.A_r);
  j["alpha"] = {{"from_delta_over_x_p", optional_json(r.alpha.alpha)},
                {"ci68", {optional_json(r.alpha.alpha_low), optional_json(r.alpha.alpha_high)}},
                {"fbm_band", {0.0, 5.0}},
                {"Gamma_band", {r.alpha.gamma_band_low, r.alpha.gamma_band_high}},
                {"A_r_band", {r.alpha.energy_ratio_band_low, r.alpha.energy_ratio_band_high}},
                {"Gamma_in_band", optional_json(r.alpha.gamma_in_band)},
                {"A_r_in_band", optional_json(r.alpha.energy_ratio_in_band)}};
  j["mechanism"] = mechanism_json(r);
  return j;
}

}  // namespace rupture::analysis
