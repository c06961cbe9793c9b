// analysis/bootstrap: the uncertainty of every number the analysis reports, by a parametric
// bootstrap of the whole peak measurement. Owns the noise model of a loading curve (white noise plus
// a random walk, for F and E_e, correlated between the two) measured from the data, and the noise
// replicates drawn from it. Not: the measurement itself — the caller passes it as a function, the
// same one that measured the curve (analysis.cpp), so the replicates see exactly its filter,
// derivative and peak fits.
//
// Why a bootstrap and not a likelihood: δ_x = x_c − x_p comes out of a filter, a derivative and two
// cubic fits; the noise that moves x_p is E_e's, the one that moves x_c is F's, and on finite
// bundles both are random walks whose low frequencies survive any low-pass. Redrawing that noise
// onto the smoothed curve and measuring again carries all of it, and its correlation through the
// filter, into the spread of the replicates without a closed form for any stage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace rupture::analysis {

// Noise of one curve, per sample: white noise of standard deviation `white` plus a random walk
// whose increments have standard deviation `walk`, or walk × walk_profile[i] at sample i of the span
// where a profile is given (its mean square is 1: a finite bundle's steps grow with the strain and
// the break density, so that the span's mean step over-states E_e's noise at x_p about fourfold;
// docs/analysis.md, "The walk's steps along the curve").
struct NoiseComponents {
  double white = 0.0, walk = 0.0;
  std::vector<double> walk_profile;  // empty: the same step everywhere
  // 0, or the samples per block mean on which a ringing curve's walk was read (estimate_noise).
  std::size_t ringing_block = 0;
  // Whether the walk was taken from E_e's walk by the breaks' physics (add_hidden_force_walk), and
  // whether it replaced a fit that read no walk in a curve that does not ring.
  bool walk_from_energy = false, walk_read_as_zero = false;
};

struct NoiseModel {
  NoiseComponents force, energy;
  double correlation = 0.0;  // of the F and E_e noise (same for both components), in [-1, 1]
};

// Fits the model to the raw curves over [low, high] from their structure function: the mean square
// of second differences at lags L = 1..8, S(L) = 6σ_w² + 2Lσ_r² + L⁴c (white noise, random walk,
// and the curve's own curvature c, which the fit separates instead of a filter, so that no noise is
// filtered away before it is measured). The correlation of F with E_e is that of their lag-1
// second differences. A curve whose S(L) falls with the lag rings (a DEM run's F sampled faster
// than its slowest mode), which the three terms cannot describe: its walk is read on block means
// (NoiseComponents::ringing_block) and the ringing taken as white noise of its own variance.
// Second differences beyond 10 robust sd are left out (a sudden drop at failure is no noise), the sd
// read as `outliers` says.
enum class OutlierScale {
  // One scale over [low, high]: a span that may hold a collapse, whose smooth fast fall covers many
  // samples in a row and would set its own neighbourhood's scale (the whole record's kind reading).
  span,
  // Each value's neighbourhood's (the values within 32 on either side): a span that stops short of
  // any collapse. A finite bundle's or a run's walk grows along the curve with its breaks (steps near
  // the peak 10-100 times those at the start); one scale over the span is the quiet part's and left
  // out the walk where it matters (docs/analysis.md, "The bootstrap's noise read on the loading").
  local,
};
// What one row of a curve holds: the values at an instant, or their means over the row's interval
// (rupture run's *_mean columns). Neighbouring means share a part of the walk between them, so a
// walk's second differences at lag L have variance (2L − 1)σ_r² on interval means where instants have
// 2Lσ_r²; read with 2L, the fit took a pure walk's variance at 0.65-0.67 of its value (docs/analysis.md,
// "The walk read on rows that are means").
enum class RowKind { instants, interval_means };
NoiseModel estimate_noise(std::span<const double> force, std::span<const double> energy, std::size_t low,
                          std::size_t high, OutlierScale outliers = OutlierScale::span,
                          RowKind rows = RowKind::instants);
// The fewest samples a span needs for estimate_noise: the longest lag on both sides of 17 samples.
inline constexpr std::size_t shortest_noise_span = 33;

// Whether a random walk dominates one curve's noise: its share of the lag-1 structure function,
// 2σ_r², exceeds white noise's, 6σ_w².
bool random_walk_dominates(const NoiseComponents& curve);
// Whether it dominates the noise of F or of E_e.
bool random_walk_dominates(const NoiseModel& model);

// How many of the four quarters of [low, high] a random walk dominates, each quarter's noise
// fitted on its own. A sharp force peak or collapse sits in one quarter; over the whole curve the
// fit's single curvature term cannot absorb it and it inflates the white term, so the whole-curve
// reading takes some finite bundles for white noise. Measured by bench/noise_kind_votes; not the
// analysis's choice, which reads the whole curve (docs/analysis.md, "Calibration", held-out 8: on
// DEM curves the quarter reading moved x_c). 0 for a span too short for quarters of 33 samples.
int walk_dominated_quarters(std::span<const double> force, std::span<const double> energy, std::size_t low,
                            std::size_t high);

// Fills each walk-dominated curve's walk_profile over [low, high] (the model fitted there) from the
// physics of a breaking solid rather than from the noise itself: each break drops the secant
// stiffness k = F/x by one bond's share, F by x times it and E_e by x²/2 times it, and the number of
// breaks in a step is Poisson, so F's step² ∝ x² s(x) and E_e's ∝ x⁴ s(x), with s = −dk/dx read
// from the curve (k averaged over a sixteenth of the span on each side, 3 to 200 samples). Relative
// to its mean over the span (mean square 1), floored at 1 % of it. A curve whose noise a walk does
// not dominate, or whose stiffness never falls, keeps an empty profile (the same step everywhere).
// `strain` is the uniform grid of `force`, from strain 0 (k needs the strain itself).
void add_walk_profiles(NoiseModel& model, std::span<const double> strain, std::span<const double> force,
                       std::size_t low, std::size_t high);

// Where F rings (NoiseComponents::ringing_block), the walk read on its block means is lost under
// the ringing (0 on about half of the run-like known answers cut by a collapse) or takes a part of it
// for a walk (up to 2.4 times the true step on a test bundle); where F carries white noise or leftover
// ringing above its walk, the fit reads the walk as zero (on 39 % of run-like means every 400 steps
// cut by a collapse). Either way the replicates' walk in F, the noise that survives the filter and
// moves x_c, is wrong. The breaks that make E_e's walk make F's: for a linear elastic solid held at a
// displacement, E_e = F u / 2 before and after each break (Clapeyron), so each of F's steps is F/E_e
// times E_e's. Where F rings or its walk is read as zero, and a walk dominates E_e's noise (which does
// not ring), F's walk is taken from E_e's: its step times F/E_e, in rms over [low, high] with each
// sample weighted by E_e's step there from the breaks' physics (add_walk_profiles' x^4 s(x), unfloored),
// and a breaking solid's profile for F where E_e has one; not where the stiffness never falls (no
// breaks to carry). On finite bundles whose own F walk is read, the mapped walk is 1.00 of it (median;
// quartiles 0.97-1.03; docs/analysis.md, "F's walk taken from E_e's with the breaks' own weights"). The
// correlation of the two walks stays the model's one correlation. Call after add_walk_profiles.
void add_hidden_force_walk(NoiseModel& model, std::span<const double> strain, std::span<const double> force,
                           std::span<const double> energy, std::size_t low, std::size_t high);

// Adds one draw of the model's noise to `force` and `energy` (same length), from a generator
// seeded by (seed, replicate): the draw depends on nothing else. The random walk starts at 0 on the
// first sample: only its increments inside the span move a maximum.
void add_model_noise(const NoiseModel& model, std::span<double> force, std::span<double> energy,
                     std::uint64_t seed, std::uint64_t replicate);

// The numbers measured on one replicate.
struct PeakValues {
  double x_c = 0.0, F_c = 0.0, x_p = 0.0, Erate_max = 0.0, x_m = 0.0, E_max = 0.0;
  // The cubic fits' own error at x_c and x_p, estimated from a second fit over a narrower window
  // (fit_window_error); 0 where that fit fails.
  double x_c_fit_error = 0.0, x_p_fit_error = 0.0;
};

// Measures (force, energy), each with noise added; nullopt when a peak is not found.
using PeakMeasure =
    std::function<std::optional<PeakValues>(std::span<const double> force, std::span<const double> energy)>;

struct BootstrapOptions {
  int replicates = 200;
  std::uint64_t seed = 1;
  // Random-walk steps that follow the curve's breaks (add_walk_profiles) instead of one stationary
  // step. The step at x_p is right (0.94-0.96 of a bundle's true step); with its own interval factors
  // (delta_interval_scales) it passed held-out 16 and, re-analysing the small-absolute study scan,
  // accepted 45 of its 48 points where the stationary step accepts 42 (docs/analysis.md, "The walk's
  // steps from the falling stiffness"). analyze_curve applies it only to curves read as a random walk.
  bool walk_profile = true;
};

struct BootstrapResult {
  std::vector<PeakValues> replicates;  // the successful ones, in replicate order
  int attempted = 0, failed = 0;       // failed: a peak not found
};

// Measures `replicates` noisy copies of (force, energy) = the smoothed curves. Replicates are
// independent and are measured in parallel; the result is the same for any thread count.
BootstrapResult bootstrap_peaks(std::span<const double> force, std::span<const double> energy,
                                const NoiseModel& model, const PeakMeasure& measure,
                                const BootstrapOptions& options);

// Summary of one bootstrapped quantity: the estimate corrected by half the bootstrap's bias
// estimate, its sd (the replicates' spread and the other half of the bias, in quadrature), and
// equal-tailed 68 % and 95 % intervals from the replicates' quantiles around their median (the
// basic bootstrap, which keeps a skewed spread), placed on the estimate and widened by the same
// factor as the sd. `kept_bias` is a part of the replicates' mean shift that is not the smoothing's and
// is left uncorrected (still counted in the sd): x_c's at a collapse's cut, which no replicate's
// maximum passes.
struct BootstrapInterval {
  double estimate = 0.0, sd = 0.0;
  double ci68_low = 0.0, ci68_high = 0.0, ci95_low = 0.0, ci95_high = 0.0;
  double bias = 0.0;    // mean of the replicates minus the uncorrected estimate
  double spread = 0.0;  // sd of the replicates
};
BootstrapInterval bootstrap_interval(double estimate, std::vector<double> replicates, double kept_bias = 0.0);

// Adds a systematic error `shift` (strain units) to an interval: sd in quadrature, the intervals
// widened about the estimate by the same factor (or, with no spread at all, ±shift and ±1.96 shift).
BootstrapInterval add_systematic(BootstrapInterval interval, double shift);

}  // namespace rupture::analysis
