// analysis/monitor: the live precursor warning. Fed a loading curve one sample at a time, using
// only past samples, it raises a warning the moment the energy-rate maximum is confirmed while the
// force is still rising, and predicts the coming critical strain x_c and the elastic energy to be
// released E_max from the FBM power-law relations over 0 <= α <= 5. Not: reading files (the CLI's
// `rupture monitor` and the DEM run loop feed it).
//
// Use (e.g. inline in a running simulation, once per recorded curve row):
//   analysis::Monitor monitor;                       // MonitorOptions{} for the defaults below
//   if (auto w = monitor.add_point(strain, force, elastic_energy)) { report(*w); }
//   ... at the end: auto s = monitor.summary();      // observed x_c, lead, whether the prediction held
//
// Method: each new sample completes a window of the last `window` samples; a cubic least-squares
// fit of E_e(x) and of F(x) over that window gives ℰ, F and dF/dx at the window's centre (a
// causal one-sided estimate, delayed by window/2 samples). The running maximum of ℰ is confirmed
// once ℰ has stayed more than `drop` (fraction) below it for `confirm` consecutive samples while
// dF/dx > 0. Then x_p and ℰ_max come from a cubic fit to the ℰ history around its maximum, and
//   x_c ∈ [x_p⁻·r(5), x_p⁺·r(0)],  r(α) = x_c/x_p (paper eq. 16),
//   E_max ∈ [min A_r(α), max A_r(α)] · x_p·ℰ_max (eq. 23) over the same α range and x_p, ℰ_max bounds,
// with x_p± = x_p ± `sigmas`·(standard error of x_p). Strain is taken from its zero (unloaded) state.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rupture::analysis {

struct MonitorOptions {
  std::size_t window = 41;   // samples per causal cubic fit
  double drop = 0.03;        // fraction of the running ℰ maximum that ℰ must fall below it
  std::size_t confirm = 10;  // consecutive samples below that level to confirm the maximum
  double alpha_low = 0.0, alpha_high = 5.0;  // FBM exponent range of the predictions
  double sigmas = 2.0;                       // widen x_p and ℰ_max by this many standard errors
};

struct Interval {
  double low = 0.0, high = 0.0;
  bool contains(double v) const { return v >= low && v <= high; }
};

struct Warning {
  std::size_t sample = 0;                         // 0-based index of the sample that confirmed the maximum
  double strain = 0.0;                            // strain of that sample (strain units of the input)
  double force = 0.0;                             // force of that sample
  double x_p = 0.0, x_p_error = 0.0;              // precursor strain and its standard error
  double Erate_max = 0.0, Erate_max_error = 0.0;  // ℰ_max (energy / strain unit)
  Interval x_c;                                   // predicted critical strain
  Interval E_max;  // predicted maximum elastic energy (energy released at failure)
  // The warning comes (window/2 + confirm) rows after x_p. It is in time when it comes before the
  // earliest predicted x_c; otherwise the rows are too far apart, and rows at most
  // `max_row_spacing` apart (strain units) would have warned in time.
  bool in_time = true;
  double max_row_spacing = 0.0;
};

struct MonitorSummary {
  std::size_t samples = 0;
  std::optional<Warning> warning;
  std::optional<double> x_c, E_max;          // observed afterwards (cubic fits to the smoothed history)
  std::optional<double> lead;                // x_c − warning strain
  std::optional<bool> x_c_held, E_max_held;  // observed values inside the predicted intervals
  bool force_peaked_before_warning = false;  // the force maximum passed before any confirmation
};

// The warning (or null) and the outcome, in the input's strain and energy units: the "monitor"
// block of `rupture monitor --json` and of a run's run.json.
nlohmann::json to_json(const MonitorSummary& summary, const std::string& strain_unit,
                       const std::string& energy_unit);

class Monitor {
 public:
  explicit Monitor(MonitorOptions options = {});

  // Feeds the next sample (strain non-decreasing). Returns the warning exactly once, at the sample
  // that confirms the energy-rate maximum; std::nullopt otherwise.
  std::optional<Warning> add_point(double strain, double force, double energy);

  const std::optional<Warning>& warning() const { return warning_; }
  std::size_t samples() const { return strain_.size(); }
  // What the data fed so far says: observed x_c and E_max, lead and whether the prediction held.
  MonitorSummary summary() const;

 private:
  MonitorOptions options_;
  std::vector<double> strain_, force_, energy_;  // raw samples
  // Causal estimates at window centres.
  std::vector<double> centre_, rate_, force_smooth_, energy_smooth_;
  double rate_error_ = 0.0;   // standard error of the latest ℰ estimate
  std::size_t rate_top_ = 0;  // index (in the estimates) of the running ℰ maximum
  std::size_t below_ = 0;     // consecutive estimates below the confirmation level
  bool force_peaked_ = false;
  std::optional<Warning> warning_;
};

}  // namespace rupture::analysis
