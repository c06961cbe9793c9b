// cli/analyze_command: `rupture analyze CURVES.csv` — the precursor analysis of one loading curve
// (src/analysis): writes analysis.json and prints a short summary. Exit 0 accepted, 4 analysed but
// rejected (reason printed), 2 bad input.
#include "cli/analyze_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/analysis.hpp"
#include "analysis/curve_file.hpp"
#include "analysis/option_words.hpp"
#include "cli/commands.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace rupture::cli {

namespace {

std::string with_error(const analysis::Measured& m) {
  return m.error > 0.0 ? fmt::format("{:.6g} ± {:.2g} {}", m.value, m.error, m.unit)
                       : fmt::format("{:.6g} {}", m.value, m.unit);
}

// What the analysis made of the input: rows, resampling, filter and the noise kind read.
void print_input(const analysis::AnalysisResult& r, std::FILE* out) {
  fmt::print(out, "{}: {} rows", r.source, r.resample.input_rows);
  if (r.resample.resampled || r.resample.duplicates_merged > 0 || r.resample.block_average > 1) {
    fmt::print(
        out, " ({}{}{} -> {} uniform rows)",
        r.resample.duplicates_merged > 0 ? fmt::format("{} duplicates merged, ", r.resample.duplicates_merged)
                                         : "",
        r.resample.resampled ? (r.resample.on_lattice ? "resampled on the rows' lattice" : "resampled")
                             : "uniform",
        r.resample.block_average > 1 ? fmt::format(", averaged in blocks of {}", r.resample.block_average)
                                     : "",
        r.resample.output_rows);
  }
  fmt::print(out, "\n  filter      {}", analysis::to_string(r.filter.kind));
  if (r.filter.kind == analysis::FilterKind::butterworth) {
    fmt::print(out, " order {}, cutoff {:.4g} x Nyquist", r.filter.butterworth_order, r.filter.cutoff);
  } else if (r.filter.kind == analysis::FilterKind::savitzky_golay) {
    fmt::print(out, " window {}, order {}", r.filter.savgol_window, r.filter.savgol_order);
  }
  fmt::print(out, "; derivative window {} samples\n", r.derivative_window);
  fmt::print(out, "  noise       F {}, E_e {} (over the whole record)", analysis::noise_name(r.force_walk),
             analysis::noise_name(r.energy_walk));
  if (r.x_c_interval) {
    fmt::print(out, "; intervals sized for {}{}",
               analysis::scored_as_random_walk(r) ? "a random walk" : "white noise",
               r.quiet && !analysis::reads_random_walk(r)
                   ? fmt::format(" (quiet: white noise below {:g} % of the peaks)",
                                 100.0 * analysis::quiet_white_noise_share)
                   : "");
  }
  fmt::print(out, "\n");
}

// Under an interval whose white noise lies outside the range its factors were checked on
// [checked_from, checked_to]: that level and the range (another reason is a warning of its own). Not
// on a curve cut by a sharp collapse, whose factors follow no level (the warning says why).
void print_level_note(std::FILE* out, const analysis::AnalysisResult& r, const char* name, const char* noise,
                      std::optional<double> level, double checked_from, double checked_to) {
  if (r.collapse_onset || !level || (*level >= checked_from && *level <= checked_to)) return;
  const std::string checked = std::isfinite(checked_to)
                                  ? fmt::format("{:g}-{:g} %", 100.0 * checked_from, 100.0 * checked_to)
                                  : fmt::format("{:g} % and above", 100.0 * checked_from);
  fmt::print(out, "              ({} {:.3g} %; {}'s factors are calibrated for {})\n", noise, 100.0 * *level,
             name, checked);
}

// The measured numbers, each strain's and δ_x's 95 % interval marked where it is not calibrated.
void print_numbers(const analysis::AnalysisResult& r, std::FILE* out) {
  const auto line = [out](const char* name, const std::optional<analysis::Measured>& m) {
    fmt::print(out, "  {:<11} {}\n", name, m ? with_error(*m) : std::string("not found"));
  };
  const auto strain_line = [&](const char* name, const std::optional<analysis::Measured>& m,
                               const std::optional<analysis::StrainInterval>& interval) {
    if (!m || !interval) return line(name, m);
    fmt::print(out, "  {:<11} {} (95 % [{:.6g}, {:.6g}]{})\n", name, with_error(*m), interval->ci95_low,
               interval->ci95_high, analysis::calibration_mark(interval->scales.calibrated));
  };
  const double from = analysis::white_factors_checked_from, above = std::numeric_limits<double>::infinity();
  strain_line("x_c", r.x_c, r.x_c_interval);
  if (r.x_c_interval && analysis::critical_strain_scales.white_noise.calibrated)
    print_level_note(out, r, "x_c", "F's white noise, share of F_c:", analysis::critical_noise_level(r), from,
                     above);
  line("F_c", r.F_c);
  strain_line("x_p", r.x_p, r.x_p_interval);
  if (r.x_p_interval && analysis::precursor_white_levels.passed_last_check)
    print_level_note(out, r, "x_p", "E_e's white noise, share of E_max:", analysis::precursor_noise_level(r),
                     analysis::precursor_white_levels.calibrated_from,
                     analysis::precursor_white_levels.calibrated_to);
  line("Erate_max", r.Erate_max);
  line("x_m", r.x_m);
  line("E_max", r.E_max);
  if (r.delay) {
    const auto& d = *r.delay;
    fmt::print(out, "  delta_x     {:.6g} ± {:.2g} {} ({}; 68 % [{:.6g}, {:.6g}], 95 % [{:.6g}, {:.6g}]{})\n",
               d.mean, d.sd, r.strain_unit, analysis::to_string(r.delay_method), d.ci68_low, d.ci68_high,
               d.ci95_low, d.ci95_high, analysis::calibration_mark(r.interval_scales.calibrated));
    if (r.delay_method == analysis::DelayMethod::fitted_maxima)
      print_level_note(out, r, "delta_x", "the larger white noise of F and E_e, share of its peak:",
                       analysis::delay_noise_level(r), from, above);
  }
  line("Gamma", r.Gamma);
  line("A_r", r.A_r);
}

// The text summary on `out` (stderr when the document itself goes to stdout with -o -).
void print_summary(const analysis::AnalysisResult& r, const std::filesystem::path& output, std::FILE* out) {
  for (const auto& warning : r.warnings) fmt::print(stderr, "rupture analyze: warning: {}\n", warning);
  print_input(r, out);
  print_numbers(r, out);
  if (r.alpha.alpha)
    fmt::print(out, "  alpha       {:.3g} (from delta_x/x_p, FBM power law)\n", *r.alpha.alpha);
  if (r.alpha.gamma_in_band || r.alpha.energy_ratio_in_band) {
    const auto yes_no = [](const std::optional<bool>& b) { return b ? (*b ? "yes" : "no") : "n/a"; };
    fmt::print(out, "  FBM band    Gamma in [{:.3g}, {:.3g}]: {}; A_r in [{:.3g}, {:.3g}]: {}\n",
               r.alpha.gamma_band_low, r.alpha.gamma_band_high, yes_no(r.alpha.gamma_in_band),
               r.alpha.energy_ratio_band_low, r.alpha.energy_ratio_band_high,
               yes_no(r.alpha.energy_ratio_in_band));
  }
  if (r.mechanism)
    fmt::print(out, "  mechanism   {} ({})\n",
               r.accepted ? analysis::to_string(r.mechanism->mechanism)
                          : fmt::format("none, rejected; the features say {}",
                                        analysis::to_string(r.mechanism->mechanism)),
               r.mechanism->reason);
  fmt::print(out, "  {}\n", r.accepted ? "accepted" : "REJECTED: " + r.rejection);
  fmt::print(out, "  wrote {}\n",
             output == "-" ? std::string("the document to standard output") : output.string());
}

}  // namespace

void add_curve_column_options(CLI::App& cmd, analysis::ColumnChoice& columns) {
  cmd.add_option("--strain", columns.strain, "Strain column (default: strain)");
  cmd.add_option("--force", columns.force, "Force column (default: force, else force_top)");
  cmd.add_option("--energy", columns.energy, "Elastic energy column (default: elastic_energy)");
  cmd.add_option("--strain-scale", columns.strain_scale, "Multiply the strain column by this");
  cmd.add_option("--force-scale", columns.force_scale, "Multiply the force column by this");
  cmd.add_option("--energy-scale", columns.energy_scale, "Multiply the energy column by this");
  cmd.add_option("--strain-unit", columns.strain_unit,
                 "Strain unit after scaling (default: from the header)");
  cmd.add_option("--force-unit", columns.force_unit, "Force unit after scaling (default: from the header)");
  cmd.add_option("--energy-unit", columns.energy_unit,
                 "Energy unit after scaling (default: from the header)");
  cmd.add_option_function<std::string>(
         "--rows",
         [&columns](const std::string& word) {
           columns.rows = analysis::from_word(analysis::row_kind_words, word);
         },
         "What a row holds: instants, or interval-means (each row the mean over its interval, as rupture "
         "run's *_mean columns, or LAMMPS fix ave/time with Nevery x Nrepeat = Nfreq, write them; the noise "
         "model reads a walk on them by its own term). Default: interval-means where a run's *_mean columns "
         "are read, else instants")
      ->check(CLI::IsMember(analysis::word_list(analysis::row_kind_words)));
}

AnalyzeOutcome analyze_and_write(const AnalyzeOptions& options) {
  analysis::CurveFileInputs inputs;
  inputs.curves = options.curves;
  inputs.breaks = options.breaks;
  inputs.no_breaks = options.no_breaks;
  inputs.columns = options.columns;
  inputs.options = options.analysis;
  const auto analysed = analysis::analyze_curve_file(inputs, "rupture analyze");
  const std::filesystem::path output = options.output.empty() ? inputs.curves.parent_path() / "analysis.json"
                                                              : std::filesystem::path(options.output);
  io::write_output(output, analysed.document.dump(2) + "\n");
  print_summary(analysed.result, output, output == "-" ? stderr : stdout);
  return {analysed.result, output};
}

void add_analyze_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<AnalyzeOptions>();
  auto* cmd = app.add_subcommand(
      "analyze",
      "Analyse a loading curve for the precursor of failure (x_c, x_p, delta_x, Gamma, A_r, class)");
  cmd->add_option("curves", o->curves,
                  "CSV with a header: rupture's curves.csv, an FBM curve, or any table (name the columns)")
      ->required();
  cmd->add_option("-o,--out,--output", o->output,
                  "Result file (default: analysis.json beside the curves; - for stdout)");
  cmd->add_option(
      "--breaks", o->breaks,
      "Bond-break table with a strain column (default: breaks.csv beside the curves, if present)");
  cmd->add_flag("--no-breaks", o->no_breaks, "Ignore any breaks.csv");
  add_curve_column_options(*cmd, o->columns);
  cmd->add_option("--filter", o->filter, "Zero-phase low-pass for F and E_e: butterworth | savgol | none")
      ->check(CLI::IsMember({"butterworth", "savgol", "none"}));
  cmd->add_option("--cutoff", o->analysis.filter.cutoff,
                  "Butterworth cutoff in units of the Nyquist frequency (0 < c < 1; default: from the noise)")
      ->check(CLI::Range(0.0, 0.999));
  cmd->add_option("--order", o->analysis.filter.butterworth_order, "Butterworth order")
      ->check(CLI::Range(1, 12));
  cmd->add_option("--window", o->analysis.filter.savgol_window,
                  "Savitzky-Golay smoothing window in samples (odd; default: from the noise)");
  cmd->add_option("--derivative-window", o->analysis.derivative_window,
                  "Samples of the cubic Savitzky-Golay derivative (odd; default: from the filter)");
  cmd->add_option("--peak-drop", o->analysis.peak.drop,
                  "Peak fits use the samples within this fraction of the maximum")
      ->check(CLI::Range(0.001, 0.9));
  cmd->add_option("--delay-method", o->delay_method,
                  "delta_x from the fitted maxima (fitted-maxima, default) or by the paper's l1 shift of the "
                  "energy rate onto F (shift-l1)")
      ->check(CLI::IsMember(analysis::word_list(analysis::delay_method_words)));
  cmd->add_option(
         "--force-peak-form", o->force_peak_form,
         "How the force peaks before a collapse: smooth (a cubic over the filtered top, default) or corner "
         "(it turns at its peak and sags to the collapse, as a DEM tissue does: x_c is the corner of two "
         "lines on the unfiltered rows near the collapse)")
      ->check(CLI::IsMember(analysis::word_list(analysis::peak_form_words)));
  cmd->add_option(
         "--smoothing-floor", o->analysis.smoothing_floor_share,
         "Where the noise of F or E_e reads as white, the automatic filter averages over at least this "
         "share of the rows up to the force peak, where they are 100 or more (default 0: the noise alone "
         "chooses; 0.25 mends DEM runs at rows every 100-200 steps, see docs/analysis.md); withdrawn "
         "where it would reach from the energy-rate peak over the force peak into a collapse")
      ->check(CLI::Range(0.0, analysis::max_smoothing_floor_share));
  cmd->add_option("--max-samples", o->analysis.max_samples,
                  "Denser curves are averaged in blocks down to this many samples (0: never)");
  cmd->add_option("--replicates", o->analysis.uncertainty.replicates,
                  "Noise replicates of the bootstrap that gives every uncertainty")
      ->check(CLI::Range(analysis::min_replicates, analysis::max_replicates));
  cmd->add_option("--seed", o->analysis.uncertainty.seed, "Seed of the bootstrap's noise replicates");
  cmd->add_flag("--walk-profile,!--no-walk-profile", o->analysis.uncertainty.walk_profile,
                "Random-walk noise: bootstrap steps that follow the curve's breaks (default; calibrated) "
                "or one stationary step (the bootstrap's own intervals, conservative)");
  cmd->add_option("--delay-window", o->analysis.delay.window_drop,
                  "shift-l1: delta_x misfit over F >= (1 - this) F_c")
      ->check(CLI::Range(0.01, 0.9));
  cmd->add_option("--grid-points", o->analysis.delay.grid_points, "shift-l1: points of the posterior grid")
      ->check(CLI::Range(101, 100001));
  cmd->callback([o, &exit_code] {
    auto& a = o->analysis;
    // The words were checked against the same tables (IsMember above).
    a.delay_method = *analysis::from_word(analysis::delay_method_words, o->delay_method);
    a.force_peak_form = *analysis::from_word(analysis::peak_form_words, o->force_peak_form);
    a.filter.kind = o->filter == "savgol" ? analysis::FilterKind::savitzky_golay
                    : o->filter == "none" ? analysis::FilterKind::none
                                          : analysis::FilterKind::butterworth;
    if (a.filter.savgol_window > 0 && a.filter.savgol_window % 2 == 0) {
      throw InputError("--window", fmt::format("{} is even", a.filter.savgol_window),
                       "give an odd number of samples");
    }
    if (a.derivative_window > 0 && (a.derivative_window % 2 == 0 || a.derivative_window < 5)) {
      throw InputError("--derivative-window",
                       fmt::format("{} is not an odd number >= 5", a.derivative_window),
                       "give an odd number of samples, at least 5");
    }
    const auto outcome = analyze_and_write(*o);
    const auto& result = outcome.result;
    if (!result.accepted) {
      fmt::print(stderr, "rupture analyze: rejected: {}\n", result.rejection);
      exit_code = exit_rejected;
    }
  });
}

}  // namespace rupture::cli
