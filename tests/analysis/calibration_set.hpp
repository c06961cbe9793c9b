// The calibration set of the precursor analysis: ELS fiber-bundle loading curves of many strength
// distributions, whose maxima are known exactly, sampled at a chosen number of rows, with
// independent white noise on F and E_e or as finite bundles of N fibers. Used by the calibration
// test (a small share) and by bench/analysis_calibration (the whole table, docs/analysis.md).
// Per N κ = 1: F = x (1 − P(x)), E_e = x² (1 − P(x)) / 2, ℰ = x (1 − P) − x² p / 2.
#pragma once

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/analysis.hpp"
#include "core/random.hpp"
#include "synthetic_curves.hpp"

namespace rupture::analysis::calibration {

using testing::bundle_curve;

struct Shape {
  std::string name;
  std::function<double(double)> cdf, pdf;
  double x_end;  // the curves run over [0, x_end]
};

struct Truth {
  double x_c, x_p, x_m, F_c, E_max, Erate_max;
  double delta() const { return x_c - x_p; }
  double gamma() const { return (x_m - x_c) / (x_c - x_p); }
  double energy_ratio() const { return E_max / (x_p * Erate_max); }
};

inline Shape weibull(double k) {
  char name[64];
  std::snprintf(name, sizeof name, "weibull k=%g", k);
  return {name, [k](double x) { return x <= 0 ? 0.0 : 1.0 - std::exp(-std::pow(x, k)); },
          [k](double x) { return x <= 0 ? 0.0 : k * std::pow(x, k - 1) * std::exp(-std::pow(x, k)); },
          std::pow(-std::log(0.002), 1.0 / k)};
}

inline Shape power_law(double alpha) {
  char name[64];
  std::snprintf(name, sizeof name, "powerlaw alpha=%g", alpha);
  return {name, [alpha](double x) { return x <= 0   ? 0.0
                                           : x >= 1 ? 1.0
                                                    : std::pow(x, 1 + alpha); },
          [alpha](double x) { return x <= 0 || x >= 1 ? 0.0 : (1 + alpha) * std::pow(x, alpha); }, 1.0};
}

inline Shape uniform(double a, double b) {
  char name[64];
  std::snprintf(name, sizeof name, "uniform [%g,%g]", a, b);
  return {name, [a, b](double x) { return std::clamp((x - a) / (b - a), 0.0, 1.0); },
          [a, b](double x) { return x < a || x > b ? 0.0 : 1.0 / (b - a); }, b};
}

inline Shape log_normal(double sigma) {
  char name[64];
  std::snprintf(name, sizeof name, "lognormal sigma=%g", sigma);
  const double s2 = std::sqrt(2.0);
  return {name, [=](double x) { return x <= 0 ? 0.0 : 0.5 * std::erfc(-std::log(x) / (sigma * s2)); },
          [=](double x) {
            return x <= 0 ? 0.0
                          : std::exp(-std::pow(std::log(x), 2) / (2 * sigma * sigma)) /
                                (x * sigma * std::sqrt(2 * M_PI));
          },
          std::exp(3.0 * sigma)};
}

// A two-population bundle: a share `weak` of Weibull(k, λ = 1) fibers and the rest Weibull(k, λ =
// `strong_scale`).
inline Shape weibull_mixture(const std::string& name, double weak, double k, double strong_scale,
                             double x_end) {
  const auto cdf = [k](double x, double lambda) { return 1.0 - std::exp(-std::pow(x / lambda, k)); };
  const auto pdf = [k](double x, double lambda) {
    const double t = x / lambda;
    return k / lambda * std::pow(t, k - 1.0) * std::exp(-std::pow(t, k));
  };
  return {name,
          [=](double x) { return x <= 0 ? 0.0 : weak * cdf(x, 1.0) + (1.0 - weak) * cdf(x, strong_scale); },
          [=](double x) { return x <= 0 ? 0.0 : weak * pdf(x, 1.0) + (1.0 - weak) * pdf(x, strong_scale); },
          x_end};
}

// 70 % Weibull(k=4, λ=1) + 30 % Weibull(k=4, λ=1.5): a shoulder on the weak side of the force peak.
inline Shape weibull_mixture() { return weibull_mixture("weibull mixture", 0.7, 4.0, 1.5, 2.2); }

// Gamma distribution of shape k and unit mean scale (θ = 1/k).
inline Shape gamma_shape(double k) {
  char name[64];
  std::snprintf(name, sizeof name, "gamma k=%g", k);
  return {name, [k](double x) { return x <= 0 ? 0.0 : boost::math::gamma_p(k, k * x); },
          [k](double x) { return x <= 0 ? 0.0 : k * boost::math::gamma_p_derivative(k, k * x); }, 3.0};
}

// A held-out set: one shape of each family, fixed before the change it checks (docs/analysis.md,
// "Calibration", says which) and run once for it. Uniform on [a, b]; gamma of unit mean recorded
// to `gamma_x_end`; the mixture a share `weak` of Weibull(k, λ = 1) and the rest Weibull(k, λ =
// `strong_scale`), recorded to `x_end`.
struct HeldOutSet {
  const char* name;
  double weibull_k, alpha, uniform_a, uniform_b, lognormal_sigma, gamma_k;
  struct {
    const char* name;
    double weak, k, strong_scale, x_end;
  } mixture;
  double gamma_x_end = 3.0;

  std::vector<Shape> shapes() const {
    Shape gamma = gamma_shape(gamma_k);
    gamma.x_end = gamma_x_end;
    return {weibull(weibull_k),
            power_law(alpha),
            uniform(uniform_a, uniform_b),
            log_normal(lognormal_sigma),
            gamma,
            weibull_mixture(mixture.name, mixture.weak, mixture.k, mixture.strong_scale, mixture.x_end)};
  }
};

// The held-out sets from the second on, by the name bench/analysis_calibration takes, each with what
// it was fixed before. Where a uniform law has a < (3 − √3)b/6 ≈ 0.211 b, ℰ's maximum is inside
// (at b/3), not on the jump at the threshold floor (docs/analysis.md, "Known limits").
// One set a row:
// clang-format off
inline const HeldOutSet later_held_out_sets[] = {
    // Fixed before the first held-out run was looked at in detail; not run while the method was
    // changed after it.
    {"held-out-2", 1.5, 6, 0.5, 1.0, 0.5, 4, {"weibull mixture k=6", 0.5, 6.0, 1.25, 1.8}},
    // Fixed before the smoothing-sensitivity term was tried.
    {"held-out-3", 2.5, 1, 0.1, 0.9, 0.2, 8, {"weibull mixture k=3", 0.6, 3.0, 2.0, 3.5}},
    // Fixed before the per-level interval scales were learned on the tuning set; run only to check
    // them.
    {"held-out-4", 4, 2, 0.15, 0.75, 0.4, 2.5, {"weibull mixture k=5", 0.4, 5.0, 1.4, 2.0}},
    // Fixed before the smoothing cap tied to the force peak was tuned; run only to check it and the
    // scales learned after it. Its gamma's record follows the longer tail.
    {"held-out-5", 6, 5, 0.3, 0.8, 0.6, 1.5, {"weibull mixture k=3.5", 0.5, 3.5, 1.6, 2.6}, 4.5},
    // Fixed before the interval scales were learned on the tuning and fifth sets pooled; run only to
    // check them. Its domain is the smooth ℰ maximum (a < 0.211 b).
    {"held-out-6", 3.5, 0.5, 0.1, 0.6, 0.35, 3.0, {"weibull mixture k=4.5", 0.3, 4.5, 1.3, 2.0}},
    // Fixed after the sixth was scored and before the random-walk scales were learned on the tuning,
    // fifth and sixth sets pooled (bundles only). Its power law sits between α = 3 and 5, where the
    // bootstrap's spread was least conservative.
    {"held-out-7", 1.8, 4, 0.05, 0.55, 0.25, 5.0, {"weibull mixture k=5.5", 0.6, 5.5, 1.35, 1.9}},
    // Fixed before the noise kind was read quarter by quarter; run only to check that reading. Its
    // uniform law was meant to keep ℰ's maximum off the jump by a < b/3, which is not enough: here
    // x_p = a = 0.15.
    {"held-out-8", 2.2, 7, 0.15, 0.5, 0.45, 6.0, {"weibull mixture k=4", 0.4, 4.0, 1.5, 2.4}},
    // The ninth to eleventh sets' mixtures first ran under the names of earlier sets' (different)
    // mixtures, "weibull mixture k=5", "k=3.5" and "k=4.5"; their per-curve files in
    // bench/results/calibration keep those names.
    // Fixed before the filter's edge was left out of the energy-rate search (white noise).
    {"held-out-9", 1.6, 8, 0.05, 0.45, 0.55, 3.5, {"weibull mixture k=5 50/50 x1.3", 0.5, 5.0, 1.3, 1.9}},
    // Fixed after held-out 9 failed the first form of that change, before the second was run
    // anywhere. Its log-normal law is broad (σ = 0.7: ℰ's maximum early in the record).
    {"held-out-10", 2.8, 1.5, 0.1, 0.8, 0.7, 2.0, {"weibull mixture k=3.5 30/70 x1.4", 0.3, 3.5, 1.4, 2.4}},
    // Fixed after a review found the second form acting at the start of every bootstrap window, before
    // the form restricted to the record's own edge was run anywhere.
    {"held-out-11", 3.2, 2.5, 0.12, 0.9, 0.38, 4.5, {"weibull mixture k=4.5 60/40 x1.6", 0.6, 4.5, 1.6, 2.4}},
    // Fixed before the random walk's step profile (BootstrapOptions::walk_profile) was checked
    // anywhere but the tuning set (bundles, walk-profile).
    {"held-out-12", 2.4, 3.5, 0.08, 0.7, 0.42, 7.0, {"weibull mixture k=3.8 45/55 x1.45", 0.45, 3.8, 1.45, 2.3}},
    // Fixed before the walk profile read from the curve's falling stiffness (add_walk_profiles) was
    // checked anywhere but the tuning set (bundles, walk-profile).
    {"held-out-13", 4.4, 4.5, 0.06, 0.65, 0.32, 5.5, {"weibull mixture k=5 35/65 x1.5", 0.35, 5.0, 1.5, 2.3}},
    // Fixed after held-out 13 missed its rule by 0.2 % and before the random-walk factors learned on
    // the tuning set and held-out 13 pooled were checked anywhere (bundles, walk-profile).
    {"held-out-14", 2.6, 5.5, 0.04, 0.5, 0.48, 3.8, {"weibull mixture k=4.2 55/45 x1.35", 0.55, 4.2, 1.35, 2.1}},
    // Twelve shapes in two rows of one name, fixed after held-outs 13 and 14 showed a set of six
    // shapes moving the coverage by ±5 points, and before the random-walk factors learned on the
    // tuning set and held-outs 13 and 14 pooled were checked anywhere (bundles, walk-profile). Each
    // parameter drawn at random within its family's range (Python's random.Random(15), two
    // significant digits, names not used before); its uniform laws have a < 0.07 b.
    {"held-out-15", 5.8, -0.38, 0.048, 0.85, 0.59, 2.1, {"weibull mixture k=5 65/35 x1.55", 0.65, 5.0, 1.55, 2.3}},
    {"held-out-15", 4.7, 2.4, 0.041, 0.59, 0.54, 7.2, {"weibull mixture k=3.7 62/38 x1.57", 0.62, 3.7, 1.57, 2.6}},
    // Twelve shapes drawn the same way (random.Random(16)), fixed after held-out 15 failed only its
    // acceptance rule and a record whose whole noise fit is zero was first read on its loading part,
    // and before that reading and the walk profile with held-out 15's factors were checked together
    // anywhere (bundles, walk-profile). Its uniform laws have a < 0.17 b.
    {"held-out-16", 3.1, 3.9, 0.07, 0.7, 0.46, 3.6, {"weibull mixture k=3 55/45 x1.36", 0.55, 3.0, 1.36, 2.6}},
    {"held-out-16", 2.1, 7.3, 0.1, 0.62, 0.58, 7.4, {"weibull mixture k=5 62/38 x1.26", 0.62, 5.0, 1.26, 1.9}},
    // Twelve shapes drawn by bench/draw_held_out.py 17, fixed after rule 4 let the walk profile ship
    // and before estimates without the bootstrap's half-bias correction on random-walk curves, with
    // factors learned on the tuning set and held-outs 15 and 16 pooled, were checked anywhere (bundles).
    {"held-out-17", 3.8, 9.6, 0.098, 0.61, 0.24, 2.2, {"weibull mixture k=5.2 45/55 x1.3", 0.45, 5.2, 1.3, 1.9}},
    {"held-out-17", 2.9, 8.4, 0.095, 0.97, 0.22, 6.9, {"weibull mixture k=3.5 65/35 x1.5", 0.65, 3.5, 1.5, 2.6}},
    // Twelve shapes drawn by bench/draw_held_out.py 18, fixed before the peak fits' own error and the
    // x_c and x_p interval factors learned on the tuning set were checked anywhere (all groups).
    {"held-out-18", 2.3, 6.4, 0.04, 0.63, 0.39, 4.7, {"weibull mixture k=3.8 41/59 x1.5", 0.41, 3.8, 1.5, 2.5}},
    {"held-out-18", 4.5, 7.8, 0.18, 0.93, 0.29, 3.4, {"weibull mixture k=4.7 59/41 x1.3", 0.59, 4.7, 1.3, 2}},
    // Twelve shapes drawn by bench/draw_held_out.py 19, fixed before x_c's and x_p's interval
    // factors learned on the tuning set and held-out 18 pooled were checked anywhere (all groups).
    {"held-out-19", 3.3, 1.1, 0.044, 0.59, 0.33, 2.6, {"weibull mixture k=3.9 43/57 x1.4", 0.43, 3.9, 1.4, 2.3}},
    {"held-out-19", 3.9, 3.6, 0.14, 0.85, 0.37, 6.4, {"weibull mixture k=4.2 60/40 x1.5", 0.6, 4.2, 1.5, 2.4}},
    // Twelve shapes drawn by bench/draw_held_out.py 20, fixed before x_c's white and x_p's factors
    // learned on the tuning set and held-outs 18 and 19 pooled were checked anywhere (all groups).
    {"held-out-20", 5.6, 6.7, 0.16, 0.87, 0.56, 5.4, {"weibull mixture k=4.2 37/63 x1.6", 0.37, 4.2, 1.6, 2.5}},
    {"held-out-20", 3.4, 6.1, 0.1, 0.89, 0.23, 3.1, {"weibull mixture k=3.9 58/42 x1.5", 0.58, 3.9, 1.5, 2.5}},
    // Twelve shapes drawn by bench/draw_held_out.py 21, fixed before x_c's and x_p's white and x_c's
    // random-walk factors learned on the tuning set and held-outs 18 to 20 pooled were checked anywhere.
    {"held-out-21", 4.6, 6.2, 0.047, 0.71, 0.52, 6.8, {"weibull mixture k=4.5 50/50 x1.3", 0.5, 4.5, 1.3, 2}},
    {"held-out-21", 4.1, 0.23, 0.062, 0.89, 0.21, 2.7, {"weibull mixture k=4.1 68/32 x1.3", 0.68, 4.1, 1.3, 2.1}},
    // Twelve shapes drawn by bench/draw_held_out.py 22, fixed before δ_x's random-walk factors learned
    // on the tuning set and held-outs 16 to 21 pooled were checked anywhere (all groups).
    {"held-out-22", 5.5, 1.9, 0.083, 0.98, 0.44, 7.6, {"weibull mixture k=5.8 57/43 x1.5", 0.57, 5.8, 1.5, 2.1}},
    {"held-out-22", 1.7, 8.8, 0.064, 0.77, 0.28, 7.1, {"weibull mixture k=5.8 53/47 x1.5", 0.53, 5.8, 1.5, 2.1}},
    // Twelve shapes drawn by bench/draw_held_out.py 23, fixed before x_p's random-walk factors learned
    // on the tuning set and held-outs 18 to 22 pooled were checked anywhere (all groups).
    {"held-out-23", 5.7, 9.5, 0.042, 0.94, 0.41, 2.8, {"weibull mixture k=4.3 38/62 x1.3", 0.38, 4.3, 1.3, 2}},
    {"held-out-23", 1.9, 4.9, 0.077, 0.85, 0.51, 5.9, {"weibull mixture k=5.9 55/45 x1.4", 0.55, 5.9, 1.4, 1.9}},
    // Twelve shapes drawn by bench/draw_held_out.py 24, fixed before the quiet curves' reading
    // (scored_as_random_walk) and x_c's white factors learned on held-outs 22 and 23 were checked.
    {"held-out-24", 5.3, 1.4, 0.063, 1, 0.47, 6.5, {"weibull mixture k=5.1 36/64 x1.5", 0.36, 5.1, 1.5, 2.2}},
    {"held-out-24", 4.9, 4.1, 0.18, 0.93, 0.26, 5.3, {"weibull mixture k=5.7 45/55 x1.6", 0.45, 5.7, 1.6, 2.2}},
    // Twelve shapes drawn by bench/draw_held_out.py 25, fixed before x_p's white factors that follow
    // the measured noise level (learned on held-outs 20 to 24) were checked anywhere (all groups and
    // white-between: white noise at 0.5 and 2 %, levels no learning set holds).
    {"held-out-25", 5.4, -0.055, 0.071, 0.97, 0.53, 5.1, {"weibull mixture k=4.9 62/38 x1.5", 0.62, 4.9, 1.5, 2.2}},
    {"held-out-25", 3.6, 0.59, 0.14, 0.99, 0.43, 4.8, {"weibull mixture k=4.7 33/67 x1.4", 0.33, 4.7, 1.4, 2.1}},
    // Twelve shapes drawn by bench/draw_held_out.py 26, fixed before x_p's white factors below 0.2 %
    // (learned on held-outs 20 to 24 at 0.06 and 0.1 %) were checked anywhere (white-low and
    // white-low-between: white noise at 0.06, 0.08, 0.1 and 0.14 %).
    {"held-out-26", 4.2, 0.096, 0.14, 0.88, 0.36, 6.7, {"weibull mixture k=3.1 69/31 x1.6", 0.69, 3.1, 1.6, 3}},
    {"held-out-26", 5.2, -0.18, 0.078, 0.98, 0.49, 2.3, {"weibull mixture k=4.1 46/54 x1.5", 0.46, 4.1, 1.5, 2.4}},
    // Twelve shapes drawn by bench/draw_held_out.py 27, fixed before factors for curves cut by a sharp
    // collapse (learned on the tuning set's brittle groups) were checked anywhere (brittle); run once
    // for them (docs/analysis.md, "Intervals of a curve cut by a collapse").
    {"held-out-27", 3.7, 0.25, 0.12, 0.95, 0.34, 6.2, {"weibull mixture k=3.3 51/49 x1.4", 0.51, 3.3, 1.4, 2.5}},
    {"held-out-27", 2.7, 1.3, 0.032, 0.98, 0.27, 4.1, {"weibull mixture k=4.6 51/49 x1.3", 0.51, 4.6, 1.3, 2}},
    // Twelve shapes drawn by bench/draw_held_out.py 28, fixed before any interval of curves cut by a
    // sharp collapse was learned after held-out 27; run once, on the dem-like groups, to check x_c's
    // corner form (docs/analysis.md, "Known answers with a DEM-like top").
    {"held-out-28", 5.9, 2.8, 0.051, 0.99, 0.31, 6.1, {"weibull mixture k=3 35/65 x1.5", 0.35, 3, 1.5, 2.9}},
    {"held-out-28", 4.3, 2.2, 0.14, 0.74, 0.57, 3.9, {"weibull mixture k=5.3 57/43 x1.4", 0.57, 5.3, 1.4, 2}},
    // Twelve shapes drawn by bench/draw_held_out.py 29, fixed before x_p's random-walk factors learned
    // on held-outs 23 to 25 were checked, with every shipped factor on the code of this release; run
    // once (docs/analysis.md, "x_p's random-walk factors from the three latest sets, checked on held-out 29").
    {"held-out-29", 4.8, 4.2, 0.056, 0.54, 0.537, 3.3, {"weibull mixture k=4.8 60/40 x1.4", 0.6, 4.8, 1.4, 2.1}},
    {"held-out-29", 5.1, 5.8, 0.2, 0.98, 0.219, 7.7, {"weibull mixture k=4.8 46/54 x1.3", 0.46, 4.8, 1.3, 1.9}},
    // Twelve shapes drawn by bench/draw_held_out.py 30, fixed before the bootstrap's noise read on the
    // loading (docs/analysis.md, "The bootstrap's noise read on the loading") was checked with every
    // shipped factor (all groups, brittle and run-like); run once for it.
    {"held-out-30", 3.27, 0.77, 0.036, 0.49, 0.423, 7.3, {"weibull mixture k=3.3 34/66 x1.4", 0.34, 3.3, 1.4, 2.5}},
    {"held-out-30", 5.54, 3.1, 0.13, 0.9, 0.242, 7.9, {"weibull mixture k=3.2 69/31 x1.4", 0.69, 3.2, 1.4, 2.6}},
    // Twelve shapes drawn by bench/draw_held_out.py 31, fixed before the smoothing floor
    // (docs/analysis.md, "The smoothing floor") was checked with every shipped factor (all groups) and
    // against the filter before it (all, dem-like, brittle and run-like); run once for it.
    {"held-out-31", 1.57, 9.1, 0.024, 0.61, 0.409, 5.2, {"weibull mixture k=5.7 65/35 x1.3", 0.65, 5.7, 1.3, 1.8}},
    {"held-out-31", 3.39, 7.4, 0.088, 0.98, 0.313, 5.6, {"weibull mixture k=4.3 35/65 x1.3", 0.35, 4.3, 1.3, 2}},
    // Twelve shapes drawn by bench/draw_held_out.py 32, fixed before the intervals of curves cut by a
    // collapse were learned by the collapse's closeness to the force peak (docs/analysis.md, "Intervals
    // of a curve cut by a collapse, by how close it comes"); run once for their check.
    {"held-out-32", 3.98, -0.0036, 0.095, 0.72, 0.508, 3.7, {"weibull mixture k=4.9 49/51 x1.5", 0.49, 4.9, 1.5, 2.2}},
    {"held-out-32", 2.13, 9.3, 0.16, 0.99, 0.526, 2.4, {"weibull mixture k=4.5 47/53 x1.4", 0.47, 4.5, 1.4, 2.2}},
    // Twelve shapes drawn by bench/draw_held_out.py 33, fixed before the force's window ending at a
    // collapse's onset where the raw rows top out there (docs/analysis.md, "The study scan's points: two
    // ways to top out", the fourth form) was checked against the shipped analysis; run once for it.
    {"held-out-33", 4.67, 1.7, 0.058, 0.84, 0.405, 6.3, {"weibull mixture k=4 45/55 x1.6", 0.45, 4, 1.6, 2.6}},
    {"held-out-33", 5.37, 9.2, 0.18, 0.97, 0.565, 4.3, {"weibull mixture k=3.2 40/60 x1.3", 0.4, 3.2, 1.3, 2.4}},
    // Twelve shapes drawn by bench/draw_held_out.py 34, fixed before the smoothing floor bounded by the
    // peaks' distance was checked against the discrepancy rule alone (docs/analysis.md, "The smoothing
    // floor bounded by the peaks' distance"); run once for it.
    {"held-out-34", 2.82, -0.47, 0.064, 0.53, 0.322, 7.5, {"weibull mixture k=3.2 36/64 x1.5", 0.36, 3.2, 1.5, 2.7}},
    {"held-out-34", 1.79, -0.12, 0.073, 0.67, 0.321, 5.7, {"weibull mixture k=3.9 67/33 x1.4", 0.67, 3.9, 1.4, 2.3}},
    // Twelve shapes drawn by bench/draw_held_out.py 35, fixed before the factors of x_c under white noise,
    // of δ_x and x_p on a random walk and x_p's white level model were learned again on held-outs 29 to 31
    // and 34 (docs/analysis.md, "Four failed factors learned again on three or four sets pooled, checked on
    // held-out 35"); run once for them.
    {"held-out-35", 2.71, 3.2, 0.04, 0.46, 0.206, 4.9, {"weibull mixture k=5.5 32/68 x1.5", 0.32, 5.5, 1.5, 2.1}},
    {"held-out-35", 4.65, 0.51, 0.13, 0.95, 0.578, 5.8, {"weibull mixture k=5.5 39/61 x1.4", 0.39, 5.5, 1.4, 2}},
    // Twelve shapes drawn by bench/draw_held_out.py 36, fixed before the factors of curves cut by a
    // collapse were learned again on held-outs 32 to 34 run at this code (docs/analysis.md, "The factors of
    // curves cut by a collapse learned again on three sets, checked on held-out 36"); run once for them.
    {"held-out-36", 5.06, 4.3, 0.094, 0.65, 0.563, 4.6, {"weibull mixture k=4.5 55/45 x1.3", 0.55, 4.5, 1.3, 2}},
    {"held-out-36", 3.69, 5.3, 0.082, 0.66, 0.493, 3.2, {"weibull mixture k=3.6 43/57 x1.4", 0.43, 3.6, 1.4, 2.4}},
    // Twelve shapes drawn by bench/draw_held_out.py 37, fixed before the factors of curves cut by a
    // collapse were learned again on held-outs 32 to 34 with F's walk taken from E_e's where F rings
    // (docs/analysis.md, "F's walk taken from E_e's where F rings, checked on held-out 37"); run once
    // for them.
    {"held-out-37", 2.39, 0.79, 0.15, 0.81, 0.555, 7.8, {"weibull mixture k=3.3 62/38 x1.4", 0.62, 3.3, 1.4, 2.5}},
    {"held-out-37", 4.06, 5.2, 0.13, 0.81, 0.503, 6.6, {"weibull mixture k=3.9 58/42 x1.4", 0.58, 3.9, 1.4, 2.3}},
    // Twelve shapes drawn by bench/draw_held_out.py 38, fixed before the run-like and dem-like groups of
    // held-outs 32 to 34 were run again with the walk read on rows that are means by its own term
    // (docs/analysis.md, "The walk read on rows that are means, checked on held-out 38"); run once for them.
    {"held-out-38", 4.22, 8.7, 0.11, 0.97, 0.429, 4.4, {"weibull mixture k=3.3 58/42 x1.6", 0.58, 3.3, 1.6, 2.9}},
    {"held-out-38", 4.51, 8.9, 0.12, 0.89, 0.316, 2.9, {"weibull mixture k=4.2 41/59 x1.4", 0.41, 4.2, 1.4, 2.2}},
    {"held-out-39", 3.78, 2.9, 0.13, 0.86, 0.467, 4.2, {"weibull mixture k=5.7 68/32 x1.5", 0.68, 5.7, 1.5, 2.1}},
    {"held-out-39", 4.83, 3.7, 0.13, 0.76, 0.296, 7.36, {"weibull mixture k=5.2 32/68 x1.5", 0.32, 5.2, 1.5, 2.2}},
};
// clang-format on

// The nine shapes of the calibration table.
inline std::vector<Shape> shapes() {
  return {weibull(2),    weibull(3),        weibull(5),      power_law(-0.5),  power_law(3),
          power_law(10), uniform(0.2, 1.0), log_normal(0.3), weibull_mixture()};
}

inline double force_of(const Shape& s, double x) { return x * (1.0 - s.cdf(x)); }
inline double energy_of(const Shape& s, double x) { return 0.5 * x * x * (1.0 - s.cdf(x)); }
inline double rate_of(const Shape& s, double x) { return x * (1.0 - s.cdf(x)) - 0.5 * x * x * s.pdf(x); }

// The maximum of f on [0, x_end]: a dense scan, then Brent's method around the best sample.
inline double argmax(const std::function<double(double)>& f, double x_end) {
  const int n = 20000;
  int best = 1;
  for (int i = 1; i < n; ++i) {
    if (f(x_end * i / n) > f(x_end * best / n)) best = i;
  }
  const auto r = boost::math::tools::brent_find_minima([&](double x) { return -f(x); },
                                                       x_end * (best - 1) / n, x_end * (best + 1) / n, 52);
  return r.first;
}

inline Truth truth(const Shape& s) {
  Truth t;
  t.x_c = argmax([&](double x) { return force_of(s, x); }, s.x_end);
  t.x_p = argmax([&](double x) { return rate_of(s, x); }, s.x_end);
  t.x_m = argmax([&](double x) { return energy_of(s, x); }, s.x_end);
  t.F_c = force_of(s, t.x_c);
  t.E_max = energy_of(s, t.x_m);
  t.Erate_max = rate_of(s, t.x_p);
  return t;
}

inline Curve exact_curve(const Shape& s, std::size_t rows) {
  Curve c;
  c.source = s.name;
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (std::size_t i = 0; i < rows; ++i) {
    const double x = s.x_end * static_cast<double>(i) / static_cast<double>(rows - 1);
    c.strain.push_back(x);
    c.force.push_back(force_of(s, x));
    c.energy.push_back(energy_of(s, x));
  }
  return c;
}

// Independent Gaussian noise of `level` times each curve's peak on F and on E_e.
inline Curve white_noise_curve(const Shape& s, std::size_t rows, double level, std::uint64_t seed) {
  Curve c = exact_curve(s, rows);
  const auto t = truth(s);
  Rng rng(seed, RandomStream::analysis_noise, 7);
  for (std::size_t i = 0; i < rows; ++i) {
    c.force[i] += level * t.F_c * rng.normal();
    c.energy[i] += level * t.E_max * rng.normal();
  }
  c.source += " white";
  return c;
}

// The thresholds of a bundle of `fibers` fibers drawn from the shape (by bisection on the CDF), per
// N κ = 1, sorted. The uniforms are drawn in order and each is inverted on its own, so the inversions
// (60 CDF calls a fiber: most of a 10⁶-fiber group's time) run in parallel and give the same bundle for
// any thread count.
inline std::vector<double> bundle_thresholds(const Shape& s, std::size_t fibers, std::uint64_t seed) {
  Rng rng(seed, RandomStream::analysis_noise, 8);
  std::vector<double> thresholds(fibers);
  for (auto& th : thresholds) th = rng.uniform01();
  const auto count = static_cast<std::ptrdiff_t>(fibers);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const double u = thresholds[std::size_t(k)];
    double lo = 0.0, hi = s.x_end * 4.0;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (s.cdf(mid) < u ? lo : hi) = mid;
    }
    thresholds[std::size_t(k)] = 0.5 * (lo + hi);
  }
  std::sort(thresholds.begin(), thresholds.end());
  return thresholds;
}

// A strain-controlled bundle of `fibers` fibers (bundle_thresholds) at `rows` strains.
inline Curve finite_bundle_curve(const Shape& s, std::size_t rows, std::size_t fibers, std::uint64_t seed) {
  return bundle_curve(bundle_thresholds(s, fibers, seed), rows, s.x_end, s.name + " bundle");
}

// How a run-like curve is recorded (run_like_curve).
struct RunRows {
  std::size_t every = 0;  // steps between rows; 0: not run-like
  bool means = false;     // each row the means over its interval (rupture run's *_mean columns)
  double ring = 0.0;      // rms of F's ringing over [0.7, 0.95] x_c, fraction of F_c
  bool collapse = false;  // the sample comes apart at 1.03-1.2 x_c (drawn per curve)
  bool sag = false;       // with collapse: F sags from x_c to a collapse at 1.02-1.06 x_c (run_like_sag)
};

// How a tissue's force tops out (the study's five dense runs, docs/analysis.md): F rises to a kink,
// 0.2-1 F_c/x_c steep on its left (a bundle's top is flat there), and sags 2-5 % to the collapse at
// 1.03-1.06 x_c while E_e still rises to just before it. A sagging run-like curve loses, beyond the
// bundle's own breaks, fibres at a steady rate in strain from a kink on (a Poisson count of breaks a
// step, each kicking F's ringing as the bundle's own breaks do): the rate that holds F level there,
// plus an excess drawn in [0.5, 1.5] times the fibres intact at the kink per x_c. The kink is drawn in
// [0.82, 0.94] of the law's x_c, but at least 0.05 x_c past x_p (capped at x_c), so that ℰ's maximum
// stays the law's; the collapse comes at b times the kink, b in [1.02, 1.06]: the sag there is 1-9 %.
struct Sag {
  double kink = 0.0;  // strain where the extra breaking starts: the curve's x_c
  double rate = 0.0;  // extra breaks per unit strain (level + excess), share of the fibres intact at the kink
  double cut = 0.0;   // strain where the sample comes apart
};
inline Sag run_like_sag(const Shape& s, std::uint64_t seed) {
  Rng rng(seed, RandomStream::analysis_noise, 13);
  const Truth law = truth(s);
  const double kink =
      std::max(rng.uniform(0.82, 0.94) * law.x_c, std::min(law.x_p + 0.05 * law.x_c, law.x_c));
  const double survive = 1.0 - s.cdf(kink);
  // F = x I with I' = -pdf - rate I(kink): level at the kink for rate = 1/kink - pdf/I.
  const double level = std::max(0.0, 1.0 / kink - s.pdf(kink) / survive);
  const double excess = rng.uniform(0.5, 1.5) / law.x_c;
  return {kink, level + excess, rng.uniform(1.02, 1.06) * kink};
}

// The intact share of a sagging run-like curve's mean (run_like_sag) at strain x.
inline double sagging_intact(const Shape& s, const Sag& sag, double x) {
  const double extra = x > sag.kink ? sag.rate * (1.0 - s.cdf(sag.kink)) * (x - sag.kink) : 0.0;
  return 1.0 - s.cdf(x) - extra;
}

// Where run_like_curve's sample comes apart: b x_c, b drawn in [1.03, 1.2] (with a sag: run_like_sag).
inline double run_like_cut(const Shape& s, std::uint64_t seed, bool sag = false) {
  if (sag) return run_like_sag(s, seed).cut;
  Rng rng(seed, RandomStream::analysis_noise, 12);
  return rng.uniform(1.03, 1.2) * truth(s).x_c;
}

// The truth of a run-like curve: the law's, or with a sag that of its mean up to the collapse.
inline Truth run_like_truth(const Shape& s, std::uint64_t seed, const RunRows& rows) {
  if (!rows.sag) return truth(s);
  const Sag sag = run_like_sag(s, seed);
  const auto force = [&](double x) { return x * sagging_intact(s, sag, x); };
  const auto energy = [&](double x) { return 0.5 * x * x * sagging_intact(s, sag, x); };
  const auto rate = [&](double x) {
    const double slope = -s.pdf(x) - (x > sag.kink ? sag.rate * (1.0 - s.cdf(sag.kink)) : 0.0);
    return force(x) + 0.5 * x * x * slope;
  };
  Truth t;
  t.x_c = argmax(force, sag.cut);
  t.x_p = argmax(rate, sag.cut);
  t.x_m = argmax(energy, sag.cut);
  t.F_c = force(t.x_c);
  t.E_max = energy(t.x_m);
  t.Erate_max = rate(t.x_p);
  return t;
}

// The tissue's lowest mode as a damped oscillator sampled once a step (period `period` steps, quality
// 10): out[k] from the two before it and the step's drive.
struct StepOscillator {
  double pull, damping;
  explicit StepOscillator(double period) {
    constexpr double pi = 3.14159265358979323846, quality = 10.0;
    const double omega = 2.0 * pi / period, decay = std::exp(-omega / (2.0 * quality));
    pull = 2.0 * decay * std::cos(omega);
    damping = decay * decay;
  }
  void step(std::vector<double>& out, std::size_t k, double drive) const {
    out[k] = pull * out[k - 1] - damping * out[k - 2] + drive;
  }
};

// run_like_curve's every step (100,000 of them): strain, F with its ringing, E_e.
inline Curve run_like_steps(const Shape& s, std::size_t fibers, const RunRows& rows, std::uint64_t seed) {
  constexpr std::size_t steps = 100000, collapse_steps = 1000;
  const auto thresholds = bundle_thresholds(s, fibers, seed);
  Rng rng(seed, RandomStream::analysis_noise, 11);
  const StepOscillator mode(rng.uniform(250.0, 450.0));
  const auto t = truth(s);
  if (rows.sag && !rows.collapse) throw std::invalid_argument("run_like_steps: a sag needs its collapse");
  // The sag's breaks: a Poisson process in their expected count, arrivals one exponential apart.
  const Sag sag = rows.sag ? run_like_sag(s, seed) : Sag{2.0 * s.x_end, 0.0, 0.0};
  const double cut = !rows.collapse ? 2.0 * s.x_end : rows.sag ? sag.cut : run_like_cut(s, seed);
  Rng sag_rng(seed, RandomStream::analysis_noise, 14);
  double sag_expected = 0.0, sag_next = -std::log(sag_rng.uniform01_open_zero()), sag_broken = 0.0;
  std::size_t intact_at_kink = 0;
  Curve c;
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  auto &x = c.strain, &force = c.force, &energy = c.energy;
  x.resize(steps + 1);
  force.resize(steps + 1);
  energy.resize(steps + 1);
  std::vector<double> ring(steps + 1, 0.0), after(steps + 1, 0.0);
  std::size_t broken = 0, cut_step = 0, ring_samples = 0;
  double ring_squares = 0.0, after_squares = 0.0;
  for (std::size_t k = 0; k <= steps; ++k) {
    x[k] = s.x_end * static_cast<double>(k) / static_cast<double>(steps);
    double kick = 0.0;
    if (x[k] < cut) {
      for (; broken < thresholds.size() && thresholds[broken] <= x[k]; ++broken) kick += rng.normal();
      if (x[k] > sag.kink) {
        if (intact_at_kink == 0) intact_at_kink = thresholds.size() - broken;
        sag_expected += sag.rate * double(intact_at_kink) * (x[k] - x[k - 1]);
        for (; sag_next <= sag_expected; sag_next -= std::log(sag_rng.uniform01_open_zero())) {
          sag_broken += 1.0;
          kick += sag_rng.normal();
        }
      }
      const double intact =
          1.0 - (static_cast<double>(broken) + sag_broken) / static_cast<double>(thresholds.size());
      force[k] = x[k] * intact;
      energy[k] = 0.5 * x[k] * x[k] * intact;
    } else {
      // The sample comes apart: every fibre left breaks at once, F falls towards 7 % of its value and
      // E_e towards 30 % (the pieces' stored energy) by e every collapse_steps, and the pieces ring on.
      if (cut_step == 0) {
        cut_step = k;
        broken = thresholds.size();
      }
      const double fall = std::exp(-static_cast<double>(k + 1 - cut_step) / double(collapse_steps));
      force[k] = force[cut_step - 1] * (0.07 + 0.93 * fall);
      energy[k] = energy[cut_step - 1] * (0.3 + 0.7 * fall);
      if (k >= cut_step + 2) mode.step(after, k, rng.normal());
      after_squares += after[k] * after[k];
    }
    if (k >= 2) mode.step(ring, k, kick);
    if (x[k] >= 0.7 * t.x_c && x[k] <= 0.95 * t.x_c) {
      ring_squares += ring[k] * ring[k];
      ++ring_samples;
    }
  }
  // The pieces ring at 5 times the loading's level (the study's run: F's sd 3-4 % of F_c after it came
  // apart against 0.3-0.6 % before).
  const double scale =
      ring_squares > 0.0 ? rows.ring * t.F_c / std::sqrt(ring_squares / double(ring_samples)) : 0.0;
  const double after_scale =
      after_squares > 0.0 ? 5.0 * rows.ring * t.F_c / std::sqrt(after_squares / double(steps + 1 - cut_step))
                          : 0.0;
  for (std::size_t k = 0; k <= steps; ++k) force[k] += scale * ring[k] + after_scale * after[k];
  return c;
}

// A bundle recorded as `rupture run` records a tissue (docs/analysis.md, "Known answers that ring as
// a run does"): the strain x_end reached in 100,000 steps; F rings as the tissue does once bonds break,
// a damped oscillator of period P steps (drawn in [250, 450]; the reduced tissue's is about 330 at the
// study's dt) and quality 10, kicked by every break with a normal impulse, scaled so that its rms over
// [0.7, 0.95] x_c is `rows.ring` F_c (0.26-0.60 % on five seeds of the study's run); E_e carries the
// bundle's own walk. With `rows.collapse` the sample comes apart at b x_c, b drawn in [1.03, 1.2] (the
// study's five seeds: 1.07-1.10; with `rows.sag`, run_like_sag's): every fibre left breaks in that step, F
// and E_e fall by e every 1,000 steps towards 7 % and 30 % of their values there, and the pieces ring on at 5
// times the loading's level. A row every `rows.every` steps from step 0, each the step's values or, with
// `rows.means`, the means of 20 samples over the row's interval as rupture run takes them (the first row: the
// instant).
inline Curve run_like_curve(const Shape& s, std::size_t fibers, const RunRows& rows, std::uint64_t seed) {
  const Curve steps = run_like_steps(s, fibers, rows, seed);
  const std::size_t stride = std::max<std::size_t>(1, rows.every / 20);
  // A row ending at step `end`: that step's value, or the mean of the samples since the row before.
  const auto row = [&](const std::vector<double>& y, std::size_t end) {
    if (!rows.means || end == 0) return y[end];
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t k = end - rows.every + stride; k <= end; k += stride, ++n) sum += y[k];
    return sum / double(n);
  };
  Curve c;
  c.source = s.name + " run-like";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  c.rows = rows.means ? RowKind::interval_means : RowKind::instants;
  for (std::size_t end = 0; end < steps.strain.size(); end += rows.every) {
    c.strain.push_back(row(steps.strain, end));
    c.force.push_back(row(steps.force, end));
    c.energy.push_back(row(steps.energy, end));
  }
  return c;
}

// The tuning set and the first held-out set split the nine shapes above.
inline bool in_first_held_out(const Shape& s) {
  return s.name.rfind("lognormal", 0) == 0 || s.name == "weibull mixture" || s.name == "powerlaw alpha=10";
}

// A set by the name bench/analysis_calibration takes (tuning, held-out, held-out-2 ... held-out-39,
// all; a held-out name's rows in order); empty for any other name.
inline std::vector<Shape> calibration_set(const std::string& name) {
  std::vector<Shape> chosen;
  for (const auto& set : later_held_out_sets) {
    if (name != set.name) continue;
    const auto row = set.shapes();
    chosen.insert(chosen.end(), row.begin(), row.end());
  }
  if (!chosen.empty() || (name != "tuning" && name != "held-out" && name != "all")) return chosen;
  for (auto& s : shapes())
    if (name == "all" || (name == "held-out") == in_first_held_out(s)) chosen.push_back(s);
  return chosen;
}

// The noise groups of the calibration table: independent white noise at a share of each peak, or a
// finite bundle (random-walk noise), or a bundle whose F also carries white noise.
struct NoiseGroup {
  std::string name;
  double level = 0.0;                       // white noise on F and E_e, fraction of each peak
  std::size_t fibers = 0;                   // finite bundle
  double force_white = 0.0;                 // white noise on F alone, fraction of its peak
  bool collapse = false;                    // a sharp collapse after the force peak (collapse_cut)
  RunRows run{};                            // recorded as a run records a tissue (run_like_curve)
  double cut_from = 1.03, cut_span = 0.47;  // the collapse at b x_c, b drawn in [from, from + span]
};
inline std::vector<NoiseGroup> noise_groups() {
  return {{"white 0.2 %", 0.002, 0},  {"white 1 %", 0.01, 0},      {"white 3 %", 0.03, 0},
          {"bundle N=1e4", 0, 10000}, {"bundle N=1e5", 0, 100000}, {"bundle N=1e6", 0, 1000000}};
}

// White noise at levels between the table's (0.5 and 2 %): no set learned on them, so factors that
// follow the measured noise level are checked where they interpolate (held-out 25 on).
inline std::vector<NoiseGroup> between_noise_groups() {
  return {{"white 0.5 %", 0.005, 0}, {"white 2 %", 0.02, 0}};
}

// White noise below the table's lowest level, where a DEM curve's E_e lies (0-0.09 % of E_max in
// the window on the study's tissue; docs/analysis.md): x_p's factors that follow the noise level
// are learned at 0.06 and 0.1 % (white-low) and checked at 0.08 and 0.14 % (white-low-between) and
// on the anchors' own levels of a set not learned on.
inline std::vector<NoiseGroup> low_noise_groups() {
  return {{"white 0.06 %", 0.0006, 0}, {"white 0.1 %", 0.001, 0}};
}
inline std::vector<NoiseGroup> low_between_noise_groups() {
  return {{"white 0.08 %", 0.0008, 0}, {"white 0.14 %", 0.0014, 0}};
}

// The noise of a DEM curve (docs/analysis.md, held-out 8): E_e a walk (every break drops it), F
// white on top of the same walk (elastic waves at the plates; 0.5-1.2 % of F_c on the default
// study's tissue of 12,600 bonds).
inline std::vector<NoiseGroup> mixed_noise_groups() {
  return {{"bundle N=1e4 + F white 1 %", 0, 10000, 0.01}, {"bundle N=1e5 + F white 1 %", 0, 100000, 0.01}};
}

// A brittle sample's curve: the force and energy held from b x_c on and falling by e every 3 rows, with
// b drawn per curve in [1.03, 1.5] (the default study's run breaks at about 1.07 x_c). Under white
// noise the collapse replaces the exact curve beneath the noise; a bundle is held at its value at
// the cut (docs/analysis.md, "A collapse the filter cannot follow").
inline std::vector<NoiseGroup> brittle_noise_groups() {
  // F: 0.2 % plus 1.99 % on F alone, 2.0 % in all; E_e 0.2 %: the proportions of rupture's own runs.
  return {{"brittle F 2 % E_e 0.2 %", 0.002, 0, 0.0199, true},
          {"brittle white 1 %", 0.01, 0, 0.0, true},
          {"brittle bundle N=1e5 + F white 1 %", 0, 100000, 0.01, true}};
}

// The same three noises with the collapse within 2 % past the force peak (b in [1.0, 1.02]), where
// the force rises into it: three of eight points of the study scan top out so (docs/analysis.md,
// "The study scan's points").
inline std::vector<NoiseGroup> brittle_close_noise_groups() {
  std::vector<NoiseGroup> groups = brittle_noise_groups();
  for (auto& g : groups) {
    g.name.replace(0, std::string("brittle").size(), "brittle close");
    g.cut_from = 1.0;
    g.cut_span = 0.02;
  }
  return groups;
}

// Bundles of 10⁴ fibers recorded as a run records a tissue (run_like_curve): rows every 100, 200 and
// 400 steps, as the instant's values or the means over each row's interval; coming apart after the
// force peak as rupture's tissues do, and (the last six groups) not coming apart. The noise the analysis
// reads on them matches what it reads on the study's run at rows every 100 steps (five seeds, means):
// E_e's walk step 0.07 % of E_max (DEM median 0.06 %, with 1,000 steps over the curve's x_end), F's
// white noise 0.5 % of F_c with F's ringing at 0.8 % of F_c over [0.7, 0.95] x_c (DEM 0.3-0.7 %).
inline std::vector<NoiseGroup> run_like_noise_groups() {
  std::vector<NoiseGroup> groups;
  for (const bool collapse : {true, false})
    for (const std::size_t every : {100, 200, 400})
      for (const bool means : {false, true})
        groups.push_back({"run-like rows every " + std::to_string(every) + (means ? " means" : " samples") +
                              (collapse ? " collapse" : ""),
                          0, 10000, 0.0, false, RunRows{every, means, 0.008, collapse}});
  return groups;
}

// Run-like curves whose force sags before the collapse as a tissue's does (run_like_sag): rows every
// 100, 200 and 400 steps, single samples or means.
inline std::vector<NoiseGroup> dem_like_noise_groups() {
  std::vector<NoiseGroup> groups;
  for (const std::size_t every : {100, 200, 400})
    for (const bool means : {false, true})
      groups.push_back({"dem-like rows every " + std::to_string(every) + (means ? " means" : " samples"), 0,
                        10000, 0.0, false, RunRows{every, means, 0.008, true, true}});
  return groups;
}

// The dem-like group of rows every `every` steps, as single samples or means, by its name.
inline NoiseGroup dem_like_group(std::size_t every, bool means) {
  const std::string name = "dem-like rows every " + std::to_string(every) + (means ? " means" : " samples");
  for (const auto& g : dem_like_noise_groups())
    if (g.name == name) return g;
  throw std::invalid_argument("no dem-like group '" + name + "'");
}

inline double collapse_cut(const Shape& s, std::uint64_t seed, double from = 1.03, double span = 0.47) {
  Rng rng(seed, RandomStream::analysis_noise, 10);
  return (from + span * rng.uniform01()) * truth(s).x_c;
}
// White noise stays on the collapse (the exact curve beneath it is replaced); a bundle's curve has no
// separate noise and is held at its last sample before the cut.
inline void cut_at_collapse(Curve& c, const Shape& s, double cut, bool white_noise) {
  const double step = c.strain[1] - c.strain[0];
  std::size_t held = 0;
  while (held + 1 < c.strain.size() && c.strain[held + 1] <= cut) ++held;
  const double from = white_noise ? cut : c.strain[held];
  const double force_held = white_noise ? force_of(s, cut) : c.force[held];
  const double energy_held = white_noise ? energy_of(s, cut) : c.energy[held];
  for (std::size_t i = held + 1; i < c.strain.size(); ++i) {
    const double x = c.strain[i], fall = std::exp(-(x - from) / (3.0 * step));
    const double force_noise = white_noise ? c.force[i] - force_of(s, x) : 0.0;
    const double energy_noise = white_noise ? c.energy[i] - energy_of(s, x) : 0.0;
    c.force[i] = force_held * fall + force_noise;
    c.energy[i] = energy_held * fall + energy_noise;
  }
}

// Curve k of a group: the set's shapes in turn, then 300, 1000 and 5000 rows in turn, seed 1000 k + 17.
struct CalibrationCase {
  const Shape& shape;
  std::size_t rows;
  std::uint64_t seed;

  static CalibrationCase at(const std::vector<Shape>& set, int k) {
    const auto index = static_cast<std::size_t>(k);
    constexpr std::size_t rows_choice[] = {300, 1000, 5000};
    return {set[index % set.size()], rows_choice[(index / set.size()) % 3],
            static_cast<std::uint64_t>(1000 * k + 17)};
  }
  Curve draw(const NoiseGroup& g) const {
    Curve c = g.run.every > 0 ? run_like_curve(shape, g.fibers, g.run, seed)
              : g.fibers > 0  ? finite_bundle_curve(shape, rows, g.fibers, seed)
                              : white_noise_curve(shape, rows, g.level, seed);
    if (g.collapse)
      cut_at_collapse(c, shape, collapse_cut(shape, seed, g.cut_from, g.cut_span), g.fibers == 0);
    if (g.collapse) c.source += " collapse";
    if (g.force_white > 0.0) {
      const double F_c = truth(shape).F_c;
      Rng rng(seed, RandomStream::analysis_noise, 9);
      for (double& f : c.force) f += g.force_white * F_c * rng.normal();
      c.source += " + white F";
    }
    return c;
  }
};

}  // namespace rupture::analysis::calibration
