// analysis: reads a loading curve's precursor of failure (paper section 4): filters F and E_e with
// one zero-phase filter, differentiates E_e, fits the maxima (x_c, x_p, x_m) inside the loading
// phase, takes δ_x = x_c − x_p from the fitted maxima (or, as an option, by the paper's l1 shift
// inversion), derives Γ, A_r and the FBM exponent α they imply, gives every number an uncertainty
// by a parametric bootstrap of the curve's own noise (bootstrap.hpp), decides acceptance and
// classifies the breaking mechanism. The live counterpart is monitor.hpp.
// Owns: the numerics on columns of doubles. Not: files — callers read CSV into io::CsvTable and write
// the JSON this returns (src/cli/analyze_command.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/bootstrap.hpp"
#include "analysis/delay.hpp"
#include "analysis/filters.hpp"
#include "analysis/mechanism.hpp"
#include "analysis/peak_fit.hpp"
#include "analysis/resample.hpp"
#include "io/csv.hpp"

namespace rupture::analysis {

// Which columns hold strain, force and elastic energy, and how to scale them. Empty names mean the
// names rupture writes: strain; force, else force_top; elastic_energy.
struct ColumnChoice {
  std::string strain, force, energy;
  double strain_scale = 1.0, force_scale = 1.0, energy_scale = 1.0;  // multiply the column by this
  std::string strain_unit, force_unit, energy_unit;  // unit after scaling; empty = the header's
  // What a row holds; unset: interval means where a run's *_mean columns are read, else instants.
  std::optional<RowKind> rows;
};

// The three columns of one loading curve, scaled, in file order.
struct Curve {
  std::string source;
  std::vector<double> strain, force, energy;
  std::string strain_unit, force_unit, energy_unit;
  std::string strain_column, force_column, energy_column;  // header fields used
  std::vector<std::string> warnings;                       // e.g. a column whose header names no unit
  // Instants, or each row the means over its interval (rupture run's *_mean columns): the noise model
  // reads a walk on means with its own term (RowKind).
  RowKind rows = RowKind::instants;
};

// Where the three columns are in a table's header, and their units after scaling. Throws
// InputError naming the file, the missing column and the option that names it.
struct CurveColumns {
  std::size_t strain = 0, force = 0, energy = 0;
  RowKind rows = RowKind::instants;  // ColumnChoice::rows, else interval means for a run's *_mean columns
  std::string strain_unit, force_unit, energy_unit;
  std::vector<std::string> warnings;
};
CurveColumns find_curve_columns(const io::CsvTable& table, const ColumnChoice& choice = {});

// Picks and checks the columns; throws InputError naming the file, line and column for a missing
// column or a non-finite value.
Curve select_curve(const io::CsvTable& table, const ColumnChoice& choice = {});

// The bond breaks of a `breaks.csv`: column `strain` multiplied by `scale`; with the mean heights
// (mm) of the bottom and top glued layers, also each break's height between them from column `y`
// (the pull axis), when the table has it.
BreakLog select_breaks(const io::CsvTable& breaks, double scale = 1.0,
                       std::optional<std::pair<double, double>> layer_heights = std::nullopt);

struct AcceptanceRules {
  double min_prominence = 0.1;  // F and ℰ peaks must rise this fraction of their height above their bases
  double competing_maximum = 0.9;  // reject if another significant force maximum reaches this fraction of F_c
  double max_relative_delay_sd = 0.25;  // reject if δ_x's unscaled sd exceeds this fraction of x_c
  double max_failed_replicates =
      0.05;  // reject if a peak is lost in more than this share of noise replicates
  double collapse_fraction =
      0.25;  // the loading phase ends where F first falls below this fraction of F_c after x_c
};

// How δ_x is estimated. fitted_maxima: x_c − x_p of the cubic peak fits, unbiased for any curve
// shape (the default). shift_l1: the paper's inversion F(x) ≈ c·ℰ(x − δ) (eq. 26), kept for
// comparison; it assumes the two peaks have one shape, which only the uniform law gives.
enum class DelayMethod { fitted_maxima, shift_l1 };
const char* to_string(DelayMethod method);

// How the force tops out before a collapse, where x_c lies within the filter's edge of its onset:
// smooth (the cubic over the filtered top, as everywhere) or at a corner (a DEM tissue's force turns at
// its peak and sags to the collapse over fewer rows than the edge: x_c is the corner of two lines
// fitted to the unfiltered rows there, fit_corner). The rows cannot tell the two apart under their
// noise, so the choice is the user's (docs/analysis.md, "Known answers with a DEM-like top").
enum class PeakForm { smooth, corner };
const char* to_string(PeakForm form);

struct AnalysisOptions {
  std::size_t max_samples = 20000;  // denser curves are block-averaged to this many samples (0 = never)
  FilterSettings filter;
  int derivative_window = 0;  // samples (odd) of the cubic Savitzky–Golay derivative; 0 = from the filter
  PeakFitOptions peak;
  DelayMethod delay_method = DelayMethod::fitted_maxima;
  DelayOptions delay;  // shift_l1 only
  PeakForm force_peak_form = PeakForm::smooth;
  BootstrapOptions uncertainty;
  AcceptanceRules acceptance;
  MechanismRules mechanism;
  // Under random-walk noise the automatic filter's period is at most this share of the samples from
  // the curve's start to the filtered force's maximum; 0: no cap. 0.5 was chosen among 0.35, 0.5 and
  // 0.7 by δ_x's rms error (bench/smoothing_share_sweep; docs/analysis.md, "The smoothing cap").
  double random_walk_smoothing_share = 0.5;
  // Where F's or E_e's noise reads as white (or rings), the automatic filter's period is at least this
  // share of the same samples, where they are 100 or more; 0 (the default): the discrepancy rule's
  // choice alone. That rule reads the noise of the curves, which leaves ℰ, their derivative,
  // under-smoothed, and a ringing sampled a few rows a period looks like signal to it. 0.25 mends DEM
  // runs at rows every 100-200 steps and white noise on dense rows, but moves x_p on sharp peaks (δ_x
  // under a tenth of x_c) and failed held-out 31's rule on the dem-like groups, so it is an option
  // (docs/analysis.md, "The smoothing floor"). On a record cut by a collapse it is withdrawn where under
  // it ℰ's maximum lies within 0.15 of the rise before F's (AnalysisResult::smoothing_floor_withdrawn).
  double smoothing_floor_share = 0.0;
  // δ_x's, x_c's and x_p's intervals scaled by their factors (delta_interval_scales and the strain
  // scales, below); false keeps the bootstrap's own, from which bench/interval_scales.py learns them.
  bool calibrated_intervals = true;
};

// How far δ_x's bootstrap intervals (fitted-maxima method) are stretched or shrunk about the
// estimate, per level and per kind of noise the analysis tells apart
// (scored_as_random_walk): split-conformal quantiles of the stretch each interval
// needed to reach the true δ_x (bench/interval_scales.py; docs/analysis.md, "Calibration"), rounded
// up to four digits. A kind's factors ship only if they pass the check fixed before it was run, on
// an untouched held-out set: each level's coverage of that kind within 63-73 % and 93-97 %, no group
// more than 2 binomial sd below nominal, >= 99 % of the curves accepted.
// - White noise: learned on the tuning set and held-out 5's smooth shapes, passed on held-out 6
//   (69.4 %, 94.9 %).
// - Random walk with a stationary step: failed held-out 6 (68 %: 62.9 %, and 61.5 % at N = 10^4), so
//   those intervals stay the bootstrap's own (factor 1, conservative: 93-94 % and 99-100 % there).
// - Random walk with the step profile (BootstrapOptions::walk_profile): learned on the tuning set
//   and held-outs 16 to 21 pooled (78 shapes), passed held-out 22 (68.4 %, 94.7 %; lowest group
//   63.7 %, 92.9 %), 23 and, with quiet curves scored as a walk, 24 (66.2 %, 95.6 %), where the
//   white factors passed too (69.9 %, 96.3 %); without that reading they failed through the
//   bundles read as white (N = 10^4: 3 of 7 at 95 %; N = 10^5: 3 of 6). The earlier 0.9744/1.0973 (18 shapes)
//   passed held-outs 16, 17 and 20 and fell four curves short on held-out 21 (docs/analysis.md, "δ_x's
//   random-walk factors learned on 78 shapes"). Estimates without the half-bias correction, with factors
//   0.9017 and 1.0153, failed held-out 17 ("The bootstrap's bias on a random walk"). Scored again on
//   held-out 34's bundles they over-covered at 95 % (72.7 %, 98.3 %; outside 93-97 %). Learned again on
//   the bundles of held-outs 29, 30 and 34 at this code (1,795 curves; 1.0137/1.1266 before), they
//   passed held-out 35 (69.7 %, 96.3 %; lowest group 66.8 %, 95.5 %), where the old ones failed (97.2 %
//   at 95 %). The white ones passed it too (68.7 %, 94.6 %).
// calibrated: the factors passed such a check; false where they are 1 for want of one, or kept from a
// check they failed, or the options asked for the bootstrap's own, so a report can say which
// intervals carry a promise.
struct IntervalScales {
  double level68 = 1.0, level95 = 1.0;
  bool calibrated = false;
  // Where the check these factors last faced found them short (what its curves with known answers
  // covered), for the warning that says they are not calibrated; empty where they passed or where no
  // check has said more than the comment beside them.
  std::string_view shortfall{};
};
inline constexpr IntervalScales uncalibrated_scales{};
// The kind whose factors a curve's intervals take is the one read over the whole record
// (reads_random_walk), except on a quiet curve: one whose bootstrap window holds white noise below
// this share of F_c and of E_max. The white factors (< 1 for δ_x) were learned where white noise of
// 0.2-3 % sets the spread; on a quiet curve the spread comes from the walk, the peak fit and the
// smoothing, as under a walk. On held-outs 22 and 23, 84 finite bundles (sharp power laws, most at
// 300 rows) read as white over the whole record, whose collapse inflates the white term; all but
// one hold white noise below 0.05 % of the peaks in the window, every white-noise curve 0.14 % or more
// (docs/analysis.md, "Quiet curves take the walk's factors"). A curve without E_max is not quiet;
// a noise-free one, whose fitted white term is 0, is.
inline constexpr double quiet_white_noise_share = 5e-4;

// What a printed interval adds after its numbers: nothing when calibrated, else that it is not
// (the terminal, the study's last line and the report say it alike).
constexpr std::string_view calibration_mark(bool calibrated) { return calibrated ? "" : ", not calibrated"; }
struct NoiseIntervalScales {
  IntervalScales white_noise, random_walk, random_walk_profile;
  constexpr const IntervalScales& for_noise(bool random_walk_dominates, bool walk_profile) const {
    if (!random_walk_dominates) return white_noise;
    return walk_profile ? random_walk_profile : random_walk;
  }
};
inline constexpr NoiseIntervalScales delta_interval_scales{.white_noise = {0.7062, 0.8581, true},
                                                           .random_walk = uncalibrated_scales,
                                                           .random_walk_profile = {0.9666, 1.0093, true}};

// x_c's and x_p's intervals: ± level68 sd (68 %) and ± 1.96 level95 sd (95 %) about the estimate,
// where sd is the bootstrap's spread with the smoothing shift and the peak fit's own error in
// quadrature. Each kind's factors ship only after passing a held-out check fixed before it ran
// (docs/analysis.md, "The strains' own intervals" and the held-out 19 to 21 sections):
// - x_c, random walk with the step profile: learned on the tuning set and held-outs 18 to 20 pooled,
//   passed held-out 21 (67.7 %, 95.1 %; lowest group 64.5 %, 94.1 %), 22, 23 and 24. The
//   earlier 1.0266/1.1339 passed held-out 19 and missed held-out 20 by one curve.
// - x_p, random walk with the step profile: 0.9423/1.0074 (learned on the tuning set and held-outs
//   18 and 19) passed held-outs 20 and 21 and missed 22 by one curve; relearned on the tuning set and
//   held-outs 18 to 22 (0.9356/1.0296), both failed held-out 23's rule 2 through six white-noise
//   curves read as a walk (α = 9.5, 0.2 %, 300 rows: 1 of 6 covered at 68 %), so, as fixed before
//   that check, the relearned factors are kept and not calibrated. They passed held-out 24 and
//   missed held-out 25 at N = 10^4 (68 %: 121 of 200, 124 needed). Learned again on held-outs 23
//   to 25 pooled (0.9752/1.0953; the sets whose code is nearest this release's), they passed the
//   untouched held-out 29 (71.4 %, 95.3 %; lowest group 66.7 %, 95.0 %) and shipped, calibrated. On
//   held-out 34's bundles they covered 72.2 %, 97.3 % (just over 97 %). Learned again on the bundles of
//   held-outs 29, 30 and 34 at this code (0.9752/1.0953 before), they passed held-out 35 (70.2 %, 96.5 %;
//   lowest group 66.8 %, 95.0 %), where the old ones failed (73.2 %, 97.5 %).
// - x_p, white: one factor per kind cannot serve it (0.7556/0.8785 passed held-out 21 and failed
//   held-out 22, white 1 % at 68 %: 58.2 %); its factors follow the measured noise level instead
//   (precursor_white_levels, below). white_noise here is for a curve without E_max, where that level
//   is not measured: 1, not calibrated.
// - x_c, white: failed held-outs 18 to 21 (on 21 only through the bundles read as white); with quiet
//   curves scored as a walk (quiet_white_noise_share), learned on held-outs 22 and 23 and passed
//   held-out 24 (68.9 %, 93.9 %; lowest group 66.3 %, 92.6 %, white 3 %). Scored again on held-out 34's
//   white groups (the default analysis) they failed at 95 % (91.4 %; white 1 %: 178 of 198, 182 needed).
//   Learned again on the white groups of held-outs 29, 30, 31 and 34 at this code (2,360 curves;
//   0.7399/0.8176 before), they passed held-out 35 (69.7 %, 93.8 %; lowest group 67.2 %, 92.8 %,
//   white 3 %), where the old ones failed (92.6 % at 95 %). The walk's passed it too (72.1 %, 96.7 %).
inline constexpr NoiseIntervalScales critical_strain_scales{.white_noise = {0.7231, 0.8774, true},
                                                            .random_walk = uncalibrated_scales,
                                                            .random_walk_profile = {1.0468, 1.1232, true}};
inline constexpr NoiseIntervalScales precursor_strain_scales{.white_noise = uncalibrated_scales,
                                                             .random_walk = uncalibrated_scales,
                                                             .random_walk_profile = {0.8980, 0.9939, true}};

// Intervals of a curve cut by a sharp collapse (AnalysisResult::collapse_onset): the bootstrap's sd is
// too small where the collapse comes close to the force peak (x_c's cubic reaches into the collapse
// and comes early; the noise model reads less than the collapse moves) and too large on white noise
// where it leaves room, so their factors follow the collapse's closeness, the onset over x_c minus 1
// (collapse_closeness): near below collapse_near_closeness, far from it on, per noise kind
// (scored_as_random_walk). Split-conformal on the brittle, brittle-close, dem-like and run-like groups
// of held-outs 32-34 run at this code (F's walk taken from E_e's where F rings or its walk is read as
// zero, weighted by the breaks' physics, add_hidden_force_walk; a walk on rows that are interval means
// read by its own term, RowKind; 9,894 curves with a collapse; bench/interval_scales.py
// --collapse-closeness 0.1), rounded up to four digits, learned under the default peak form and, on a
// walk, the walk's step profile (under others the bootstrap's own), white ones not calibrated below
// white_factors_checked_from. Checked once on held-out 39 (3,289 such curves; docs/analysis.md,
// collapse_check_section) with the rule fixed before it: a cell is calibrated where its coverage lies
// within 63-73 % and 93-97 % with no group (those under 20 curves pooled) more than 2 binomial sd below
// nominal; a cell that fails keeps its factors, not calibrated, where they bring its coverage nearer
// nominal at both levels than the bootstrap's own, else factor 1. Passed: δ_x's and x_p's far walk cells
// (70.1 / 94.5 %, 63.7 / 93.7 %) and x_c's white far cell (65.6 / 95.2 %), as on held-out 38. Each failed
// cell says what fell short in its `shortfall` below. The near walk cells of δ_x and x_c and the near white
// ones of δ_x and x_c fail through finite bundles or white curves cut within 2 % past their peak
// (brittle-close), where x_c comes early, a bias no factor mends (some through dem-like rows as well); the
// white far cells of δ_x and x_p through two curves in small groups; x_p's near walk cell through dem-like
// samples and run-like means, its near white one through dem-like means; x_c's far walk cell (67.8 / 94.7 %)
// through run-like means every 200 steps, 63 of 108 at 68 % where 65 were needed. x_p's white near cell ships
// factor 1, its candidate not nearer nominal at 95 % than the bootstrap's own. The check the cells below last
// faced, as the collapse warning cites it: its name and its section in docs/analysis.md (what fell short in a
// cell that failed it is the cell's own shortfall).
inline constexpr std::string_view collapse_factors_checked_on = "held-out 39";
inline constexpr std::string_view collapse_check_section =
    "F's walk taken from E_e's with the breaks' own weights, also where it is read as zero, checked on "
    "held-out 39";
struct CollapseIntervalScales {
  IntervalScales white_near, white_far, walk_near, walk_far;
  constexpr const IntervalScales& for_curve(bool random_walk, bool near) const {
    if (random_walk) return near ? walk_near : walk_far;
    return near ? white_near : white_far;
  }
};
// A cell in words: "a random walk with a far collapse".
std::string collapse_cell_words(bool random_walk, bool near);
// The cells of a table that passed their check, in words, joined by "and"; "no kind of noise" where
// none did (the report's reason names them from the table).
std::string calibrated_collapse_cells(const CollapseIntervalScales& cells);
inline constexpr double collapse_near_closeness = 0.1;
constexpr bool is_near_collapse(double closeness) { return closeness < collapse_near_closeness; }
// The shortfalls are held-out 39's figures under the factors shipped (bench/interval_scales.py with
// --pool-groups-below 20 --pool-checks; the full tables in docs/analysis.md's section).
inline constexpr CollapseIntervalScales collapse_delta_scales{
    .white_near =
        {1.3859, 1.8984, false,
         "brittle-close curves (noise 2 % on F, 0.2 % on E_e) covered 86 of 199 at 68 % (123 needed), "
         "dem-like means every 400 steps 9 of 21 at 68 % (11 needed) and 16 at 95 % (18 needed), the "
         "groups under 20 curves, pooled, 23 of 28 at 95 % (25 needed)"},
    .white_far = {0.6918, 0.7782, false,
                  "the groups under 20 curves, pooled, covered 1 of 2 at 95 % (2 needed)"},
    .walk_near = {1.6353, 2.3617, false,
                  "finite bundles cut within 2 % past their peak (N = 1e5, F white 1 %) covered 38 of 196 at "
                  "68 % (121 needed) and 132 at 95 % (181 needed)"},
    .walk_far = {1.1418, 1.2768, true}};
inline constexpr CollapseIntervalScales collapse_critical_scales{
    .white_near =
        {1.7711, 1.3641, false,
         "brittle-close curves covered at 68 % 106 of 199 with noise 2 % on F and 0.2 % on E_e (123 "
         "needed) and 106 of 189 with white noise 1 % (117 needed)"},
    .white_far = {0.7195, 0.8235, true},
    .walk_near =
        {1.3680, 1.4290, false,
         "finite bundles cut within 2 % past their peak (N = 1e5, F white 1 %) covered 45 of 196 at 68 % "
         "(121 needed) and 175 at 95 % (181 needed), dem-like means every 100 steps 99 of 179 at 68 % (110 "
         "needed) and samples every 100 steps 98 of 168 at 68 % (103 needed) and 151 at 95 % (154 needed)"},
    .walk_far = {1.0624, 1.2161, false,
                 "run-like means every 200 steps covered 63 of 108 at 68 % (65 needed)"}};
inline constexpr CollapseIntervalScales collapse_precursor_scales{
    .white_near =
        {1.0, 1.0, false,
         "with the bootstrap's own intervals (the learned factor was not nearer nominal at both "
         "levels) all the cell's curves covered 82.7 % at 68 % (63-73 % asked), dem-like means every "
         "400 steps 8 of 21 at 68 % (11 needed) and 13 at 95 % (18 needed), dem-like means every 200 "
         "steps 23 of 27 at 95 % (24 needed), the groups under 20 curves, pooled, 20 of 28 at 95 % (25 "
         "needed)"},
    .white_far = {0.7106, 0.8124, false,
                  "the groups under 20 curves, pooled, covered 1 of 2 at 95 % (2 needed)"},
    .walk_near = {1.1215, 1.3541, false,
                  "dem-like samples every 400 steps covered 138 of 152 at 95 % (140 needed), run-like means "
                  "every 100 steps 56 of 63 (57 needed) and every 200 steps 70 of 81 (74 needed)"},
    .walk_far = {1.0571, 1.2568, true}};

// White-noise factors that follow the curve's measured white noise in E_e, ν (the noise model's
// white term in the bootstrap window over E_max): each level's factor interpolated linearly in log ν
// between anchors and held at the end anchors beyond them, calibrated for ν within [calibrated_from,
// calibrated_to]. Below calibrated_from the factor is 1 (the bootstrap's own sd), not calibrated: the
// factors' fall towards low noise is not extrapolated (on DEM curves E_e's noise is mostly a walk).
struct NoiseLevelAnchor {
  double share = 0.0;  // white noise in E_e, fraction of E_max
  double level68 = 1.0, level95 = 1.0;
};
struct WhiteLevelScales {
  std::span<const NoiseLevelAnchor> anchors;
  double calibrated_from = 0.0, calibrated_to = 0.0;
  bool passed_last_check = true;  // false: the factors are applied, but a held-out check failed them
};
// A model's factors at ν = `energy_white_share` (1, not calibrated, where it is NaN).
IntervalScales white_level_scales(const WhiteLevelScales& model, double energy_white_share);

// x_p's white model: the factor its 68 % interval needs rises with ν (split-conformal per white group
// on held-outs 20 to 24: 0.55-0.64 at 0.2 %, 0.73-0.88 at 1 %, 0.77-0.95 at 3 %), since at low noise
// x_p's errors are heavy-tailed against its sd, whose smoothing shift and peak-fit terms do not shrink
// with the noise. Anchors: those quantiles on the five sets pooled (the curves scored as white), rounded
// up; calibrated for ν within the learning curves' 0.5th-99.5th percentiles (0.175 % and 3.164 %,
// rounded outward); above it the 3 % anchor's, not calibrated. Passed held-out 25, whose white groups
// include 0.5 and 2 %, levels no learning set held (68.8 %, 93.9 %). Anchors at 0.06 and 0.1 % (learned
// on the same shapes at those levels) failed held-out 26 (97.2 % at 95 %: too wide), so below 0.17 %
// the factor stays 1 (docs/analysis.md, "Intervals below the table's lowest noise"). Passed held-out
// 29 (66.2 %, 94.9 %) and failed held-out 30 by two curves (white 1 %: 121 of 198 covered at 68 %, 123
// needed; all white 64.1 %, 94.2 %; docs/analysis.md, "The bootstrap's noise read on the loading").
// The anchors below were learned again the same way on the white groups of held-outs 29, 30, 31 and 34
// at this code (2,360 curves; the range from their ν, 0.173-3.164 %, rounded outward as before; anchors
// before 0.6213/0.8308, 0.8100/0.8463, 0.8683/0.9152) and passed held-out 35 (68.6 %, 95.0 %; lowest
// group 66.7 %, 94.0 %).
// Every white factor was checked on white noise of 0.2-3 % of the peaks, from this share up (the
// learning curves' 0.5th percentile of their measured level, 0.175 %, rounded down). Below it,
// δ_x's and x_c's single white factors (delta_interval_scales, critical_strain_scales) were too wide
// at 0.06-0.14 % (held-out 26: δ_x 97.6 % at 95 %, x_c 73.8 % at 68 %; docs/analysis.md, "Intervals
// below the table's lowest noise"), so there they keep their factors, not calibrated: at the level
// that sets their spread, F's for x_c (critical_noise_level), the larger of F's and E_e's for δ_x
// (delay_noise_level). x_p's take factor 1 there (precursor_white_levels).
inline constexpr double white_factors_checked_from = 0.0017;
inline constexpr std::array<NoiseLevelAnchor, 3> precursor_white_anchors{
    {{0.002, 0.6835, 0.8528}, {0.01, 0.8515, 0.9488}, {0.03, 0.8831, 0.9343}}};
inline constexpr WhiteLevelScales precursor_white_levels{precursor_white_anchors, white_factors_checked_from,
                                                         0.032, true};

// A strain's intervals (x_c, x_p) and the factors that sized them.
struct StrainInterval {
  double ci68_low = 0.0, ci68_high = 0.0, ci95_low = 0.0, ci95_high = 0.0;
  IntervalScales scales;
};

// A measured number with its 1-sigma uncertainty (0 when not estimated) and unit.
struct Measured {
  double value = 0.0, error = 0.0;
  std::string unit;
};

// Γ and A_r of the FBM power law p(x) = (1+α) x^α over 0 <= α <= 5: the band of the paper's
// figures 16 and 17, against which a run (alpha_estimate) or a scan (scan/claims) is compared.
struct FbmBand {
  double gamma_low = 0.0, gamma_high = 0.0;
  double energy_ratio_low = 0.0, energy_ratio_high = 0.0;
};
const FbmBand& power_law_band();

struct AlphaEstimate {
  std::optional<double> alpha, alpha_low, alpha_high;  // from δ_x/x_p and its 68 % interval (eq. 18)
  double gamma_band_low = 0.0, gamma_band_high = 0.0;  // Γ(α) over 0 <= α <= 5
  double energy_ratio_band_low = 0.0, energy_ratio_band_high = 0.0;  // A_r(α) over 0 <= α <= 5
  std::optional<bool> gamma_in_band, energy_ratio_in_band;
};

struct AnalysisResult {
  std::string source;
  ResampleReport resample;
  RowKind rows = RowKind::instants;  // Curve::rows, as the noise model read them
  FilterSettings filter;             // with the automatic choices filled in
  // The noise kind read in each curve over the whole record: whether a random walk dominates it.
  // One filter serves both; its automatic choice ran on the increments where either reads so.
  bool force_walk = false, energy_walk = false;
  // Whether AnalysisOptions::smoothing_floor_share strengthened the automatic filter, and whether it was
  // withdrawn again because under it ℰ's maximum lay too close to F's.
  bool smoothing_floor_applied = false, smoothing_floor_withdrawn = false;
  // White noise in the bootstrap window below quiet_white_noise_share of both peaks: the intervals
  // then take the random walk's factors whatever the whole record reads.
  bool quiet = false;
  IntervalScales interval_scales;  // the factors applied to δ_x's intervals (fitted maxima)
  int derivative_window = 0;
  double force_noise = 0.0, energy_noise = 0.0;               // σ̂ of the raw curves (third differences)
  std::optional<PeakFit> force_peak, energy_peak, rate_peak;  // x_c/F_c, x_m/E_max, x_p/ℰ_max
  std::optional<Measured> x_c, F_c, x_m, E_max, x_p, Erate_max;
  std::optional<StrainInterval> x_c_interval, x_p_interval;  // where the bootstrap gave their sd
  double loading_phase_end = 0.0;  // strain where the loading phase ends (AcceptanceRules::collapse_fraction)
  // Strain where a collapse too sharp for the filter begins; the loading and the collapse are then
  // filtered apart (docs/analysis.md, "A collapse the filter cannot follow").
  std::optional<double> collapse_onset;
  DelayMethod delay_method = DelayMethod::fitted_maxima;
  // fitted_maxima: the replicates' sampling distribution centred on the estimate, widened by the 68 %
  // factor as its sd is; shift_l1: the posterior.
  std::optional<DelayPosterior> delay;
  std::optional<Measured> delta_x, Gamma, A_r;  // δ_x: estimate ± sd
  std::optional<Measured>
      delta_x_direct;  // x_c − x_p from the peak fits (= delta_x by default), ± the bootstrap's own sd
  // The bootstrap's bias estimates (replicates' mean minus the data's value; half of each is
  // subtracted from its estimate).
  struct {
    double x_c = 0.0, x_p = 0.0, delta_x = 0.0;
  } bootstrap_bias;
  // The systematic errors added to x_c's and x_p's sd in quadrature (strain unit): the shift under a
  // weaker filter, and the cubic peak fits' own error beyond what the noise puts into its estimate.
  struct {
    double x_c = 0.0, x_p = 0.0;
  } smoothing_shift, peak_fit_error;
  NoiseModel noise_model;  // fitted in the bootstrap window, up to noise_span_high
  double bootstrap_window_low = 0.0, bootstrap_window_high = 0.0;
  double noise_span_high = 0.0;  // the window's end, or where a sharp collapse begins before it
  int bootstrap_replicates = 0, bootstrap_failed = 0;
  AlphaEstimate alpha;
  MechanismFeatures features;
  std::optional<MechanismClass> mechanism;  // the class the features give; reported only when accepted
  int force_maxima = 0;
  bool accepted = false;
  std::string rejection;              // why not accepted
  std::vector<std::string> warnings;  // about the input (from the Curve)
  std::string strain_unit, force_unit, energy_unit;
  std::vector<double> filtered_force, filtered_energy, energy_rate;  // on the uniform grid
  double x0 = 0.0, step = 0.0;
};

// Fewest rows the pipeline accepts with these options.
std::size_t minimum_rows(const AnalysisOptions& options);

// What δ_x's 95 % interval says of the order of the two maxima, in words for summaries: the
// energy-rate maximum came before the force maximum, after it, or the data cannot tell.
std::string precursor_order(double ci95_low, double ci95_high);

// Runs the whole pipeline. `breaks` may be empty (then the class rests on the curves alone). Throws
// InputError when the curve has fewer distinct strains than minimum_rows() (naming the source). Rejections
// are not errors: they come back with accepted = false and the reason.
AnalysisResult analyze_curve(const Curve& curve, AnalysisOptions options, const BreakLog& breaks = {});

// Whether a random walk dominates the noise of F or of E_e over the whole record: the filter was
// then chosen on the increments, and the bootstrap's walk follows the step profile.
bool reads_random_walk(const AnalysisResult& result);
// The kind whose factors the intervals take: a random walk where the whole record reads so or the
// curve is quiet (quiet_white_noise_share).
bool scored_as_random_walk(const AnalysisResult& result);
// Whether F's random walk is missing from what a curve scored as a walk fits: its bootstrap window's
// noise model fits no walk in F while it fits one in E_e (F's walk swamped by white noise at the
// structure function's short lags, or too small per step to fit, as on the largest bundles at 300
// rows). Left out, the replicates missed it and x_c's intervals covered 24-50 % at 68 % on such curves
// with known answers (docs/analysis.md, "Known limits"): x_c's interval is then marked not calibrated.
// Where a walk dominates E_e's noise, F's is taken from E_e's (add_hidden_force_walk); the collapse
// cells were learned and checked with that (held-out 39), the factors of curves not cut by a collapse
// were not, and on held-out 39's mixed curves without a collapse it served δ_x (64.9 / 93.5 %) but not
// x_c (68.2 / 97.6 %) or x_p (59.6 / 92.7 %): on such a curve both strains' intervals are marked not
// calibrated. A warning says so where an interval would otherwise have been calibrated.
bool force_walk_hidden(const AnalysisResult& result);
// Whether the bootstrap window's noise model read a ringing curve's walk on block means
// (NoiseComponents::ringing_block). That reading was measured on known answers that ring as a run
// does (docs/analysis.md, "What F's ringing does to the noise model"), not checked on held-out
// ones: the intervals of x_c, x_p and δ_x are then marked not calibrated, with a warning.
bool ringing_read(const AnalysisResult& result);
// E_e's white noise in the bootstrap window as a share of E_max (the level x_p's and δ_x's white
// factors follow); NaN without E_max or where it is 0.
double energy_white_share(const AnalysisResult& result);
// The level x_p's white factors follow: energy_white_share on a curve scored as white where it is
// measured; none on a walk or without E_max (x_p then takes precursor_strain_scales).
std::optional<double> precursor_noise_level(const AnalysisResult& result);
// F's white noise in the bootstrap window over F_c on a curve scored as white (x_c's level); none on a
// walk or without F_c.
std::optional<double> critical_noise_level(const AnalysisResult& result);
// The larger of precursor_noise_level and critical_noise_level where measured (δ_x's level: either
// curve's noise can set its spread); none where neither is.
std::optional<double> delay_noise_level(const AnalysisResult& result);
// x_p's interval factors for a result: the walk's for a curve scored as a random walk
// (precursor_strain_scales), else those that follow E_e's measured white noise (precursor_white_levels;
// 1, not calibrated, without E_max).
IntervalScales precursor_scales(const AnalysisResult& result, bool walk_profile);
// δ_x's and x_c's interval factors: their kind's (delta_interval_scales, critical_strain_scales); white
// ones not calibrated where their level (delay_noise_level, critical_noise_level) lies below
// white_factors_checked_from.
IntervalScales delay_scales(const AnalysisResult& result, bool walk_profile);
IntervalScales critical_scales(const AnalysisResult& result, bool walk_profile);
// How close a collapse comes to the force peak: collapse_onset over x_c minus 1; none without an onset
// or a positive x_c.
std::optional<double> collapse_closeness(const AnalysisResult& result);
// The factors of a curve cut by a collapse from one of the collapse tables, by its kind and closeness
// (1, not calibrated, without a closeness); white ones not calibrated below white_factors_checked_from at
// `level` (the quantity's noise level, as for curves without a collapse).
IntervalScales collapse_scales(const CollapseIntervalScales& table, const AnalysisResult& result,
                               std::optional<double> level);
// The unit of ℰ = dE_e/dx: E_e's unit per strain unit.
std::string energy_rate_unit(const AnalysisResult& result);
// A noise kind in words, as analysis.json, the terminal and the calibration files write it.
std::string_view noise_name(bool random_walk);
// The kind the intervals take, in words, as written to analysis.json beside the factors.
std::string noise_kind(const AnalysisResult& result);

// Everything in the result except the grid curves, each number as {value, error, unit}; the
// posterior as arrays.
nlohmann::json to_json(const AnalysisResult& result);

}  // namespace rupture::analysis
