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
  char name[32];
  std::snprintf(name, sizeof name, "weibull k=%g", k);
  return {name, [k](double x) { return x <= 0 ? 0.0 : 1.0 - std::exp(-std::pow(x, k)); },
          [k](double x) { return x <= 0 ? 0.0 : k * std::pow(x, k - 1) * std::exp(-std::pow(x, k)); },
          std::pow(-std::log(0.002), 1.0 / k)};
}

inline Shape power_law(double alpha) {
  char name[32];
  std::snprintf(name, sizeof name, "powerlaw alpha=%g", alpha);
  return {name, [alpha](double x) { return x <= 0   ? 0.0
                                           : x >= 1 ? 1.0
                                                    : std::pow(x, 1 + alpha); },
          [alpha](double x) { return x <= 0 || x >= 1 ? 0.0 : (1 + alpha) * std::pow(x, alpha); }, 1.0};
}

inline Shape uniform(double a, double b) {
  char name[32];
  std::snprintf(name, sizeof name, "uniform [%g,%g]", a, b);
  return {name, [a, b](double x) { return std::clamp((x - a) / (b - a), 0.0, 1.0); },
          [a, b](double x) { return x < a || x > b ? 0.0 : 1.0 / (b - a); }, b};
}

inline Shape log_normal(double sigma) {
  char name[32];
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
  char name[32];
  std::snprintf(name, sizeof name, "gamma k=%g", k);
  return {name, [k](double x) { return x <= 0 ? 0.0 : boost::math::gamma_p(k, k * x); },
          [k](double x) { return x <= 0 ? 0.0 : k * boost::math::gamma_p_derivative(k, k * x); }, 3.0};
}

// 50 % Weibull(k=6, λ=1) + 50 % Weibull(k=6, λ=1.25).
inline Shape weibull_mixture_narrow() { return weibull_mixture("weibull mixture k=6", 0.5, 6.0, 1.25, 1.8); }

// A second held-out set, defined before the first held-out run was looked at in detail and not
// run while the method was changed after it (bench/analysis_calibration held-out-2).
inline std::vector<Shape> second_held_out_shapes() {
  return {weibull(1.5),    power_law(6),   uniform(0.5, 1.0),
          log_normal(0.5), gamma_shape(4), weibull_mixture_narrow()};
}

// 60 % Weibull(k=3, λ=1) + 40 % Weibull(k=3, λ=2).
inline Shape weibull_mixture_wide() { return weibull_mixture("weibull mixture k=3", 0.6, 3.0, 2.0, 3.5); }

// A third held-out set, fixed before the smoothing-sensitivity term was tried
// (bench/analysis_calibration held-out-3).
inline std::vector<Shape> third_held_out_shapes() {
  return {weibull(2.5),    power_law(1),   uniform(0.1, 0.9),
          log_normal(0.2), gamma_shape(8), weibull_mixture_wide()};
}

// A fourth held-out set, fixed before the per-level interval scales were learned on the tuning set
// and run only to check them (bench/analysis_calibration held-out-4).
inline std::vector<Shape> fourth_held_out_shapes() {
  return {weibull(4),      power_law(2),     uniform(0.15, 0.75),
          log_normal(0.4), gamma_shape(2.5), weibull_mixture("weibull mixture k=5", 0.4, 5.0, 1.4, 2.0)};
}

// A fifth held-out set, fixed before the smoothing cap tied to the force peak (docs/analysis.md) was
// tuned, and run only to check it and the interval scales learned after it
// (bench/analysis_calibration held-out-5). Gamma's x_end follows its longer tail.
inline std::vector<Shape> fifth_held_out_shapes() {
  Shape broad_gamma = gamma_shape(1.5);
  broad_gamma.x_end = 4.5;
  return {weibull(6),      power_law(5), uniform(0.3, 0.8),
          log_normal(0.6), broad_gamma,  weibull_mixture("weibull mixture k=3.5", 0.5, 3.5, 1.6, 2.6)};
}

// A sixth held-out set, fixed before the interval scales were learned on the tuning set and the fifth
// set pooled, and run only to check them (bench/analysis_calibration held-out-6). Its domain is the
// smooth ℰ maximum: its uniform law has a < 0.211 b, so its energy-rate peak is not at the threshold floor
// (docs/analysis.md, "Known limits").
inline std::vector<Shape> sixth_held_out_shapes() {
  return {weibull(3.5),     power_law(0.5),   uniform(0.1, 0.6),
          log_normal(0.35), gamma_shape(3.0), weibull_mixture("weibull mixture k=4.5", 0.3, 4.5, 1.3, 2.0)};
}

// A seventh held-out set, fixed after the sixth was scored and before the random-walk interval
// scales were learned on the tuning, fifth and sixth sets pooled; run only to check them
// (bench/analysis_calibration held-out-7 ... bundle). Its power law sits between α = 3 and 5, where
// the bootstrap's spread was least conservative; its uniform law has a < 0.211 b (see below).
inline std::vector<Shape> seventh_held_out_shapes() {
  return {weibull(1.8),     power_law(4),     uniform(0.05, 0.55),
          log_normal(0.25), gamma_shape(5.0), weibull_mixture("weibull mixture k=5.5", 0.6, 5.5, 1.35, 1.9)};
}

// An eighth held-out set, fixed before the analysis read the noise kind quarter by quarter and run
// only to check that reading with the interval scales that ship (bench/analysis_calibration
// held-out-8 ... all; docs/analysis.md). Its uniform law was meant to keep ℰ's maximum off the jump
// at the threshold floor by a < b/3; that is not enough: ℰ's left limit at the floor, a, beats the
// interior maximum b²/(6(b − a)) whenever a > (3 − √3)b/6 ≈ 0.211 b, so here x_p = a = 0.15 (docs/
// analysis.md, "Known limits").
inline std::vector<Shape> eighth_held_out_shapes() {
  return {weibull(2.2),     power_law(7),     uniform(0.15, 0.5),
          log_normal(0.45), gamma_shape(6.0), weibull_mixture("weibull mixture k=4", 0.4, 4.0, 1.5, 2.4)};
}

// The ninth to eleventh sets' mixtures first ran under the names of earlier sets' (different)
// mixtures, "weibull mixture k=5", "k=3.5" and "k=4.5"; their per-curve files in
// bench/results/calibration keep those names.
// A ninth held-out set, fixed before the filter's edge was left out of the energy-rate search and
// run only to check that change (bench/analysis_calibration held-out-9 ... white). Its uniform law
// has a = 0.11 b < 0.211 b: ℰ's maximum is inside, at b/3.
inline std::vector<Shape> ninth_held_out_shapes() {
  return {weibull(1.6),        power_law(8),
          uniform(0.05, 0.45), log_normal(0.55),
          gamma_shape(3.5),    weibull_mixture("weibull mixture k=5 50/50 x1.3", 0.5, 5.0, 1.3, 1.9)};
}

// A tenth held-out set, fixed after held-out 9 failed the first form of that change and before the
// second was run anywhere (bench/analysis_calibration held-out-10 ... white). Its log-normal law is
// broad (σ = 0.7: ℰ's maximum early in the record); its uniform law has a = 0.125 b < 0.211 b.
inline std::vector<Shape> tenth_held_out_shapes() {
  return {weibull(2.8),      power_law(1.5),
          uniform(0.1, 0.8), log_normal(0.7),
          gamma_shape(2.0),  weibull_mixture("weibull mixture k=3.5 30/70 x1.4", 0.3, 3.5, 1.4, 2.4)};
}

// An eleventh held-out set, fixed after a review found the second form acting at the start of every
// bootstrap window, not only at the record's own edge, and before the form restricted to that edge
// was run anywhere (bench/analysis_calibration held-out-11 ... white). Its uniform law has
// a = 0.133 b < 0.211 b.
inline std::vector<Shape> eleventh_held_out_shapes() {
  return {weibull(3.2),       power_law(2.5),
          uniform(0.12, 0.9), log_normal(0.38),
          gamma_shape(4.5),   weibull_mixture("weibull mixture k=4.5 60/40 x1.6", 0.6, 4.5, 1.6, 2.4)};
}

// A twelfth held-out set, fixed before the random walk's step profile (BootstrapOptions::walk_profile)
// was checked anywhere but the tuning set (bench/analysis_calibration held-out-12 ... bundle
// walk-profile; the rule in docs/analysis.md). Its uniform law has a = 0.114 b < 0.211 b.
inline std::vector<Shape> twelfth_held_out_shapes() {
  return {weibull(2.4),       power_law(3.5),
          uniform(0.08, 0.7), log_normal(0.42),
          gamma_shape(7.0),   weibull_mixture("weibull mixture k=3.8 45/55 x1.45", 0.45, 3.8, 1.45, 2.3)};
}

// A thirteenth held-out set, fixed before the walk profile read from the curve's falling stiffness
// (add_walk_profiles) was checked anywhere but the tuning set (bench/analysis_calibration
// held-out-13 ... bundle walk-profile; the rule in docs/analysis.md). Its uniform law has
// a = 0.092 b < 0.211 b.
inline std::vector<Shape> thirteenth_held_out_shapes() {
  return {weibull(4.4),        power_law(4.5),
          uniform(0.06, 0.65), log_normal(0.32),
          gamma_shape(5.5),    weibull_mixture("weibull mixture k=5 35/65 x1.5", 0.35, 5.0, 1.5, 2.3)};
}

// A fourteenth held-out set, fixed after held-out 13 missed its rule by 0.2 % and before the
// random-walk factors learned on the tuning set and held-out 13 pooled were checked anywhere
// (bench/analysis_calibration held-out-14 ... bundle walk-profile; the rule in docs/analysis.md). Its
// uniform law has a = 0.08 b < 0.211 b.
inline std::vector<Shape> fourteenth_held_out_shapes() {
  return {weibull(2.6),       power_law(5.5),
          uniform(0.04, 0.5), log_normal(0.48),
          gamma_shape(3.8),   weibull_mixture("weibull mixture k=4.2 55/45 x1.35", 0.55, 4.2, 1.35, 2.1)};
}

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

// A strain-controlled bundle of `fibers` fibers with thresholds drawn from the shape (by bisection
// on the CDF), per N κ = 1.
inline Curve finite_bundle_curve(const Shape& s, std::size_t rows, std::size_t fibers, std::uint64_t seed) {
  Rng rng(seed, RandomStream::analysis_noise, 8);
  std::vector<double> thresholds(fibers);
  for (auto& th : thresholds) {
    const double u = rng.uniform01();
    double lo = 0.0, hi = s.x_end * 4.0;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (s.cdf(mid) < u ? lo : hi) = mid;
    }
    th = 0.5 * (lo + hi);
  }
  std::sort(thresholds.begin(), thresholds.end());
  return bundle_curve(thresholds, rows, s.x_end, s.name + " bundle");
}

// The tuning set and the first held-out set split the nine shapes above.
inline bool in_first_held_out(const Shape& s) {
  return s.name.rfind("lognormal", 0) == 0 || s.name == "weibull mixture" || s.name == "powerlaw alpha=10";
}

// The held-out sets from the second on, by the name bench/analysis_calibration takes.
struct NamedSet {
  const char* name;
  std::vector<Shape> (*shapes)();
};
inline constexpr NamedSet later_held_out_sets[] = {
    {"held-out-2", second_held_out_shapes},     {"held-out-3", third_held_out_shapes},
    {"held-out-4", fourth_held_out_shapes},     {"held-out-5", fifth_held_out_shapes},
    {"held-out-6", sixth_held_out_shapes},      {"held-out-7", seventh_held_out_shapes},
    {"held-out-8", eighth_held_out_shapes},     {"held-out-9", ninth_held_out_shapes},
    {"held-out-10", tenth_held_out_shapes},     {"held-out-11", eleventh_held_out_shapes},
    {"held-out-12", twelfth_held_out_shapes},   {"held-out-13", thirteenth_held_out_shapes},
    {"held-out-14", fourteenth_held_out_shapes}};

// A set by the name bench/analysis_calibration takes (tuning, held-out, held-out-2 ... held-out-14,
// all); empty for any other name.
inline std::vector<Shape> calibration_set(const std::string& name) {
  for (const auto& set : later_held_out_sets)
    if (name == set.name) return set.shapes();
  std::vector<Shape> chosen;
  if (name != "tuning" && name != "held-out" && name != "all") return chosen;
  for (auto& s : shapes())
    if (name == "all" || (name == "held-out") == in_first_held_out(s)) chosen.push_back(s);
  return chosen;
}

// The noise groups of the calibration table: independent white noise at a share of each peak, or a
// finite bundle (random-walk noise), or a bundle whose F also carries white noise.
struct NoiseGroup {
  std::string name;
  double level = 0.0;        // white noise on F and E_e, fraction of each peak
  std::size_t fibers = 0;    // finite bundle
  double force_white = 0.0;  // white noise on F alone, fraction of its peak
};
inline std::vector<NoiseGroup> noise_groups() {
  return {{"white 0.2 %", 0.002, 0},  {"white 1 %", 0.01, 0},      {"white 3 %", 0.03, 0},
          {"bundle N=1e4", 0, 10000}, {"bundle N=1e5", 0, 100000}, {"bundle N=1e6", 0, 1000000}};
}

// The noise of a DEM curve (docs/analysis.md, held-out 8): E_e a walk (every break drops it), F
// white on top of the same walk (elastic waves at the plates; 0.5-1.2 % of F_c on the default
// study's tissue of 12,600 bonds).
inline std::vector<NoiseGroup> mixed_noise_groups() {
  return {{"bundle N=1e4 + F white 1 %", 0, 10000, 0.01}, {"bundle N=1e5 + F white 1 %", 0, 100000, 0.01}};
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
    Curve c = g.fibers > 0 ? finite_bundle_curve(shape, rows, g.fibers, seed)
                           : white_noise_curve(shape, rows, g.level, seed);
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
