// The pipeline on curves with known answers: analytic FBM bundles (uniform and power law), a curve
// whose force peaks before its energy rate (negative δ_x), rejected shapes, messy sampling, and
// the calibration of the δ_x posterior over many noise seeds.
#include "analysis/analysis.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <tuple>

#include "analysis/option_words.hpp"
#include "calibration_set.hpp"
#include "core/error.hpp"
#include "fbm/power_law.hpp"
#include "io/csv.hpp"
#include "synthetic_curves.hpp"

namespace rupture::analysis {
namespace {

using testing::add_noise;
using testing::force_first_curve;
using testing::power_law_curve;

// A run's curves.csv: the means over each row's interval are read where all three are there and no
// column is named; naming one, or a file without one of them, reads the rows' single samples.
TEST(CurveColumns, ARunsRowMeansAreReadAsASetUnlessAColumnIsNamed) {
  const std::string header =
      "time[s],strain[%],force_top[N],elastic_energy[mJ],strain_mean[%],force_top_mean[N],elastic_energy_"
      "mean[mJ]\n";
  const auto table = io::parse_csv(header + "0,0,0,0,0,0,0\n1,2,3,4,5,6,7\n", "curves.csv");
  const auto means = find_curve_columns(table);
  EXPECT_EQ(std::tuple(means.strain, means.force, means.energy), std::tuple(4u, 5u, 6u));
  EXPECT_EQ(select_curve(table).force_column, "force_top_mean[N]");
  EXPECT_EQ(select_curve(table).rows, RowKind::interval_means);
  ColumnChoice force_named;
  force_named.force = "force_top";
  const auto named = find_curve_columns(table, force_named);
  EXPECT_EQ(std::tuple(named.strain, named.force, named.energy), std::tuple(1u, 2u, 3u));
  EXPECT_EQ(select_curve(table, force_named).rows, RowKind::instants);
  ColumnChoice said_means = force_named;  // a named column whose rows the caller says are means
  said_means.rows = RowKind::interval_means;
  EXPECT_EQ(select_curve(table, said_means).rows, RowKind::interval_means);
  ColumnChoice said_instants;
  said_instants.rows = RowKind::instants;
  EXPECT_EQ(select_curve(table, said_instants).rows, RowKind::instants);
  const auto without = io::parse_csv(
      "strain[%],force_top[N],elastic_energy[mJ],strain_mean[%],force_top_mean[N]\n0,0,0,0,0\n1,2,3,4,5\n",
      "old.csv");
  const auto plain = find_curve_columns(without);
  EXPECT_EQ(std::tuple(plain.strain, plain.force, plain.energy), std::tuple(0u, 1u, 2u));
}

TEST(AnalyzeCurve, UniformBundleRecoversClosedForms) {
  const auto r = analyze_curve(power_law_curve(0.0, 2001), {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_NEAR(r.x_c->value, 0.5, 1e-6);
  EXPECT_NEAR(r.F_c->value, 0.25, 1e-7);
  EXPECT_NEAR(r.x_m->value, 2.0 / 3.0, 1e-6);
  EXPECT_NEAR(r.E_max->value, 2.0 / 27.0, 1e-7);
  EXPECT_NEAR(r.x_p->value, 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(r.Erate_max->value, 1.0 / 6.0, 1e-6);
  EXPECT_NEAR(r.delta_x->value, 1.0 / 6.0, 1e-5);
  EXPECT_NEAR(r.delay->map, 1.0 / 6.0, 1e-5);
  EXPECT_NEAR(r.Gamma->value, 1.0, 1e-4);
  EXPECT_NEAR(r.A_r->value, 4.0 / 3.0, 1e-5);
  ASSERT_TRUE(r.alpha.alpha);
  EXPECT_NEAR(*r.alpha.alpha, 0.0, 1e-3);
  EXPECT_TRUE(*r.alpha.gamma_in_band);
  EXPECT_TRUE(*r.alpha.energy_ratio_in_band);
}

TEST(AnalyzeCurve, PowerLawBundlesRecoverClosedForms) {
  for (double alpha : {1.0, 2.0, 4.0}) {
    const auto expected = fbm::power_law::maxima(alpha);
    const auto r = analyze_curve(power_law_curve(alpha, 4001), {});
    ASSERT_TRUE(r.accepted) << r.rejection;
    EXPECT_NEAR(r.x_c->value, expected.x_c, 2e-4 * expected.x_c) << alpha;
    EXPECT_NEAR(r.F_c->value, expected.F_c, 2e-4 * expected.F_c) << alpha;
    EXPECT_NEAR(r.x_m->value, expected.x_m, 2e-4 * expected.x_m) << alpha;
    EXPECT_NEAR(r.E_max->value, expected.E_max, 2e-4 * expected.E_max) << alpha;
    EXPECT_NEAR(r.x_p->value, expected.x_p, 2e-4 * expected.x_p) << alpha;
    EXPECT_NEAR(r.Erate_max->value, expected.Erate_max, 2e-4 * expected.Erate_max) << alpha;
    // δ_x from the fitted maxima is exact for any shape; the paper's l1 alignment of F with the
    // shifted ℰ (eq. 26, kept as --delay-method shift-l1) sits 2-3 % above it on these skewed peaks.
    EXPECT_NEAR(r.delta_x->value, expected.delta_x, 1e-3 * expected.delta_x) << alpha;
    EXPECT_NEAR(r.delta_x_direct->value, expected.delta_x, 2e-4 * expected.delta_x) << alpha;
    AnalysisOptions l1;
    l1.delay_method = DelayMethod::shift_l1;
    const auto shifted = analyze_curve(power_law_curve(alpha, 4001), l1);
    EXPECT_GT(shifted.delta_x->value, 1.01 * expected.delta_x) << alpha;
    EXPECT_LT(shifted.delta_x->value, 1.035 * expected.delta_x) << alpha;
    EXPECT_NEAR(r.Gamma->value, expected.Gamma, 0.05 * expected.Gamma) << alpha;
    EXPECT_NEAR(r.A_r->value, expected.A_r, 2e-4 * expected.A_r) << alpha;
    ASSERT_TRUE(r.alpha.alpha);
    EXPECT_NEAR(*r.alpha.alpha, alpha, 0.2 * alpha) << alpha;
    EXPECT_TRUE(*r.alpha.energy_ratio_in_band) << alpha;
  }
}

// The walk's step profile serves only curves read as a random walk: a curve read as white keeps the
// stationary steps its white factors were learned with, even where its bootstrap window alone reads
// as a walk (a bundle of the alpha = 3 law whose F also carries white noise, as DEM curves do; the
// profile made its 68 % interval 1.25 times narrower under white factors never learned with it).
TEST(AnalyzeCurve, TheWalkProfileLeavesCurvesReadAsWhiteAlone) {
  const auto c = calibration::CalibrationCase::at(calibration::calibration_set("tuning"), 166)
                     .draw(calibration::mixed_noise_groups().front());
  AnalysisOptions stationary;
  stationary.uncertainty.walk_profile = false;
  const auto profiled = analyze_curve(c, {}), plain = analyze_curve(c, stationary);
  ASSERT_TRUE(profiled.delay && plain.delay) << profiled.rejection;
  EXPECT_FALSE(reads_random_walk(profiled));
  EXPECT_TRUE(random_walk_dominates(profiled.noise_model));  // the window alone reads as a walk
  EXPECT_TRUE(profiled.noise_model.force.walk_profile.empty());
  EXPECT_TRUE(profiled.noise_model.energy.walk_profile.empty());
  EXPECT_EQ(profiled.delay->mean, plain.delay->mean);
  EXPECT_EQ(profiled.delay->ci68_low, plain.delay->ci68_low);
  EXPECT_EQ(profiled.delay->ci95_high, plain.delay->ci95_high);
}

// A finite bundle's noise is a random walk: the analysis reads it so, follows the walk's step profile,
// applies the factors learned with it (docs/analysis.md) and says in analysis.json which it applied;
// the 95 % interval holds the 68 % one.
TEST(AnalyzeCurve, RandomWalkNoiseGetsItsOwnIntervalFactors) {
  const auto c = calibration::finite_bundle_curve(calibration::weibull(3), 1000, 100000, 7);
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_TRUE(reads_random_walk(r));
  const auto j = to_json(r);
  EXPECT_EQ(j["delta_x"]["interval_scales"]["noise"], "random walk");
  EXPECT_EQ(j["delta_x"]["interval_scales"]["ci68"].get<double>(),
            delta_interval_scales.random_walk_profile.level68);
  EXPECT_EQ(j["delta_x"]["interval_scales"]["ci95"].get<double>(),
            delta_interval_scales.random_walk_profile.level95);
  EXPECT_LE(r.delay->ci95_low, r.delay->ci68_low);
  EXPECT_GE(r.delay->ci95_high, r.delay->ci68_high);
  EXPECT_LT(r.delay->ci68_low, r.delay->mean);
  EXPECT_GT(r.delay->ci68_high, r.delay->mean);
}

// A broad law's bundle recorded to almost four times its force peak: on the increments the steps'
// noise hides the slope's shape, so the discrepancy rule alone would smooth over a quarter of the
// record (0.75, about x_c = 0.78) and put δ_x 8-12 % low. The cap ties the smoothing to the rise
// to the peak instead (a scatter of ~4 % remains at 10^5 fibers).
TEST(AnalyzeCurve, RandomWalkSmoothingIsCappedByTheRiseToTheForcePeak) {
  const auto shape = calibration::gamma_shape(2.5);
  const auto truth = calibration::truth(shape);
  const auto c = calibration::finite_bundle_curve(shape, 300, 100000, 1);
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  ASSERT_TRUE(r.force_walk && r.energy_walk);
  AnalysisOptions floored;  // a pure walk keeps the rule's choice on its increments, capped
  floored.smoothing_floor_share = 0.25;
  const auto with_floor = analyze_curve(c, floored);
  EXPECT_FALSE(with_floor.smoothing_floor_applied);
  EXPECT_EQ(with_floor.filter.cutoff, r.filter.cutoff);
  const double samples_to_peak = (r.force_peak->x - r.x0) / r.step;
  const double period = 2.0 / r.filter.cutoff;  // samples
  EXPECT_LE(period, 0.51 * samples_to_peak);
  EXPECT_NEAR(r.delay->mean, truth.delta(), 0.05 * truth.delta());
  AnalysisOptions fixed;  // the uncapped choice, for contrast: the floor's cutoff, 8/(n - 1)
  fixed.filter.cutoff = 8.0 / static_cast<double>(r.resample.output_rows - 1);
  const auto floor = analyze_curve(c, fixed);
  ASSERT_TRUE(floor.delay);
  EXPECT_LT(floor.delay->mean, 0.93 * truth.delta());
  AnalysisOptions uncapped;  // share 0: the automatic choice without the cap is that floor
  uncapped.random_walk_smoothing_share = 0.0;
  const auto free_choice = analyze_curve(c, uncapped);
  ASSERT_TRUE(free_choice.delay);
  EXPECT_GT(2.0 / free_choice.filter.cutoff, 0.51 * samples_to_peak);
  EXPECT_LT(free_choice.delay->mean, 0.93 * truth.delta());
}

// A DEM-like curve (a bundle's walk in both curves, white noise of 1 % of F_c on F alone): F reads
// white and E_e a walk. The one filter, chosen for the walk, smooths this sharp peak hard (δ_x 44 %
// too large here; a filter per curve was tried and not shipped: docs/analysis.md), and the result
// says so; a curve whose two noises agree carries no such warning.
TEST(AnalyzeCurve, ForceAndEnergyWithDifferentNoiseKindsAreWarnedOf) {
  using namespace calibration;
  const auto shape = power_law(3.0);
  const CalibrationCase mixed_case{shape, 1000, 28017};
  const auto r = analyze_curve(mixed_case.draw(mixed_noise_groups()[1]), {});
  EXPECT_FALSE(r.force_walk);
  EXPECT_TRUE(r.energy_walk);
  // F's walk is also lost under its white noise here, which is a second warning (x_c's interval).
  EXPECT_TRUE(force_walk_hidden(r));
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("the noise of F reads as white and that of E_e as a random walk"),
            std::string::npos);
  EXPECT_NE(r.warnings[1].find("fits no random walk in F"), std::string::npos);
  const auto j = to_json(r);
  EXPECT_EQ(j["filter"]["noise_read"]["force"], "white");
  EXPECT_EQ(j["filter"]["noise_read"]["elastic_energy"], "random walk");
  EXPECT_EQ(j["delta_x"]["interval_scales"]["noise"], "random walk");
  for (const NoiseGroup& agreeing :
       {NoiseGroup{"white 1 %", 0.01, 0}, NoiseGroup{"bundle N=1e5", 0, 100000}}) {
    const auto same = analyze_curve(mixed_case.draw(agreeing), {});
    EXPECT_EQ(same.force_walk, same.energy_walk) << agreeing.name;
    EXPECT_TRUE(same.warnings.empty()) << agreeing.name;
  }
}

// Brittle curves (Weibull k = 3, white noise of 2 % on F and 0.2 % on E_e, no walk) cut at 1.35 x_c,
// twelve seeds: read across the collapse, the fall entered F's structure function as a walk of 1.3 %
// of F_c a step and x_c's sd came out at 15 % of x_c. The noise is now read up to the onset: F's
// white noise as it is on every seed, no walk on most (a third fit a small one, 0.3-0.4 % of F_c a
// step, by chance), and x_c's sd (as reported: scaled by its interval's factor) a few percent of x_c at
// most, its 95 % interval holding the truth on at least 10 of the 12 seeds (at exactly 95 % coverage
// fewer happens 2 % of the time; every seed within 2.5 sd, as asked before, 14 %) and no seed beyond 4
// sd.
TEST(AnalyzeCurve, TheNoiseOfACurveCutByACollapseIsReadOnItsLoading) {
  using namespace calibration;
  const Shape s = weibull(3);
  const Truth t = truth(s);
  int without_walk = 0, held = 0;
  std::vector<double> x_c_sd;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    Curve c = white_noise_curve(s, 1000, 0.002, seed);
    cut_at_collapse(c, s, 1.35 * t.x_c, true);
    Rng rng(seed, RandomStream::analysis_noise, 9);
    for (double& f : c.force) f += 0.0199 * t.F_c * rng.normal();
    const auto r = analyze_curve(c, {});
    ASSERT_TRUE(r.accepted) << seed << ": " << r.rejection;
    ASSERT_TRUE(r.collapse_onset) << seed;
    EXPECT_LT(r.noise_span_high, *r.collapse_onset) << seed;
    EXPECT_NEAR(r.noise_model.force.white, 0.02 * t.F_c, 0.003 * t.F_c) << seed;
    if (r.noise_model.force.walk == 0.0) ++without_walk;
    EXPECT_LT(r.x_c->error, 0.06 * t.x_c) << seed;
    EXPECT_NEAR(r.x_c->value, t.x_c, 4.0 * r.x_c->error) << seed;
    if (r.x_c_interval->ci95_low <= t.x_c && t.x_c <= r.x_c_interval->ci95_high) ++held;
    x_c_sd.push_back(r.x_c->error);
  }
  EXPECT_GE(held, 10);
  EXPECT_GE(without_walk, 8);
  std::nth_element(x_c_sd.begin(), x_c_sd.begin() + 6, x_c_sd.end());
  EXPECT_LT(x_c_sd[6], 0.015 * t.x_c);
}

// F peaks at 0.4, ℰ at 0.5: the force maximum comes first, so δ_x = −0.1 and the posterior must
// say so (the prior admits both signs).
TEST(AnalyzeCurve, ForcePeakBeforeEnergyRatePeakGivesNegativeDelay) {
  Curve c = force_first_curve();
  add_noise(c, 0.01, 1e-5, 3);
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.delay);
  EXPECT_NEAR(r.x_c->value, 0.4, 0.005);
  EXPECT_NEAR(r.x_p->value, 0.5, 0.005);
  EXPECT_NEAR(r.delay->mean, -0.1, 0.005);
  EXPECT_LT(r.delay->ci95_high, 0.0);
  AnalysisOptions l1;
  l1.delay_method = DelayMethod::shift_l1;
  const auto shifted = analyze_curve(c, l1);
  ASSERT_TRUE(shifted.delay);
  EXPECT_LT(shifted.delay->prior_low, -0.1);
  EXPECT_NEAR(shifted.delay->mean, -0.1, 0.005);
}

TEST(AnalyzeCurve, RisingCurveIsRejectedBecauseTheForceMaximumIsAtTheEnd) {
  auto c = power_law_curve(0.0, 1001, 0.45);  // stops before x_c = 0.5
  c.strain_unit = "%";
  const auto r = analyze_curve(c, {});
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.rejection.find("force peak: the maximum lies at the end"), std::string::npos) << r.rejection;
  EXPECT_NE(r.rejection.find(" %)"), std::string::npos)
      << "the strain is named with its unit: " << r.rejection;
}

TEST(AnalyzeCurve, FlatCurveIsRejectedAsNotPronounced) {
  Curve c;
  c.source = "flat";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (int i = 0; i <= 1000; ++i) {
    const double x = i / 1000.0;
    c.strain.push_back(x);
    c.force.push_back(1.0 + 0.02 * std::sin(3.0 * x));  // a shallow bump
    c.energy.push_back(x);
  }
  const auto r = analyze_curve(c, {});
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.rejection.find("not pronounced"), std::string::npos) << r.rejection;
}

TEST(AnalyzeCurve, TwoComparableForceMaximaAreRejected) {
  auto c = power_law_curve(0.0, 2001);
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    const double x = c.strain[i];
    c.force[i] = std::exp(-std::pow((x - 0.3) / 0.05, 2)) + 0.95 * std::exp(-std::pow((x - 0.6) / 0.05, 2));
  }
  const auto r = analyze_curve(c, {});
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.rejection.find("several force maxima"), std::string::npos) << r.rejection;
  // The force falls to nothing between the peaks: the loading phase ends there, and the
  // mechanism's count of maxima is the phase's.
  EXPECT_EQ(r.force_maxima, 1);
}

TEST(AnalyzeCurve, DuplicatedAndUnevenSamplesAreResampled) {
  // Uneven strains x = u^1.5, with every tenth row repeated.
  Curve c;
  c.source = "messy";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (int i = 0; i <= 3000; ++i) {
    const double x = std::pow(i / 3000.0, 1.5);
    for (int copy = 0; copy < (i % 10 == 0 ? 2 : 1); ++copy) {
      c.strain.push_back(x);
      c.force.push_back(x * (1.0 - x));
      c.energy.push_back(0.5 * x * x * (1.0 - x));
    }
  }
  const auto r = analyze_curve(c, {});
  EXPECT_TRUE(r.resample.was_sorted);
  EXPECT_EQ(r.resample.duplicates_merged, 301u);
  EXPECT_FALSE(r.resample.was_uniform);
  EXPECT_TRUE(r.resample.resampled);
  EXPECT_EQ(r.resample.output_rows, 3001u);
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_NEAR(r.x_c->value, 0.5, 1e-4);
  EXPECT_NEAR(r.x_p->value, 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(r.delta_x->value, 1.0 / 6.0, 1e-3);
}

// Strain 0 -> 0.36 -> 0.28 -> 0.36 -> 1: sorting would splice the unloading branch into the
// loading; the curve is rejected with the rows where the strain goes back.
TEST(AnalyzeCurve, UnloadingLoopIsRejectedNamingTheRows) {
  const auto whole = power_law_curve(0.0, 1001);
  Curve c = whole;
  c.strain.clear();
  c.force.clear();
  c.energy.clear();
  const auto add = [&](std::size_t i) {
    c.strain.push_back(whole.strain[i]);
    c.force.push_back(whole.force[i]);
    c.energy.push_back(whole.energy[i]);
  };
  for (std::size_t i = 0; i <= 360; ++i) add(i);
  for (std::size_t i = 359; i >= 280; --i) add(i);
  for (std::size_t i = 281; i <= 1000; ++i) add(i);
  const auto r = analyze_curve(c, {});
  EXPECT_FALSE(r.accepted);
  EXPECT_FALSE(r.delta_x);
  EXPECT_NE(r.rejection.find("strain decreases from data row 361 (0.36 1) to row 362"), std::string::npos)
      << r.rejection;
  EXPECT_NE(r.rejection.find("rows 1-361"), std::string::npos) << r.rejection;
}

// After the collapse, the separated halves ring: a spike of ℰ far above its loading maximum.
// x_p, ℰ_max, A_r and δ_x must all come from the loading phase's peak.
TEST(AnalyzeCurve, RingingAfterSeparationIsNotTakenForThePrecursor) {
  auto c = power_law_curve(0.0, 3001, 1.5);
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    const double x = c.strain[i];
    if (x > 1.0) {
      // The force is gone; E_e oscillates with an amplitude of a third of its peak.
      c.force[i] = 0.02 * std::sin(60.0 * x);
      c.energy[i] = 0.03 * (1.0 + std::sin(40.0 * (x - 1.0)));
    }
  }
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_LE(r.loading_phase_end, 1.0);
  EXPECT_NEAR(r.x_p->value, 1.0 / 3.0, 2e-3);
  EXPECT_NEAR(r.Erate_max->value, 2.0 / 9.0 * 0.75, 2e-3);  // ℰ = x - 1.5 x², max 1/6 at 1/3
  EXPECT_NEAR(r.delta_x->value, 1.0 / 6.0, 2e-3);
  EXPECT_LT(r.force_maxima, 2);
}

// With the paper's l1 inversion, a fit whose best scale c is not positive aligns F with the
// negative lobe of ℰ: rejected, never reported.
TEST(AnalyzeCurve, ShiftL1WithANonPositiveScaleIsRejected) {
  // F: a Gaussian at 0.5 (width 0.05). ℰ: a narrow positive peak at 0.2 (width 0.01, so F matches
  // it badly) and a negative lobe at 0.8 with exactly F's shape: the best l1 fit shifts the lobe
  // onto F with c < 0.
  Curve c;
  c.source = "negative-lobe";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const double sqrt_pi = std::sqrt(3.14159265358979323846);
  const auto integral = [&](double x, double centre, double width) {
    return 0.5 * sqrt_pi * width * (std::erf((x - centre) / width) + std::erf(centre / width));
  };
  for (int i = 0; i <= 4000; ++i) {
    const double x = i / 4000.0;
    c.strain.push_back(x);
    c.force.push_back(std::exp(-std::pow((x - 0.5) / 0.05, 2)));
    c.energy.push_back(integral(x, 0.2, 0.01) - 0.5 * integral(x, 0.8, 0.05));
  }
  AnalysisOptions l1;
  l1.delay_method = DelayMethod::shift_l1;
  const auto r = analyze_curve(c, l1);
  EXPECT_FALSE(r.accepted);
  ASSERT_TRUE(r.delay);
  EXPECT_LT(r.delay->scale_at_map, 0.0);
  EXPECT_NE(r.rejection.find("no positive scale c"), std::string::npos) << r.rejection;
}

// One curve of a calibration set, as bench/analysis_calibration draws it, analysed with default
// options, with the truth of its shape; the test names the shape and rows it was written for.
struct AnalysedCase {
  AnalysisResult result;
  calibration::Truth truth;
};
AnalysedCase analyse_set_curve(const std::string& set_name, int k, const calibration::NoiseGroup& group,
                               std::string_view shape, std::size_t rows) {
  const auto set = calibration::calibration_set(set_name);
  const auto curve_case = calibration::CalibrationCase::at(set, k);
  EXPECT_EQ(curve_case.shape.name, shape) << set_name << " curve " << k;
  EXPECT_EQ(curve_case.rows, rows) << set_name << " curve " << k;
  return {analyze_curve(curve_case.draw(group), {}), calibration::truth(curve_case.shape)};
}

// α = 7 under 1 % white noise, 5000 rows (held-out 8's curve 31): the Butterworth filter (cutoff
// 0.017) pins the filtered E_e to its noisy first sample, and over the next ~1/cutoff samples its
// slope reached 1.1, twice ℰ's true maximum (0.55 at x = 0.62): the curve was rejected with "the
// maximum lies at the start of the data". The data's search now starts past that falling edge.
TEST(AnalyzeCurve, TheFiltersEdgeDoesNotWinTheEnergyRateMaximum) {
  const auto [r, t] =
      analyse_set_curve("held-out-8", 31, calibration::noise_groups()[1], "powerlaw alpha=7", 5000);
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_GT(r.x_p->value, 0.5);
  EXPECT_LE(r.delay->ci95_low, t.delta());
  EXPECT_GE(r.delay->ci95_high, t.delta());
}

// Held-out 22's curve 194 (uniform [0.083, 0.98], white 3 %, 1000 rows): the weaker filter's
// measurement fails at the record's start, so it adds no smoothing shift. When it stepped past the
// edge as the data's does (the third form), it found x_p 0.151 away and δ_x's sd went 0.045 ->
// 0.156: the curve was rejected as too uncertain. Only the data's measurement steps past the edge.
TEST(AnalyzeCurve, OnlyTheDatasMeasurementStepsPastTheFiltersEdge) {
  const auto [r, t] =
      analyse_set_curve("held-out-22", 194, calibration::noise_groups()[2], "uniform [0.083,0.98]", 1000);
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_EQ(r.smoothing_shift.x_p, 0.0);
  EXPECT_LT(r.delay->unscaled_sd, 0.06);  // what the acceptance rule reads
  EXPECT_NEAR(r.x_p->value, t.x_p, 0.01);
}

TEST(AnalyzeCurve, TooFewRowsIsBadInput) {
  auto c = power_law_curve(0.0, 10);
  try {
    analyze_curve(c, {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("10 data rows"), std::string::npos) << e.what();
  }
}

// Noise-free curves of every shape in the calibration table: the maxima within 0.2 % and δ_x, Γ, A_r
// within 1 % of the exact ELS values.
TEST(AnalyzeCurve, NoiseFreeCurvesOfEveryShapeRecoverTheirMaxima) {
  using namespace calibration;
  for (const auto& s : shapes()) {
    const Truth t = truth(s);
    const auto r = analyze_curve(exact_curve(s, 2000), {});
    ASSERT_TRUE(r.accepted) << s.name << ": " << r.rejection;
    EXPECT_NEAR(r.x_c->value, t.x_c, 2e-3 * t.x_c) << s.name;
    EXPECT_NEAR(r.x_p->value, t.x_p, 2e-3 * t.x_p) << s.name;
    EXPECT_NEAR(r.x_m->value, t.x_m, 2e-3 * t.x_m) << s.name;
    EXPECT_NEAR(r.delta_x->value, t.delta(), 1e-2 * t.delta()) << s.name;
    EXPECT_NEAR(r.Gamma->value, t.gamma(), 1e-2 * std::abs(t.gamma())) << s.name;
    EXPECT_NEAR(r.A_r->value, t.energy_ratio(), 1e-2 * t.energy_ratio()) << s.name;
  }
}

// An exact curve carries no noise (its third differences are its third derivative, ~1e-8 of it), so the
// smoothing floor leaves its filter, and every number, as they are.
TEST(AnalyzeCurve, TheSmoothingFloorLeavesANoiseFreeCurveAlone) {
  using namespace calibration;
  AnalysisOptions floor;
  floor.smoothing_floor_share = 0.25;
  for (const auto& s : shapes()) {
    const auto c = exact_curve(s, 2000);
    const auto floored = analyze_curve(c, floor), plain = analyze_curve(c, {});
    EXPECT_FALSE(floored.smoothing_floor_applied) << s.name;
    ASSERT_TRUE(floored.x_p && plain.x_p) << s.name;
    EXPECT_EQ(floored.filter.cutoff, plain.filter.cutoff) << s.name;
    EXPECT_EQ(floored.x_p->value, plain.x_p->value) << s.name;
  }
}

// A cubic over a peak that falls much faster after its top than it rises misses the maximum by an
// amount no noise replicate shows (−3.5e-4 at α = 8.4, whatever the rows). The peak fits' own error
// estimates it at x_c, within 15 %, and x_c's and x_p's 95 % intervals hold the truth; without the
// term the sd was 6e-8. (At x_p the noise model, read on the loading up to the collapse, takes the
// law's curvature growing towards it for a walk of 1.5e-5 a sample, whose replicates then carry x_p's
// miss instead of the fit's term: docs/analysis.md, "The bootstrap's noise read on the loading".)
TEST(AnalyzeCurve, TheCubicFitsOwnErrorOnASharpPeakIsInTheStrainsIntervals) {
  using namespace calibration;
  const Shape s = power_law(8.4);
  const Truth t = truth(s);
  const auto r = analyze_curve(exact_curve(s, 300), {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  const double x_c_error = r.x_c->value - t.x_c, x_p_error = r.x_p->value - t.x_p;
  EXPECT_GT(std::abs(x_c_error), 2e-4);  // the fit's error is there to be found
  EXPECT_GT(std::abs(x_p_error), 2e-4);
  EXPECT_NEAR(r.peak_fit_error.x_c, std::abs(x_c_error), 0.15 * std::abs(x_c_error));
  EXPECT_GE(r.x_p->error, std::abs(x_p_error));
  ASSERT_TRUE(r.x_c_interval && r.x_p_interval);
  EXPECT_LE(r.x_c_interval->ci95_low, t.x_c);
  EXPECT_GE(r.x_c_interval->ci95_high, t.x_c);
  EXPECT_LE(r.x_p_interval->ci95_low, t.x_p);
  EXPECT_GE(r.x_p_interval->ci95_high, t.x_p);
}

// A finite bundle of a sharp law at 300 rows (held-out 24, bundle N = 10^5, curve 7) reads as white
// over the whole record, whose steep decline inflates the white term; in the bootstrap window its
// white noise is far below 0.05 % of the peaks, so its intervals take the random walk's factors.
// Under 1 % white noise they stay white. (Held-out 22's curve 7, α = 8.8, was this test's case until
// its fall was found as a collapse: its noise is now read on the loading alone, a walk; below.)
TEST(AnalyzeCurve, QuietCurvesTakeTheRandomWalksFactors) {
  using namespace calibration;
  const auto bundle =
      analyse_set_curve("held-out-24", 7, noise_groups()[4], "powerlaw alpha=4.1", 300).result;
  const auto white = analyze_curve(white_noise_curve(power_law(3), 1000, 0.01, 7), {});
  ASSERT_TRUE(bundle.accepted) << bundle.rejection;
  ASSERT_TRUE(white.accepted) << white.rejection;
  EXPECT_FALSE(reads_random_walk(bundle));
  EXPECT_TRUE(bundle.quiet);
  EXPECT_LT(bundle.noise_model.force.white, quiet_white_noise_share * bundle.F_c->value);
  EXPECT_LT(bundle.noise_model.energy.white, quiet_white_noise_share * bundle.E_max->value);
  // The bootstrap follows the whole record's reading: stationary steps, as the white factors were learned.
  EXPECT_TRUE(bundle.noise_model.force.walk_profile.empty());
  EXPECT_TRUE(bundle.noise_model.energy.walk_profile.empty());
  EXPECT_TRUE(scored_as_random_walk(bundle));
  EXPECT_EQ(bundle.interval_scales.level68, delta_interval_scales.random_walk_profile.level68);
  EXPECT_EQ(bundle.x_c_interval->scales.level95, critical_strain_scales.random_walk_profile.level95);
  const auto j = to_json(bundle);
  EXPECT_EQ(j["delta_x"]["interval_scales"]["noise"], "random walk");
  EXPECT_TRUE(j["delta_x"]["interval_scales"]["quiet"].get<bool>());
  EXPECT_EQ(j["filter"]["noise_read"]["force"], "white");
  EXPECT_EQ(j["filter"]["noise_read"]["elastic_energy"], "white");
  EXPECT_FALSE(white.quiet);
  EXPECT_FALSE(scored_as_random_walk(white));
  EXPECT_EQ(white.interval_scales.level68, delta_interval_scales.white_noise.level68);
  EXPECT_FALSE(to_json(white)["delta_x"]["interval_scales"]["quiet"].get<bool>());

  const auto sharp = analyse_set_curve("held-out-22", 7, noise_groups()[4], "powerlaw alpha=8.8", 300).result;
  ASSERT_TRUE(sharp.accepted) << sharp.rejection;
  EXPECT_TRUE(sharp.collapse_onset);
  EXPECT_TRUE(reads_random_walk(sharp));
  EXPECT_TRUE(scored_as_random_walk(sharp));
}

// A DEM-like curve (a bundle whose F also carries 1 % white noise) at 1,000 rows: F's walk is lost
// under its white noise in the window's noise model and taken from E_e's, so x_c's and x_p's intervals
// say they are not calibrated (held-out 39's mixed curves) and a warning says why; δ_x's stays
// calibrated, and the same bundle without the white noise on F keeps its calibrated intervals.
TEST(AnalyzeCurve, AHiddenForceWalkLeavesTheStrainsIntervalsNotCalibrated) {
  using namespace calibration;
  const auto set = calibration_set("tuning");
  const NoiseGroup mixed = mixed_noise_groups()[0];
  const auto curve_case = CalibrationCase::at(set, static_cast<int>(set.size()));  // 1,000 rows
  ASSERT_EQ(curve_case.rows, 1000u);
  const auto hidden = analyze_curve(curve_case.draw(mixed), {});
  ASSERT_TRUE(hidden.accepted) << hidden.rejection;
  ASSERT_TRUE(force_walk_hidden(hidden)) << "F walk " << hidden.noise_model.force.walk;
  EXPECT_TRUE(hidden.noise_model.force.walk_from_energy);
  EXPECT_GT(hidden.noise_model.force.walk, 0.0);
  EXPECT_GT(hidden.noise_model.energy.walk, 0.0);
  EXPECT_FALSE(hidden.x_c_interval->scales.calibrated);
  EXPECT_FALSE(hidden.x_p_interval->scales.calibrated);
  EXPECT_TRUE(hidden.interval_scales.calibrated);
  EXPECT_EQ(hidden.x_c_interval->scales.level68, critical_strain_scales.random_walk_profile.level68);
  ASSERT_FALSE(hidden.warnings.empty());
  EXPECT_NE(hidden.warnings.back().find("fits no random walk in F"), std::string::npos);
  EXPECT_NE(hidden.warnings.back().find("F's walk was taken from E_e's"), std::string::npos);
  EXPECT_NE(hidden.warnings.back().find("the intervals of x_c and x_p are not calibrated"),
            std::string::npos);
  // Where x_c's interval is not calibrated anyway (the bootstrap's own), nothing is added.
  AnalysisOptions unscaled;
  unscaled.calibrated_intervals = false;
  const auto own = analyze_curve(curve_case.draw(mixed), unscaled);
  EXPECT_TRUE(force_walk_hidden(own));
  EXPECT_EQ(own.warnings.size(), hidden.warnings.size() - 1);
  EXPECT_FALSE(to_json(hidden)["x_c"]["interval_scales"]["calibrated"].get<bool>());
  const auto plain = analyze_curve(curve_case.draw({"bundle", 0, mixed.fibers}), {});
  ASSERT_TRUE(plain.accepted) << plain.rejection;
  EXPECT_FALSE(force_walk_hidden(plain));
  EXPECT_TRUE(plain.x_c_interval->scales.calibrated && plain.x_p_interval->scales.calibrated);
}

// x_p's white factors: the anchors at their shares, linear in log share between them (so the geometric
// mean of two shares gets the mean of their factors), the end anchors beyond them, calibrated only inside
// the learning curves' range, and 1 below it or where it is not measured.
TEST(IntervalScales, PrecursorWhiteFactorsFollowTheMeasuredNoiseLevel) {
  // The shipped model passed its last check (held-out 35). A model that failed one keeps its factors
  // and says not calibrated everywhere, as this one did between held-outs 30 and 35.
  const WhiteLevelScales& model = precursor_white_levels;
  ASSERT_TRUE(model.passed_last_check);
  WhiteLevelScales failed = model;
  failed.passed_last_check = false;
  for (const auto& a : model.anchors) {
    const auto at = white_level_scales(model, a.share);
    EXPECT_DOUBLE_EQ(at.level68, a.level68);
    EXPECT_DOUBLE_EQ(at.level95, a.level95);
    EXPECT_TRUE(at.calibrated);
    const auto kept = white_level_scales(failed, a.share);
    EXPECT_DOUBLE_EQ(kept.level68, a.level68);
    EXPECT_FALSE(kept.calibrated);
  }
  const auto &low = model.anchors[0], &high = model.anchors[1];
  const auto between = white_level_scales(model, std::sqrt(low.share * high.share));
  EXPECT_NEAR(between.level68, 0.5 * (low.level68 + high.level68), 1e-12);
  EXPECT_NEAR(between.level95, 0.5 * (low.level95 + high.level95), 1e-12);
  for (std::size_t i = 1; i < model.anchors.size(); ++i)
    EXPECT_GT(model.anchors[i].level68, model.anchors[i - 1].level68) << "rises with noise";
  ASSERT_LT(model.calibrated_from, low.share);
  const auto lowest = white_level_scales(model, model.calibrated_from);
  EXPECT_TRUE(lowest.calibrated);
  EXPECT_EQ(lowest.level68, low.level68) << "held at the lowest anchor";
  const auto quiet_end = white_level_scales(model, 0.001), loud_end = white_level_scales(model, 0.05);
  EXPECT_EQ(quiet_end.level68, 1.0) << "below the checked range: the bootstrap's own sd";
  EXPECT_FALSE(quiet_end.calibrated);
  EXPECT_EQ(loud_end.level95, model.anchors.back().level95);
  EXPECT_FALSE(loud_end.calibrated);
  EXPECT_FALSE(white_level_scales(model, 0.0).calibrated);
  EXPECT_EQ(white_level_scales(model, std::nan("")).level68, 1.0);
}

// x_c's and x_p's intervals are ± factor × sd about the estimate (± 1.96 factor × sd at 95 %), with
// the factors of the noise kind scored (1 where none passed a held-out check, and marked so), and written
// to analysis.json. The ± reported beside each number, δ_x's too, is the bootstrap's own sd scaled by the
// 68 % factor: what the 68 % interval says; δ_x keeps the sd before it for the acceptance rule.
TEST(AnalyzeCurve, TheStrainsIntervalsAreWrittenWithTheirNoiseKindsFactors) {
  using namespace calibration;
  AnalysisOptions unscaled;
  unscaled.calibrated_intervals = false;
  const auto bundle_curve = finite_bundle_curve(weibull(3), 1000, 100000, 7);
  const auto white_curve = white_noise_curve(weibull(3), 1000, 0.01, 7);
  const auto bundle = analyze_curve(bundle_curve, {});
  const auto white = analyze_curve(white_curve, {});
  for (const auto& [analysed, curve] : {std::pair{&bundle, &bundle_curve}, std::pair{&white, &white_curve}}) {
    const auto& r = *analysed;
    const auto bootstrap = analyze_curve(*curve, unscaled);
    ASSERT_TRUE(r.accepted && bootstrap.accepted) << r.rejection << bootstrap.rejection;
    const bool walk = scored_as_random_walk(r);
    for (const auto& [m, own_sd, interval, scales] :
         {std::tuple{*r.x_c, bootstrap.x_c->error, *r.x_c_interval,
                     critical_strain_scales.for_noise(walk, true)},
          std::tuple{*r.x_p, bootstrap.x_p->error, *r.x_p_interval, precursor_scales(r, true)}}) {
      EXPECT_NEAR(m.error, scales.level68 * own_sd, 1e-12 * own_sd);
      EXPECT_NEAR(interval.ci68_high - m.value, m.error, 1e-12 * own_sd);
      EXPECT_NEAR(m.value - interval.ci95_low, std::max(1.96 * scales.level95, scales.level68) * own_sd,
                  1e-12 * own_sd);
      EXPECT_EQ(interval.scales.level95, scales.level95);
      EXPECT_EQ(interval.scales.calibrated, scales.calibrated);
    }
    EXPECT_NE(r.interval_scales.level68, 1.0);  // else the two lines below cannot tell scaled from own
    EXPECT_NEAR(r.delay->sd, r.interval_scales.level68 * bootstrap.delay->sd, 1e-12 * bootstrap.delay->sd);
    EXPECT_EQ(r.delay->unscaled_sd, bootstrap.delay->sd);
    // The replicates' density drawn is widened as the sd was.
    const auto density_sd = [](const DelayPosterior& d) {
      double mass = 0.0, first = 0.0, second = 0.0;
      for (std::size_t i = 0; i < d.delta.size(); ++i) {
        mass += d.density[i];
        first += d.density[i] * d.delta[i];
        second += d.density[i] * d.delta[i] * d.delta[i];
      }
      return std::sqrt(second / mass - std::pow(first / mass, 2));
    };
    EXPECT_NEAR(density_sd(*r.delay) / density_sd(*bootstrap.delay), r.interval_scales.level68,
                0.03 * r.interval_scales.level68);
    const auto j = to_json(r);
    EXPECT_EQ(j["x_c"]["interval_scales"]["noise"], walk ? "random walk" : "white");
    EXPECT_EQ(j["x_p"]["ci95"][1].get<double>(), r.x_p_interval->ci95_high);
    EXPECT_EQ(j["uncertainty"]["systematic"]["x_c"]["peak_fit"]["value"].get<double>(), r.peak_fit_error.x_c);
  }
  EXPECT_TRUE(reads_random_walk(bundle));
  EXPECT_FALSE(reads_random_walk(white));
  EXPECT_FALSE(white.quiet);
  EXPECT_EQ(white.x_c_interval->scales.level68, critical_strain_scales.white_noise.level68);
  // x_p's white factors follow E_e's measured white noise: about 1 % of E_max here.
  const double share = energy_white_share(white);
  EXPECT_NEAR(share, 0.01, 0.002);
  EXPECT_EQ(white.x_p_interval->scales.level68, white_level_scales(precursor_white_levels, share).level68);
  EXPECT_TRUE(white.x_p_interval->scales.calibrated);  // within the model's range: passed held-out 35
  EXPECT_EQ(white.interval_scales.level68, delta_interval_scales.white_noise.level68);
  EXPECT_TRUE(white.interval_scales.calibrated);
  EXPECT_TRUE(white.x_c_interval->scales.calibrated);  // x_c's white factors passed held-out 35
  EXPECT_EQ(bundle.x_p_interval->scales.level68, precursor_strain_scales.random_walk_profile.level68);
  // At 0.08 % white noise, below the 0.2-3 % the white factors were checked on (held-out 26 found them
  // too wide there), δ_x's and x_c's intervals keep their white factors and say they are not calibrated;
  // x_p's take the bootstrap's own sd. analysis.json gives each interval's level.
  const auto quiet_white = analyze_curve(white_noise_curve(weibull(3), 1000, 0.0008, 7), {});
  ASSERT_TRUE(quiet_white.accepted) << quiet_white.rejection;
  ASSERT_FALSE(scored_as_random_walk(quiet_white));
  const auto force_level = critical_noise_level(quiet_white), delay_level = delay_noise_level(quiet_white);
  ASSERT_TRUE(force_level && delay_level);
  EXPECT_NEAR(*force_level, 0.0008, 0.0003);
  EXPECT_EQ(*delay_level, std::max(*force_level, energy_white_share(quiet_white)));
  EXPECT_LT(*delay_level, white_factors_checked_from);
  EXPECT_EQ(quiet_white.interval_scales.level68, delta_interval_scales.white_noise.level68);
  EXPECT_FALSE(quiet_white.interval_scales.calibrated);
  EXPECT_EQ(quiet_white.x_c_interval->scales.level95, critical_strain_scales.white_noise.level95);
  EXPECT_FALSE(quiet_white.x_c_interval->scales.calibrated);
  EXPECT_EQ(quiet_white.x_p_interval->scales.level68, 1.0);
  const auto j = to_json(quiet_white);
  EXPECT_EQ(j["delta_x"]["interval_scales"]["white_share"].get<double>(), *delay_level);
  EXPECT_EQ(j["x_c"]["interval_scales"]["force_white_share"].get<double>(), *force_level);
  EXPECT_FALSE(j["delta_x"]["interval_scales"]["calibrated"].get<bool>());
  const auto own = analyze_curve(white_noise_curve(weibull(3), 1000, 0.01, 7), unscaled);
  EXPECT_EQ(own.x_c_interval->ci68_high, own.x_c->value + own.x_c->error);
  EXPECT_EQ(own.x_c_interval->ci95_low, own.x_c->value - 1.96 * own.x_c->error);
  EXPECT_FALSE(own.x_c_interval->scales.calibrated);
  EXPECT_FALSE(to_json(own)["delta_x"]["interval_scales"]["calibrated"].get<bool>());
}

// The noise model tells white noise from a random walk, and measures each.
TEST(NoiseModel, SeparatesWhiteNoiseFromARandomWalk) {
  std::vector<double> white(4000), walk(4000);
  Rng rng(3, RandomStream::analysis_noise);
  double w = 0.0;
  for (std::size_t i = 0; i < white.size(); ++i) {
    const double x = static_cast<double>(i) / 4000.0;
    white[i] = x * (1.0 - x) + 0.01 * rng.normal();
    w += 0.002 * rng.normal();
    walk[i] = x * (1.0 - x) + w;
  }
  const auto model = estimate_noise(white, walk, 0, 3999);
  EXPECT_NEAR(model.force.white, 0.01, 0.001);
  EXPECT_LT(model.force.walk, 0.001);
  EXPECT_NEAR(model.energy.walk, 0.002, 0.0002);
  EXPECT_LT(model.energy.white, 0.001);
  EXPECT_NEAR(model.correlation, 0.0, 0.1);
}

// Rows that are a walk's means over their interval (as rupture run writes its *_mean columns) share
// the walk with their neighbours: read as instants, the step comes out near 0.8 of the truth; read as
// interval means, within 10 % (medians over 41 walks of 400 rows, each row the mean of 50 sub-steps).
TEST(NoiseModel, AWalkOnRowsThatAreIntervalMeansIsReadWithItsOwnTerm) {
  constexpr std::size_t rows = 400, substeps = 50;
  std::vector<double> as_instants, as_means;
  for (std::uint64_t seed = 1; seed <= 41; ++seed) {
    Rng rng(seed, RandomStream::analysis_noise);
    std::vector<double> means(rows), white(rows);
    double walk = 0.0;
    for (std::size_t i = 0; i < rows; ++i) {
      double sum = 0.0;
      for (std::size_t k = 0; k < substeps; ++k) {
        walk += rng.normal() / std::sqrt(double(substeps));  // step 1 per row
        sum += walk;
      }
      const double x = double(i) / double(rows);
      means[i] = 40.0 * x * (1.0 - x) + sum / double(substeps);
      white[i] = rng.normal();
    }
    as_instants.push_back(estimate_noise(white, means, 0, rows - 1).energy.walk);
    as_means.push_back(
        estimate_noise(white, means, 0, rows - 1, OutlierScale::span, RowKind::interval_means).energy.walk);
  }
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  EXPECT_LT(median(as_instants), 0.88);
  EXPECT_NEAR(median(as_means), 1.0, 0.1);
}

// A bundle's walk grows along the curve with its breaks, fastest near the peak: here its step is
// 10⁻⁶ + 10⁻⁴ x⁸ over x in [0, 1], so most of its variance lies in the last fifth while the median
// second difference is the quiet part's. One robust scale over the span left that fifth out as
// outliers (the walk read at a third of its rms step or less); each value's neighbourhood's scale
// keeps it (docs/analysis.md, "The bootstrap's noise read on the loading").
TEST(NoiseModel, AWalkThatGrowsAlongTheSpanIsReadWithItsNeighbourhoodsScale) {
  const std::size_t n = 4000;
  Rng rng(11, RandomStream::analysis_noise);
  std::vector<double> force(n), energy(n);
  double w = 0.0, squares = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n);
    const double step = 1e-6 + 1e-4 * std::pow(x, 8);
    squares += step * step / static_cast<double>(n);
    w += step * rng.normal();
    force[i] = x * (1.0 - x) + 1e-4 * rng.normal();
    energy[i] = 0.5 * x * x + w;
  }
  const double rms_step = std::sqrt(squares);
  const auto local = estimate_noise(force, energy, 0, n - 1, OutlierScale::local);
  EXPECT_NEAR(local.energy.walk, rms_step, 0.25 * rms_step);
  EXPECT_NEAR(local.force.white, 1e-4, 1e-5);
  const auto span = estimate_noise(force, energy, 0, n - 1, OutlierScale::span);
  EXPECT_LT(span.energy.walk, 0.35 * rms_step);
}

// A DEM run's F sampled faster than its slowest mode rings: a damped oscillation of period 3.3 rows
// (quality 10) at 20 times the walk's step. Over lags 1-8 the ringing's second differences hide the
// walk (the fit gives it no share); read on block means of about a period it is found, and the
// ringing enters as white noise of its own variance. E_e, a walk without ringing, is read as before.
TEST(NoiseModel, AWalkUnderARingingIsReadOnBlockMeans) {
  const std::size_t n = 4000;
  const double step = 0.0005, ringing_rms = 0.01;
  const calibration::StepOscillator mode(3.3);  // the run-like curves' oscillator, quality 10
  Rng rng(7, RandomStream::analysis_noise);
  std::vector<double> ringing(n, 0.0);
  for (std::size_t i = 2; i < n; ++i) mode.step(ringing, i, rng.normal());
  double square = 0.0;
  for (double r : ringing) square += r * r / static_cast<double>(n);
  std::vector<double> force(n), energy(n);
  double w = 0.0, v = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n);
    w += step * rng.normal();
    v += 0.002 * rng.normal();
    force[i] = x * (1.0 - x) + w + ringing_rms * ringing[i] / std::sqrt(square);
    energy[i] = x * (1.0 - x) + v;
  }
  const auto model = estimate_noise(force, energy, 0, n - 1);
  EXPECT_NEAR(model.force.walk, step, 0.3 * step);
  EXPECT_NEAR(model.force.white, ringing_rms, 0.3 * ringing_rms);
  EXPECT_FALSE(random_walk_dominates(model.force));
  EXPECT_NEAR(model.energy.walk, 0.002, 0.0002);
  EXPECT_LT(model.energy.white, 0.001);
}

// A finite bundle (power law α = 1: p(x) = 2x, 10^5 fibers, 2000 rows): E_e's true walk step² is
// (x²/2)² p(x) h / N ∝ x⁵ and F's x² p(x) h / N ∝ x³. The profile read from the curve's falling
// stiffness follows both (mean square 1 over the span), and replicates drawn with it carry E_e steps
// that grow as the profile does (rows from x = 0.3: below, the steps fall under the profile's floor of
// 1 % of its mean square). White noise on a curve keeps its profile empty.
TEST(NoiseModel, WalkProfileFollowsABundlesBreaks) {
  const std::size_t n = 2000, low = 300, high = 1700;
  const auto bundle = testing::finite_bundle(1.0, 100000, n, 5);
  auto model = estimate_noise(bundle.force, bundle.energy, low, high);
  ASSERT_TRUE(random_walk_dominates(model.energy));
  add_walk_profiles(model, bundle.strain, bundle.force, low, high);
  for (const auto& [profile, power] :
       {std::pair{&model.energy.walk_profile, 5.0}, {&model.force.walk_profile, 3.0}}) {
    ASSERT_EQ(profile->size(), high - low + 1);
    double mean_square = 0.0, true_mean_square = 0.0;
    for (std::size_t j = 0; j < profile->size(); ++j) {
      mean_square += (*profile)[j] * (*profile)[j] / static_cast<double>(profile->size());
      true_mean_square += std::pow(bundle.strain[low + j], power) / static_cast<double>(profile->size());
    }
    EXPECT_NEAR(mean_square, 1.0, 1e-9);
    for (std::size_t i : {std::size_t{600}, n / 2, high - 100}) {
      const double truth = std::sqrt(std::pow(bundle.strain[i], power) / true_mean_square);
      EXPECT_NEAR((*profile)[i - low], truth, 0.15 * truth) << "power " << power << ", row " << i;
    }
  }
  // Replicates: E_e's step variance in the first and last tenth of the span follows the profile.
  const auto& profile = model.energy.walk_profile;
  const std::size_t count = high - low + 1, tenth = count / 10;
  double early = 0.0, late = 0.0;
  for (std::uint64_t r = 0; r < 200; ++r) {
    std::vector<double> f(count, 0.0), e(count, 0.0);
    add_model_noise(model, f, e, 11, r);
    for (std::size_t i = 1; i < tenth; ++i) early += std::pow(e[i] - e[i - 1], 2);
    for (std::size_t i = count - tenth + 1; i < count; ++i) late += std::pow(e[i] - e[i - 1], 2);
  }
  // Each increment also holds two draws of the model's (small) white term.
  const double walk2 = model.energy.walk * model.energy.walk, white2 = 2.0 * std::pow(model.energy.white, 2);
  double profile_early = 0.0, profile_late = 0.0;
  for (std::size_t i = 1; i < tenth; ++i) profile_early += walk2 * profile[i] * profile[i] + white2;
  for (std::size_t i = count - tenth + 1; i < count; ++i)
    profile_late += walk2 * profile[i] * profile[i] + white2;
  EXPECT_NEAR(late / early, profile_late / profile_early, 0.1 * profile_late / profile_early);
  EXPECT_GT(late / early, 20.0);
  // White noise alone: no walk, no profile.
  auto noisy = testing::finite_bundle(1.0, 100000, n, 5);
  noisy.energy = bundle.energy;
  add_noise(noisy, 0.01, 0.0, 3);
  auto white = estimate_noise(noisy.force, noisy.energy, low, high);
  ASSERT_FALSE(random_walk_dominates(white.force));
  add_walk_profiles(white, noisy.strain, noisy.force, low, high);
  EXPECT_TRUE(white.force.walk_profile.empty());
}

// A finite bundle whose F rings (power law α = 1, 10^5 fibres, 500 rows; a 3.3-row ringing at 20
// times F's true walk step): the breaks that make E_e's walk make F's, each of F's steps F/E_e = 2/x
// times E_e's (Clapeyron). The walk read on F's block means is lost under the ringing (seed 1: 0) or
// takes a part of it for a walk (seed 4: twice the true step); add_hidden_force_walk takes F's walk
// from E_e's, within 20 % of its true rms step over the span (x² p(x) h / N per row, p(x) = 2x, h the
// row's strain), with a breaking solid's profile. Where F does not ring, or E_e rings too, F's reading
// stands.
TEST(NoiseModel, AWalkHiddenUnderFsRingingIsTakenFromEnergysWalk) {
  const std::size_t n = 500, low = 75, high = 425, fibers = 100000;
  for (const std::uint64_t seed : {1, 4}) {
    const auto bundle = testing::finite_bundle(1.0, fibers, n, seed);
    const double h = bundle.strain[1] - bundle.strain[0];
    double true_square = 0.0;
    for (std::size_t i = low; i <= high; ++i)
      true_square += std::pow(bundle.strain[i], 3) * 2.0 * h / double(fibers) / double(high - low + 1);
    const double true_step = std::sqrt(true_square);
    const calibration::StepOscillator mode(3.3);
    Rng rng(seed + 8, RandomStream::analysis_noise);
    std::vector<double> ringing(n, 0.0);
    for (std::size_t i = 2; i < n; ++i) mode.step(ringing, i, rng.normal());
    double square = 0.0;
    for (double r : ringing) square += r * r / double(n);
    auto ringing_force = bundle.force, ringing_energy = bundle.energy;
    for (std::size_t i = 0; i < n; ++i) {
      ringing_force[i] += 20.0 * true_step * ringing[i] / std::sqrt(square);
      ringing_energy[i] += 20.0 * true_step * ringing[i] / std::sqrt(square);
    }
    auto model = estimate_noise(ringing_force, bundle.energy, low, high);
    ASSERT_GE(model.force.ringing_block, 2u);
    ASSERT_EQ(model.energy.ringing_block, 0u);
    add_walk_profiles(model, bundle.strain, ringing_force, low, high);
    const double read = model.force.walk;
    EXPECT_GT(std::abs(read / true_step - 1.0), 0.3) << "seed " << seed;
    add_hidden_force_walk(model, bundle.strain, ringing_force, bundle.energy, low, high);
    EXPECT_NEAR(model.force.walk, true_step, 0.2 * true_step) << "seed " << seed << ", read " << read;
    EXPECT_TRUE(model.force.walk_from_energy);
    // F's profile, a breaking solid's: step² ∝ x³ here (E_e's would grow as x⁵).
    ASSERT_EQ(model.force.walk_profile.size(), high - low + 1);
    double true_profile_square = 0.0;
    for (std::size_t i = low; i <= high; ++i)
      true_profile_square += std::pow(bundle.strain[i], 3) / double(high - low + 1);
    for (std::size_t i : {std::size_t{150}, n / 2, high - 25}) {
      const double truth = std::sqrt(std::pow(bundle.strain[i], 3) / true_profile_square);
      EXPECT_NEAR(model.force.walk_profile[i - low], truth, 0.2 * truth) << "seed " << seed << ", row " << i;
    }
    // F without its ringing: its own reading stands.
    auto plain = estimate_noise(bundle.force, bundle.energy, low, high);
    add_walk_profiles(plain, bundle.strain, bundle.force, low, high);
    const auto plain_walk = plain.force.walk;
    add_hidden_force_walk(plain, bundle.strain, bundle.force, bundle.energy, low, high);
    EXPECT_EQ(plain.force.walk, plain_walk);
    EXPECT_FALSE(plain.force.walk_from_energy);
    // E_e ringing as well: no step of E_e to take F's from.
    auto both = estimate_noise(ringing_force, ringing_energy, low, high);
    ASSERT_GE(both.energy.ringing_block, 2u);
    const auto both_walk = both.force.walk;
    add_hidden_force_walk(both, bundle.strain, ringing_force, ringing_energy, low, high);
    EXPECT_EQ(both.force.walk, both_walk);
    EXPECT_FALSE(both.force.walk_from_energy);
  }
}

// The same bundle at 5,000 rows over a span from strain 0.001 to 0.5, its F walk read as zero (as white
// noise on F makes it: AnalyzeCurve.AHiddenForceWalkLeavesTheStrainsIntervalsNotCalibrated) while a walk
// dominates E_e's: F's walk is taken from E_e's, each sample weighted by E_e's step there from the breaks'
// physics, so that F's walk over E_e's is the true ratio of their rms steps (x² p h / N against
// x⁴/4 p h / N per row, p = 2x) within 5 %. Near zero strain F/E_e = 2/x has no bound: weighted by the
// noise model's floored profile instead, the ratio came out 2.2 times too large here, and F's walk
// 1.7-5.5 times its own reading on finite bundles (5,000 rows the worst; docs/analysis.md, "F's walk
// taken from E_e's with the breaks' own weights"). E_e's own reading of this steep walk is 0.73-0.82
// of its truth. Where white noise dominates E_e's noise, its small walk is no reading to take F's from.
TEST(NoiseModel, AWalkReadAsZeroIsTakenFromEnergysWalkFromStrainZeroOn) {
  const std::size_t n = 5000, low = 5, high = 2500, fibers = 100000;
  double force_square = 0.0, energy_square = 0.0;  // per row, times N / h
  for (std::size_t i = low; i <= high; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n - 1);
    force_square += std::pow(x, 3) * 2.0;
    energy_square += std::pow(x, 5) / 2.0;
  }
  const double true_ratio = std::sqrt(force_square / energy_square);
  for (const std::uint64_t seed : {1, 2, 3}) {
    const auto bundle = testing::finite_bundle(1.0, fibers, n, seed);
    auto model = estimate_noise(bundle.force, bundle.energy, low, high);
    ASSERT_TRUE(random_walk_dominates(model.energy)) << "seed " << seed;
    add_walk_profiles(model, bundle.strain, bundle.force, low, high);
    model.force.walk = 0.0;
    model.force.walk_profile.clear();
    add_hidden_force_walk(model, bundle.strain, bundle.force, bundle.energy, low, high);
    EXPECT_TRUE(model.force.walk_from_energy && model.force.walk_read_as_zero);
    EXPECT_NEAR(model.force.walk / model.energy.walk, true_ratio, 0.05 * true_ratio) << "seed " << seed;
    EXPECT_EQ(model.force.walk_profile.size(), high - low + 1);
    auto white_model = estimate_noise(bundle.force, bundle.energy, low, high);
    white_model.energy.white = 2.0 * white_model.energy.walk;  // 6σ_w² = 24σ_r² > 2σ_r²
    ASSERT_FALSE(random_walk_dominates(white_model.energy)) << "seed " << seed;
    white_model.force.walk = 0.0;
    add_hidden_force_walk(white_model, bundle.strain, bundle.force, bundle.energy, low, high);
    EXPECT_EQ(white_model.force.walk, 0.0) << "seed " << seed;
    EXPECT_FALSE(white_model.force.walk_from_energy || white_model.force.walk_read_as_zero);
  }
}

// A bundle with a sharp force peak (α = 4, 300 rows; held-out 7's curve 1 at 10^5 fibers): over the
// whole curve the collapse inflates the white term and the model reads white noise (the known limit
// "a finite bundle read as white noise"), while in at least 2 of its 4 quarters the walk dominates.
// Under white noise, even at 0.2 % where the peak is sharpest against the noise, no quarter reads
// as a walk. The quarter count is what bench/noise_kind_votes measures (docs/analysis.md, held-out
// 8). The whole-curve expectation pins that known limit: a fix of it changes this test.
TEST(NoiseModel, QuartersOfASharplyPeakedBundleReadAsARandomWalk) {
  using namespace calibration;
  const auto set = calibration_set("held-out-7");
  const auto bundle = CalibrationCase::at(set, 1);
  ASSERT_EQ(bundle.shape.name, "powerlaw alpha=4");
  const Curve c = bundle.draw({"bundle N=1e5", 0, 100000});
  const std::size_t last = c.force.size() - 1;
  EXPECT_FALSE(random_walk_dominates(estimate_noise(c.force, c.energy, 0, last)));
  EXPECT_GE(walk_dominated_quarters(c.force, c.energy, 0, last), 2);
  for (double level : {0.002, 0.03}) {
    const Curve w = bundle.draw({"white", level, 0});
    EXPECT_EQ(walk_dominated_quarters(w.force, w.energy, 0, w.force.size() - 1), 0) << level;
  }
}

// A broad law's bundle recorded to six times x_c at 5,000 rows: the whole record's noise fit finds
// no noise at all (all its curvature), which read the curve as white and left it barely smoothed
// (held-out 15, docs/analysis.md). The kind is then read on the loading part: a random walk, and δ_x
// comes out near the truth.
TEST(NoiseModel, ABundleWhoseWholeRecordShowsNoNoiseIsReadOnItsLoadingPart) {
  using namespace calibration;
  const Shape law = log_normal(0.59);
  const Curve c = finite_bundle_curve(law, 5000, 10000, 27017);
  const auto whole = estimate_noise(c.force, c.energy, 0, c.force.size() - 1);
  ASSERT_EQ(whole.force.white + whole.force.walk + whole.energy.white + whole.energy.walk, 0.0);
  const auto r = analyze_curve(c, AnalysisOptions{});
  EXPECT_EQ(noise_kind(r), "random walk");
  EXPECT_LT(r.filter.cutoff, 0.02);
  ASSERT_TRUE(r.accepted) << r.rejection;
  const double truth_delta = truth(law).delta();
  EXPECT_NEAR(r.delta_x->value, truth_delta, 0.1 * truth_delta);
  EXPECT_LT(r.delta_x->error, 0.1 * truth_delta);
}

// The DEM-like calibration group: the bundle's own curves, with white noise of the stated share of
// F_c on F alone; the noise model sees it as white on F while E_e keeps the bundle's walk.
TEST(NoiseModel, MixedNoiseGroupAddsWhiteNoiseToTheForceAlone) {
  using namespace calibration;
  const auto set = shapes();
  const auto curve_case = CalibrationCase::at(set, 1000);
  const NoiseGroup mixed = mixed_noise_groups()[1];
  const Curve bundle = curve_case.draw({"bundle", 0, mixed.fibers});
  const Curve c = curve_case.draw(mixed);
  ASSERT_EQ(c.force.size(), bundle.force.size());
  EXPECT_EQ(c.energy, bundle.energy);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < c.force.size(); ++i) sum2 += std::pow(c.force[i] - bundle.force[i], 2);
  const double sd = std::sqrt(sum2 / static_cast<double>(c.force.size()));
  EXPECT_NEAR(sd / truth(curve_case.shape).F_c, mixed.force_white, 0.1 * mixed.force_white);
  const auto model = estimate_noise(c.force, c.energy, 0, c.force.size() - 1);
  EXPECT_NEAR(model.force.white / truth(curve_case.shape).F_c, mixed.force_white, 0.2 * mixed.force_white);
}

// The brittle groups' curves (calibration_set.hpp): the exact curve up to the cut, then falling by e
// every 3 rows from its value at the cut; white noise stays on the collapse.
TEST(CalibrationSets, ABrittleCurveFollowsTheShapeToItsCutAndThenFalls) {
  using namespace calibration;
  const Shape s = weibull(3);
  const CalibrationCase curve_case{s, 500, 7};
  const double cut = collapse_cut(s, curve_case.seed);
  EXPECT_GE(cut, 1.03 * truth(s).x_c);
  EXPECT_LE(cut, 1.5 * truth(s).x_c);
  const Curve c = curve_case.draw({"brittle noise-free", 0.0, 0, 0.0, true});
  const double step = c.strain[1] - c.strain[0];
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    const double x = c.strain[i];
    const double expected =
        x <= cut ? force_of(s, x) : force_of(s, cut) * std::exp(-(x - cut) / (3.0 * step));
    ASSERT_NEAR(c.force[i], expected, 1e-12) << i;
  }
  const Curve noisy = curve_case.draw({"brittle white 1 %", 0.01, 0, 0.0, true});
  double square = 0.0;
  std::size_t after = 0;
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    if (c.strain[i] <= cut) continue;
    square += std::pow(noisy.force[i] - c.force[i], 2);
    ++after;
  }
  EXPECT_NEAR(std::sqrt(square / static_cast<double>(after)), 0.01 * truth(s).F_c, 0.003 * truth(s).F_c);
}

// The brittle-close groups: the same three noises, the collapse drawn within 2 % past the force peak;
// the curve follows the shape to that cut.
TEST(CalibrationSets, ABrittleCloseCurveIsCutWithinTwoPercentPastItsPeak) {
  using namespace calibration;
  const auto close = brittle_close_noise_groups();
  const auto brittle = brittle_noise_groups();
  ASSERT_EQ(close.size(), brittle.size());
  for (std::size_t g = 0; g < close.size(); ++g) {
    EXPECT_EQ(close[g].name, "brittle close" + brittle[g].name.substr(std::string("brittle").size()));
    EXPECT_EQ(close[g].level, brittle[g].level);
    EXPECT_EQ(close[g].fibers, brittle[g].fibers);
    EXPECT_EQ(close[g].force_white, brittle[g].force_white);
  }
  const Shape s = weibull(3);
  double lowest = 2.0, highest = 0.0;
  for (std::uint64_t seed = 17; seed < 40017; seed += 1000) {
    const double b = collapse_cut(s, seed, close[0].cut_from, close[0].cut_span) / truth(s).x_c;
    lowest = std::min(lowest, b);
    highest = std::max(highest, b);
  }
  EXPECT_GE(lowest, 1.0);
  EXPECT_LE(highest, 1.02);
  EXPECT_GT(highest - lowest, 0.015) << "the cuts spread over the range";
  NoiseGroup noise_free = close[1];
  noise_free.level = 0.0;
  const CalibrationCase curve_case{s, 1000, 7017};
  const Curve c = curve_case.draw(noise_free);
  const double cut = collapse_cut(s, curve_case.seed, noise_free.cut_from, noise_free.cut_span);
  const double step = c.strain[1] - c.strain[0];
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    const double x = c.strain[i];
    ASSERT_NEAR(c.force[i],
                x <= cut ? force_of(s, x) : force_of(s, cut) * std::exp(-(x - cut) / (3.0 * step)), 1e-12)
        << i;
  }
}

// The run-like groups' curves (calibration_set.hpp): rows on the run's step lattice, each the step's
// values or the means of 20 samples over the row's interval; F rings at the level asked for over
// [0.7, 0.95] x_c about the bundle's own force; a sample that comes apart falls towards 7 % of F and
// 30 % of E_e at its cut.
TEST(CalibrationSets, ARunLikeCurveHasTheRunsRowsItsRingingAndItsCollapse) {
  using namespace calibration;
  const Shape s = weibull(3);
  const Truth t = truth(s);
  constexpr std::uint64_t seed = 7;
  constexpr double run_steps = 100000.0;
  const Curve samples = run_like_curve(s, 10000, {200, false, 0.008, false}, seed);
  const Curve means = run_like_curve(s, 10000, {200, true, 0.008, false}, seed);
  ASSERT_EQ(samples.strain.size(), 501u);
  ASSERT_EQ(means.strain.size(), 501u);
  EXPECT_EQ(samples.rows, RowKind::instants);
  EXPECT_EQ(means.rows, RowKind::interval_means) << "read as rupture run's *_mean columns are";
  EXPECT_EQ(to_json(analyze_curve(means, {}))["resample"]["rows"], "interval-means");
  EXPECT_EQ(to_json(analyze_curve(samples, {}))["resample"]["rows"], "instants");
  for (std::size_t i = 1; i < samples.strain.size(); ++i) {
    const double row_end = 200.0 * static_cast<double>(i);
    ASSERT_NEAR(samples.strain[i], s.x_end * row_end / run_steps, 1e-12) << i;
    ASSERT_NEAR(means.strain[i], s.x_end * (row_end - 95.0) / run_steps, 1e-12)
        << i;  // steps 10, 20 ... 200 back
  }
  // Every step against the same fibres' bundle at the same strains: E_e the bundle's, F its own plus
  // the ringing, whose rms over [0.7, 0.95] x_c is the level asked for.
  const Curve every_step = run_like_curve(s, 10000, {1, false, 0.008, false}, seed);
  const Curve bundle = finite_bundle_curve(s, every_step.strain.size(), 10000, seed);
  ASSERT_EQ(every_step.strain.size(), 100001u);
  double square = 0.0;
  std::size_t ringing = 0;
  for (std::size_t i = 0; i < every_step.strain.size(); ++i) {
    ASSERT_EQ(every_step.energy[i], bundle.energy[i]) << "E_e carries the bundle's walk alone";
    if (every_step.strain[i] < 0.7 * t.x_c || every_step.strain[i] > 0.95 * t.x_c) continue;
    square += std::pow(every_step.force[i] - bundle.force[i], 2);
    ++ringing;
  }
  EXPECT_NEAR(std::sqrt(square / static_cast<double>(ringing)), 0.008 * t.F_c, 1e-9 * t.F_c);

  const Curve apart = run_like_curve(s, 10000, {200, false, 0.008, true}, seed);
  const double cut = run_like_cut(s, seed);
  EXPECT_GE(cut, 1.03 * t.x_c);
  EXPECT_LE(cut, 1.2 * t.x_c);
  std::size_t last_before = 0;
  while (apart.strain[last_before + 1] < cut) ++last_before;
  EXPECT_EQ(apart.energy[last_before], samples.energy[last_before]) << "the same curve up to the cut";
  const double held_energy =
      apart.energy.back() / 0.3;  // E_e's value at the cut's step before, from its floor
  EXPECT_GT(held_energy, 0.9 * apart.energy[last_before]);
  EXPECT_LT(held_energy, 1.1 * apart.energy[last_before]);
  double tail = 0.0;
  for (std::size_t i = apart.force.size() - 100; i < apart.force.size(); ++i) tail += apart.force[i] / 100.0;
  EXPECT_NEAR(tail, 0.07 * apart.force[last_before], 0.02 * t.F_c) << "F falls to 7 % and rings about it";
}

// The dem-like groups' curves (calibration_set.hpp, run_like_sag): the same fibres as a run-like curve
// up to the kink; past it extra breaks at the drawn rate (a Poisson count) make the mean's maximum the
// kink, F sag by 1-9 % to the collapse, and leave ℰ's maximum the law's.
TEST(CalibrationSets, ASaggingRunLikeCurveTopsOutAtItsKinkAndSagsToTheCollapse) {
  using namespace calibration;
  const Shape s = weibull(3);
  const Truth law = truth(s);
  constexpr std::uint64_t seed = 7;
  const RunRows sagging{1, false, 0.0, true, true}, plain{1, false, 0.0, false, false};
  const Sag sag = run_like_sag(s, seed);
  EXPECT_GE(sag.kink, 0.82 * law.x_c);
  EXPECT_LE(sag.kink, 0.94 * law.x_c);
  EXPECT_GE(sag.kink, law.x_p + 0.05 * law.x_c);
  EXPECT_GE(sag.cut, 1.02 * sag.kink);
  EXPECT_LE(sag.cut, 1.06 * sag.kink);

  const Truth t = run_like_truth(s, seed, sagging);
  EXPECT_NEAR(t.x_c, sag.kink, 1e-6 * law.x_c) << "the mean's force tops out at the kink";
  EXPECT_NEAR(t.x_p, law.x_p, 1e-6 * law.x_p) << "ℰ's maximum stays the law's";
  const double sag_at_cut = 1.0 - sag.cut * sagging_intact(s, sag, sag.cut) / t.F_c;
  EXPECT_GT(sag_at_cut, 0.01);
  EXPECT_LT(sag_at_cut, 0.09);

  // Every step, no ringing: the same fibres as the plain curve up to the kink; past it the extra
  // breaks (E_e = x² I / 2 gives the intact share I) follow the drawn rate within their Poisson sd.
  const Curve c = run_like_curve(s, 10000, sagging, seed);
  const Curve same = run_like_curve(s, 10000, plain, seed);
  std::size_t kink = 0, last = 0;
  while (c.strain[kink + 1] <= sag.kink) ++kink;
  while (c.strain[last + 1] < sag.cut) ++last;
  for (std::size_t i = 0; i <= kink; ++i) ASSERT_EQ(c.force[i], same.force[i]) << i;
  const auto intact = [](const Curve& curve, std::size_t i) {
    return 2.0 * curve.energy[i] / (curve.strain[i] * curve.strain[i]);
  };
  const double extra = 10000.0 * (intact(same, last) - intact(c, last));
  const double expected = sag.rate * 10000.0 * intact(same, kink) * (c.strain[last] - sag.kink);
  EXPECT_NEAR(extra, expected, 4.0 * std::sqrt(expected));
  const auto top = std::max_element(c.force.begin(), c.force.end()) - c.force.begin();
  EXPECT_NEAR(c.strain[std::size_t(top)], t.x_c, 0.02 * t.x_c) << "the fibres' own curve tops out there too";
  EXPECT_LT(c.force[last], c.force[std::size_t(top)]);
}

// The sets bench/analysis_calibration runs by name: every held-out row has its six shapes, a name
// gives all its rows, and no shape is shared with the tuning set or another row (a held-out set that
// repeats a shape checks nothing new); an unknown name gives no set. One repeat is on record:
// held-out 24 was drawn before bench/draw_held_out.py checked uniform laws and repeats held-out 18's
// uniform [0.18,0.93]; its check was scored with and without that shape (docs/analysis.md).
TEST(CalibrationSets, HeldOutSetsAreDisjointAndFoundByName) {
  using namespace calibration;
  const std::set<std::pair<std::string, std::string>> repeats_on_record = {
      {"held-out-24", "uniform [0.18,0.93]"}};
  std::set<std::string> seen;
  for (const auto& s : calibration_set("all")) EXPECT_TRUE(seen.insert(s.name).second) << s.name;
  EXPECT_EQ(calibration_set("tuning").size() + calibration_set("held-out").size(), seen.size());
  std::map<std::string, std::size_t> rows_of;
  std::set<std::pair<std::string, std::string>> repeats;
  for (const auto& set : later_held_out_sets) {
    const auto shapes = set.shapes();
    EXPECT_EQ(shapes.size(), 6u) << set.name;
    ++rows_of[set.name];
    for (const auto& s : shapes)
      if (!seen.insert(s.name).second) repeats.insert({set.name, s.name});
  }
  EXPECT_EQ(repeats, repeats_on_record);
  for (const auto& [name, rows] : rows_of) EXPECT_EQ(calibration_set(name).size(), 6 * rows) << name;
  EXPECT_EQ(calibration_set("held-out-16").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-17").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-18").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-19").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-20").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-21").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-22").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-23").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-24").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-25").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-26").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-27").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-28").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-29").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-30").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-31").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-32").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-33").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-34").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-35").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-36").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-37").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-38").size(), 12u);
  EXPECT_EQ(calibration_set("held-out-39").size(), 12u);
  EXPECT_TRUE(calibration_set("held-out-40").empty());
  EXPECT_TRUE(calibration_set("").empty());
}

// A span too short for four quarters of the structure function's longest lag is not read by quarters.
TEST(NoiseModel, SpansTooShortForQuartersAreNotVoted) {
  using namespace calibration;
  const Curve c = CalibrationCase::at(calibration_set("held-out-7"), 1).draw({"bundle N=1e5", 0, 100000});
  ASSERT_GE(walk_dominated_quarters(c.force, c.energy, 0, c.force.size() - 1), 2);
  EXPECT_EQ(walk_dominated_quarters(c.force, c.energy, 100, 100 + 4 * 33 - 2), 0);
  EXPECT_EQ(walk_dominated_quarters(c.force, c.energy, 200, 100), 0);
}

TEST(PrecursorOrder, SaysWhatTheIntervalResolves) {
  EXPECT_EQ(precursor_order(0.01, 0.03), "x_p comes before x_c (delta_x > 0 at 95 %)");
  EXPECT_EQ(precursor_order(-0.03, -0.01), "x_p comes after x_c (delta_x < 0 at 95 %)");
  EXPECT_EQ(precursor_order(-0.01, 0.03),
            "the order of x_p and x_c is not resolved (the 95 % interval of delta_x includes 0)");
}

namespace {

// Weibull ELS curves F = x e^(-x^3), E_e = F x / 2: x_c = 3^(-1/3), x_p the maximum of F (1 - 1.5 x^3).
double weibull3_force(double x) { return x * std::exp(-x * x * x); }
double weibull3_energy(double x) { return 0.5 * x * weibull3_force(x); }
double weibull3_x_p() {
  double best = 0.0, top = 0.0;
  for (int i = 1; i <= 1000000; ++i) {
    const double x = i * 1e-6, rate = weibull3_force(x) * (1.0 - 1.5 * x * x * x);
    if (rate > top) top = rate, best = x;
  }
  return best;
}

// Whether one of the result's warnings holds `text`.
bool warns(const AnalysisResult& r, std::string_view text) {
  return std::any_of(r.warnings.begin(), r.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

}  // namespace

// A curve written as `rupture run` writes it: strain ∝ steps² over a smooth start (10 % of the run),
// then a row every 200 steps, and a stop row off that lattice. The grid is the rows' own lattice, so
// the even rows are kept as they are; a grid of as many points over the range fell between the rows
// and read the white noise at 0.31 % where the rows carry 0.5 % (docs/analysis.md, "On DEM runs").
TEST(AnalyzeCurve, ARunsUnevenRowsAreAnalysedOnTheirOwnLattice) {
  Curve c;
  c.source = "run-like";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const double x_c = std::cbrt(1.0 / 3.0), ramp = 10000, stop = 100037;
  const double speed = 1.6 * x_c / (stop - ramp / 2);
  std::vector<double> steps;
  for (double s = 0; s <= 100000; s += 200) steps.push_back(s);
  steps.push_back(stop);
  for (double s : steps) {
    const double x = s < ramp ? speed * s * s / (2 * ramp) : speed * (s - ramp / 2);
    c.strain.push_back(x);
    c.force.push_back(weibull3_force(x));
    c.energy.push_back(weibull3_energy(x));
  }
  const double F_c = weibull3_force(x_c);
  add_noise(c, 0.005 * F_c, 0.005 * weibull3_energy(1.0), 11);
  const std::span<const double> columns[] = {c.force, c.energy};
  ResampleReport report;
  const UniformCurves grid = resample_uniform(c.strain, columns, report);
  EXPECT_TRUE(report.resampled);
  EXPECT_TRUE(report.on_lattice);
  EXPECT_NEAR(grid.step, speed * 200, 1e-12);
  EXPECT_NEAR(grid.x(grid.size() - 1), c.strain[c.strain.size() - 2], 1e-12);  // the last even row
  std::size_t kept = 0;  // even rows whose values the grid holds unchanged
  for (std::size_t i = 0; i + 1 < c.strain.size(); ++i) {
    const double at = (c.strain[i] - grid.x0) / grid.step;
    const auto k = static_cast<std::size_t>(std::lround(at));
    if (std::abs(at - static_cast<double>(k)) < 1e-6 && k < grid.size()) {
      EXPECT_NEAR(grid.y[0][k], c.force[i], 1e-12 * F_c) << i;
      ++kept;
    }
  }
  EXPECT_GE(kept, 450u);
  const auto r = analyze_curve(c, {});
  EXPECT_TRUE(r.resample.on_lattice);
  EXPECT_NEAR(r.force_noise, 0.005 * F_c, 0.1 * 0.005 * F_c);
  EXPECT_FALSE(r.collapse_onset);  // the law's own gradual decline is no collapse
}

// Rows in close pairs (a logger writing twice per tick): the small gap is the median spacing, and its
// lattice would hold a million points for 2,000 rows; the grid of as many points as rows serves instead.
TEST(AnalyzeCurve, RowsInClosePairsAreNotPutOnTheLatticeOfTheirSmallGap) {
  std::vector<double> strain, force;
  for (int k = 0; k < 1000; ++k) {
    for (const double x : {k * 1e-3, k * 1e-3 + 1e-9}) {
      strain.push_back(x);
      force.push_back(weibull3_force(x));
    }
  }
  const std::span<const double> columns[] = {force};
  ResampleReport report;
  const UniformCurves grid = resample_uniform(strain, columns, report);
  EXPECT_TRUE(report.resampled);
  EXPECT_FALSE(report.on_lattice);
  EXPECT_EQ(grid.size(), 2000u);
  EXPECT_NEAR(grid.step, strain.back() / 1999.0, 1e-15);
}

// A Weibull k = 3 curve that falls by e every 3 rows from `cut` on (a brittle sample breaking apart), F
// with white noise of `force_noise` of F_c and E_e of `energy_noise` of its value at the cut (by default
// 2 % and 0.2 %, as on rupture's own runs).
Curve brittle_curve(double cut, std::size_t rows, std::uint64_t seed, double force_noise = 0.02,
                    double energy_noise = 0.002) {
  const double x_c = std::cbrt(1.0 / 3.0);
  Curve c;
  c.source = "collapse";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const double step = 1.5 * x_c / static_cast<double>(rows - 1);
  for (std::size_t i = 0; i < rows; ++i) {
    const double x = step * static_cast<double>(i);
    const double fall = x > cut ? std::exp(-(x - cut) / (3 * step)) : 1.0;
    c.strain.push_back(x);
    c.force.push_back(weibull3_force(std::min(x, cut)) * fall);
    c.energy.push_back(weibull3_energy(std::min(x, cut)) * fall);
  }
  add_noise(c, force_noise * weibull3_force(x_c), energy_noise * weibull3_energy(cut), seed);
  return c;
}

// One filter over the whole record spreads the drop back with an overshoot and put x_p at the
// collapse (0.80-0.83 where it is 0.49) and δ_x near 0; filtered on either side of the onset, the
// loading keeps its maxima.
TEST(AnalyzeCurve, ASharpCollapseDoesNotPullThePrecursorOntoIt) {
  const double x_c = std::cbrt(1.0 / 3.0), x_p = weibull3_x_p(), cut = 1.2 * x_c;
  const std::size_t rows = 500;
  const double step = 1.5 * x_c / (rows - 1);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto r = analyze_curve(brittle_curve(cut, rows, seed), {});
    ASSERT_TRUE(r.accepted) << seed << ": " << r.rejection;
    ASSERT_TRUE(r.collapse_onset) << seed;
    EXPECT_NEAR(*r.collapse_onset, cut, 3 * step) << seed;
    EXPECT_EQ(to_json(r)["collapse_onset"]["unit"], "1");
    // The intervals take the factors of curves cut by a collapse (ACurveCutByACollapseTakesTheFactorsOf
    // HowCloseItComes), and a warning says the record was cut.
    EXPECT_TRUE(warns(r, "collapse too sharp for the filter")) << seed;
    EXPECT_NEAR(r.x_p->value, x_p, 0.05 * x_p) << seed;
    EXPECT_NEAR(r.x_c->value, x_c, 0.05 * x_c) << seed;  // rms 1.8 % over 20 seeds (flat top, 2 % noise)
    // 0.15 until the loading's cut end was continued by its trend line (filter_continuing_end): that
    // extends F's top as a plateau and moves x_c towards the cut, δ_x's rms error on this line 8.0 ->
    // 10.9 % over 20 seeds (and 30.6 -> 19.4 % at 1.05 x_c); seed 2 here is now 17 % off.
    EXPECT_NEAR(r.delta_x->value, x_c - x_p, 0.2 * (x_c - x_p)) << seed;
    EXPECT_LT(r.delay->ci95_low, x_c - x_p) << seed;
    EXPECT_GT(r.delay->ci95_high, x_c - x_p) << seed;
  }
}

// A curve cut by a collapse takes the collapse tables' factors (collapse_delta_scales and the strain
// ones) by its noise kind and by how close the collapse comes to the force peak: near at 1.05 x_c, far
// at 1.2 x_c; each interval is the bootstrap's own stretched by them, calibrated in the cells that passed
// held-out 39 (δ_x's and x_p's far walk cells, x_c's white far cell). Under the corner form, which the
// factors were not learned with, with the bootstrap's own asked for, or on a walk without its step profile,
// the intervals are the bootstrap's own, not calibrated, and the warning says which.
TEST(AnalyzeCurve, ACurveCutByACollapseTakesTheFactorsOfHowCloseItComes) {
  // The cells written out here, not through CollapseIntervalScales::for_curve, so a swap there shows.
  const auto cell = [](const CollapseIntervalScales& table, bool walk, bool near) {
    return walk ? (near ? table.walk_near : table.walk_far) : (near ? table.white_near : table.white_far);
  };
  AnalysisOptions own;
  own.calibrated_intervals = false;
  AnalysisOptions corner;
  corner.force_peak_form = PeakForm::corner;
  AnalysisOptions stationary_walk;
  stationary_walk.uncertainty.walk_profile = false;
  const auto bundle_shape = calibration::weibull(3);
  const double white_x_c = std::cbrt(1.0 / 3.0), bundle_x_c = calibration::truth(bundle_shape).x_c;
  for (const bool walk : {false, true}) {
    for (const double cut : {1.05, 1.2}) {
      // White: brittle_curve; walk: a finite bundle (N = 10^5) held from the cut on, as the calibration's
      // brittle bundle groups are.
      Curve curve = walk ? calibration::finite_bundle_curve(bundle_shape, 1000, 100000, 3)
                         : brittle_curve(cut * white_x_c, 500, 3);
      if (walk) calibration::cut_at_collapse(curve, bundle_shape, cut * bundle_x_c, false);
      const auto r = analyze_curve(curve, {});
      const auto bootstrap = analyze_curve(curve, own);
      const std::string which = fmt::format("{} cut at {} x_c", walk ? "bundle" : "white", cut);
      ASSERT_TRUE(r.accepted && bootstrap.accepted) << which << ": " << r.rejection << bootstrap.rejection;
      ASSERT_EQ(scored_as_random_walk(r), walk) << which;
      ASSERT_TRUE(collapse_closeness(r)) << which;
      EXPECT_NEAR(*collapse_closeness(r), cut - 1.0, 0.03) << which;
      const bool near = cut < 1.1;
      ASSERT_EQ(is_near_collapse(*collapse_closeness(r)), near) << which << ": " << *collapse_closeness(r);
      EXPECT_EQ(to_json(r)["collapse_closeness"]["value"].get<double>(), *collapse_closeness(r)) << which;
      const auto delta = cell(collapse_delta_scales, walk, near);
      const auto critical = cell(collapse_critical_scales, walk, near);
      const auto precursor = cell(collapse_precursor_scales, walk, near);
      EXPECT_EQ(r.interval_scales.level68, delta.level68) << which;
      EXPECT_EQ(r.interval_scales.level95, delta.level95) << which;
      EXPECT_EQ(r.x_c_interval->scales.level68, critical.level68) << which;
      EXPECT_EQ(r.x_p_interval->scales.level95, precursor.level95) << which;
      // Held-out 39 calibrated δ_x's and x_p's far walk cells and x_c's white far cell.
      const bool far_walk = walk && !near, far_white = !walk && !near;
      EXPECT_EQ(delta.calibrated, far_walk) << which;
      EXPECT_EQ(precursor.calibrated, far_walk) << which;
      EXPECT_EQ(critical.calibrated, far_white) << which;
      EXPECT_EQ(r.x_p_interval->scales.calibrated, far_walk) << which;
      EXPECT_EQ(r.interval_scales.calibrated, far_walk) << which;
      EXPECT_EQ(r.x_c_interval->scales.calibrated, far_white) << which;
      // The same bootstrap, stretched: x_c's and x_p's half-widths are the factor times the own sd, δ_x's
      // the factor times the own half-width on each side; the reported sd of each is the own sd times the
      // 68 % factor.
      EXPECT_NEAR(r.x_c->error, critical.level68 * bootstrap.x_c->error, 1e-12) << which;
      EXPECT_NEAR(r.x_c_interval->ci95_high - r.x_c->value,
                  std::max(1.96 * critical.level95, critical.level68) * bootstrap.x_c->error, 1e-12)
          << which;
      EXPECT_NEAR(r.delay->sd, delta.level68 * bootstrap.delay->sd, 1e-12) << which;
      EXPECT_NEAR(r.x_p_interval->ci95_high - r.x_p->value,
                  std::max(1.96 * precursor.level95, precursor.level68) * bootstrap.x_p->error, 1e-12)
          << which;
      EXPECT_DOUBLE_EQ(r.delay->mean, bootstrap.delay->mean) << which;
      EXPECT_NEAR(r.delay->ci68_high - r.delay->mean,
                  delta.level68 * (bootstrap.delay->ci68_high - bootstrap.delay->mean), 1e-12)
          << which;
      EXPECT_TRUE(warns(r, near ? "x_c after x_c: near" : "x_c after x_c: far")) << which;
      EXPECT_TRUE(warns(r, "take the factors of such curves")) << which;
      const std::string status =
          far_walk ? fmt::format(
                         "calibrated for x_p and delta_x (their cells passed {}); not calibrated for x_c [",
                         collapse_factors_checked_on)
          : far_white
              ? fmt::format(
                    "calibrated for x_c (their cells passed {}); not calibrated for x_p and delta_x [",
                    collapse_factors_checked_on)
              : std::string("not calibrated for x_c, x_p and delta_x [");
      EXPECT_TRUE(warns(r, "how close the collapse comes (near: less than 10 % of x_c after it); " + status))
          << which << ": " << fmt::format("{}", fmt::join(r.warnings, "\n"));
      // Each interval not calibrated says what its own cell's check found short, in x_c, x_p, δ_x order
      // inside one bracket that ends the status; a calibrated one says nothing there.
      std::vector<std::string> shortfalls;
      for (const auto& [name, scales] :
           {std::pair{"x_c", critical}, std::pair{"x_p", precursor}, std::pair{"delta_x", delta}}) {
        EXPECT_EQ(scales.shortfall.empty(), scales.calibrated) << which << ", " << name;
        if (!scales.calibrated) shortfalls.push_back(fmt::format("{}: {}", name, scales.shortfall));
      }
      EXPECT_TRUE(
          warns(r, fmt::format("[on {}'s curves with known answers in this curve's cell ({} with a {} "
                               "collapse), {}] (docs/analysis.md",
                               collapse_factors_checked_on, walk ? "a random walk" : "white noise",
                               near ? "near" : "far", fmt::join(shortfalls, "; "))))
          << which << ": " << fmt::format("{}", fmt::join(r.warnings, "\n"));
      EXPECT_TRUE(warns(bootstrap, "are the bootstrap's own, not calibrated")) << which;
      // The corner form keeps the bootstrap's own; a stationary walk step does on a walk only (a white
      // curve's intervals do not use the walk's step).
      for (const auto& [options, kept] : {std::pair{corner, true}, std::pair{stationary_walk, walk}}) {
        const auto other = analyze_curve(curve, options);
        ASSERT_TRUE(other.accepted) << which << ": " << other.rejection;
        EXPECT_EQ(other.interval_scales.level68, kept ? 1.0 : delta.level68) << which;
        EXPECT_EQ(other.x_c_interval->scales.level68, kept ? 1.0 : critical.level68) << which;
        EXPECT_EQ(other.x_p_interval->scales.calibrated, !kept && precursor.calibrated) << which;
        EXPECT_EQ(warns(other, "are the bootstrap's own, not calibrated"), kept) << which;
      }
    }
  }
}

// A white curve cut 20 % past its peak sits in x_c's calibrated cell (white far); with a ringing on F as
// large as three times its white noise the noise model reads a ringing, which leaves its intervals not
// calibrated, and the collapse warning, said after it, says so instead of "calibrated".
TEST(AnalyzeCurve, ACalibratedCollapseCellLeftUncalibratedByARingingSaysSo) {
  const double x_c = std::cbrt(1.0 / 3.0);
  Curve c = brittle_curve(1.2 * x_c, 500, 3);
  const calibration::StepOscillator mode(3.3);
  Rng rng(21, RandomStream::analysis_noise);
  std::vector<double> ringing(c.force.size(), 0.0);
  for (std::size_t i = 2; i < ringing.size(); ++i) mode.step(ringing, i, rng.normal());
  double square = 0.0;
  for (double v : ringing) square += v * v / double(ringing.size());
  const auto plain = analyze_curve(c, {});
  for (std::size_t i = 0; i < c.force.size(); ++i)
    c.force[i] += 0.06 * weibull3_force(x_c) * ringing[i] / std::sqrt(square);
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(plain.accepted && r.accepted) << plain.rejection << r.rejection;
  ASSERT_FALSE(scored_as_random_walk(r));
  ASSERT_FALSE(is_near_collapse(*collapse_closeness(r)));
  EXPECT_TRUE(plain.x_c_interval->scales.calibrated);
  EXPECT_TRUE(warns(
      plain,
      "how close the collapse comes (near: less than 10 % of x_c after it); calibrated for x_c (their"));
  ASSERT_TRUE(ringing_read(r));
  EXPECT_FALSE(r.interval_scales.calibrated || r.x_c_interval->scales.calibrated ||
               r.x_p_interval->scales.calibrated);
  EXPECT_TRUE(warns(r, "rings"));
  EXPECT_TRUE(warns(r, fmt::format("not calibrated here for x_c, although their cells passed {}",
                                   collapse_factors_checked_on)));
}

// In the white far cell, whose x_c factors passed their check, F's white noise at 0.05 % of F_c lies
// below the level from which the white factors were checked (white_factors_checked_from): x_c's
// interval (sized by F's noise) keeps its factor, not calibrated here, and the collapse warning says so
// apart from x_p's and δ_x's, whose cells failed the check.
TEST(AnalyzeCurve, AnIntervalWhoseCellPassedButWhoseNoiseLevelWasNotCheckedSaysSo) {
  const double x_c = std::cbrt(1.0 / 3.0), cut = 1.2 * x_c;
  const auto r = analyze_curve(brittle_curve(cut, 500, 3, 5e-4, 0.01), {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  ASSERT_FALSE(scored_as_random_walk(r));
  ASSERT_FALSE(is_near_collapse(*collapse_closeness(r)));
  EXPECT_FALSE(r.x_c_interval->scales.calibrated);
  EXPECT_EQ(r.x_c_interval->scales.level68, collapse_critical_scales.white_far.level68);
  EXPECT_FALSE(r.x_p_interval->scales.calibrated || r.interval_scales.calibrated);
  EXPECT_TRUE(warns(
      r,
      fmt::format("; not calibrated here for x_c, although their cells passed {}: another warning "
                  "says why (a ringing, the smoothing floor, a white noise below the levels from which "
                  "the white factors were checked); not calibrated for x_p and delta_x [on {}'s curves "
                  "with known answers in this curve's cell (white noise with a far collapse), x_p: {}; "
                  "delta_x: {}] (docs/analysis.md",
                  collapse_factors_checked_on, collapse_factors_checked_on,
                  collapse_precursor_scales.white_far.shortfall, collapse_delta_scales.white_far.shortfall)))
      << fmt::format("{}", fmt::join(r.warnings, "\n"));
}

// Cut 5 % past the force peak (the default study's run breaks 7 % past it), the loading's filtered end
// reaches both maxima. The plain padding pinned it to the last noisy sample before the drop and flipped
// the curve's bend there: x_p 0.55 on average over 20 seeds where it is 0.49, δ_x 26 % short. Continued
// by its end's tangent (filter_continuing_end), over 20 seeds δ_x's mean error is -4.2 % (rms 8.9 %;
// -7.2 % and 9.8 % with the straight line), 19 are accepted (seed 6 here loses a maximum in 11 of 200
// replicates, the limit is 10) and δ_x's 95 % interval holds the truth on all 19.
TEST(AnalyzeCurve, TheLoadingsCutEndLeavesThePrecursorWhereItIs) {
  const double x_c = std::cbrt(1.0 / 3.0), x_p = weibull3_x_p();
  int accepted = 0, held = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const auto r = analyze_curve(brittle_curve(1.05 * x_c, 500, seed), {});
    if (!r.accepted) {
      EXPECT_TRUE(r.rejection.starts_with("the peaks are unstable under the curve's own noise"))
          << seed << ": " << r.rejection;
      continue;
    }
    ++accepted;
    ASSERT_TRUE(r.collapse_onset) << seed;
    EXPECT_NEAR(r.x_p->value, x_p, 0.07 * x_p) << seed;
    EXPECT_NEAR(r.x_c->value, x_c, 0.05 * x_c) << seed;
    EXPECT_LE(r.x_c->value, *r.collapse_onset) << seed;
    // At the cut x_c keeps its bootstrap shift and x_p takes its half correction; δ_x follows both.
    EXPECT_NEAR(r.delta_x->value, r.x_c->value - r.x_p->value, 1e-12) << seed;
    EXPECT_NEAR(r.delta_x->value, x_c - x_p, 0.3 * (x_c - x_p)) << seed;
    held += r.delay->ci95_low < x_c - x_p && r.delay->ci95_high > x_c - x_p;
  }
  EXPECT_GE(accepted, 9);
  EXPECT_GE(held, accepted - 1);
}

// A run-like curve (calibration_set.hpp) analysed with default options, with where it was cut and its
// row spacing (strain).
struct AnalysedRunLike {
  double cut, row;
  AnalysisResult r;
};
AnalysedRunLike analysed_run_like(const calibration::Shape& s, const calibration::RunRows& rows,
                                  std::uint64_t seed) {
  const Curve c = calibration::run_like_curve(s, 10000, rows, seed);
  return {calibration::run_like_cut(s, seed), c.strain[1] - c.strain[0], analyze_curve(c, {})};
}

// A run's rows every 100 steps of a sample that comes apart (calibration_set.hpp's run-like curves):
// F rings at a third of a cycle per row, reads as white and is barely filtered (cutoff ~0.46), and F
// takes ~9 rows to fall from twice the collapse level to below it. With a collapse width of two filter
// edges (6 rows) the drop was not taken for a collapse, the derivative's overshoot at its corner won ℰ's
// search and x_p came out 0.73-0.81 where it is 0.49 (δ_x of the wrong sign); with the onset walked back
// through F's ringing only as far as the width, the loading kept E_e's first falling rows. Now the
// onset lies within 10 rows of the cut, before it, and the maxima are the loading's. Since F's walk is
// read under its ringing (block means), the replicates wander more and seed 31017 loses a maximum in
// 12 of 200 (the limit is 10): the only rejection allowed here is that one, and the measurement must
// hold either way.
TEST(AnalyzeCurve, ARunsRingingCollapseIsFoundWhereE_eBeginsToFall) {
  using namespace calibration;
  const Shape s = weibull(3);
  const Truth t = truth(s);
  for (const std::uint64_t seed : {1017, 7017, 31017}) {
    const auto [cut, row, r] = analysed_run_like(s, {100, false, 0.008, true}, seed);
    EXPECT_TRUE(r.accepted || r.rejection.starts_with("the peaks are unstable under the curve's own noise"))
        << seed << ": " << r.rejection;
    ASSERT_TRUE(r.x_p && r.x_c && r.delta_x) << seed;
    ASSERT_TRUE(r.collapse_onset) << seed;
    EXPECT_LE(*r.collapse_onset, cut) << seed;
    EXPECT_GE(*r.collapse_onset, cut - 10 * row) << seed;
    EXPECT_NEAR(r.x_p->value, t.x_p, 0.03 * t.x_p) << seed;
    EXPECT_NEAR(r.x_c->value, t.x_c, 0.03 * t.x_c) << seed;
    EXPECT_NEAR(r.delta_x->value, t.delta(), 0.15 * t.delta()) << seed;
  }
}

// The same run's means every 400 steps: 250 rows, the force peak some 70 rows in, and F falls from
// twice the collapse level to below it over 3-4 rows (by e every 2.5 rows, each row a mean over its
// interval). A twentieth of the rise to the peak (3 rows) did not take that for a collapse: one filter
// then ran across it, ℰ peaked on its corner, x_p came out past x_c (0.85-0.92 where it is 0.47,
// δ_x -0.13 to -0.20 where it is +0.24) and the bootstrap's bias correction moved it further. A drop
// within 5 rows is now a collapse however short the rise.
TEST(AnalyzeCurve, ACollapseOverAFewCoarseRowsIsFoundHoweverShortTheRise) {
  using namespace calibration;
  const Shape s = weibull(2);
  const Truth t = truth(s);
  for (const std::uint64_t seed : {30017, 42017, 186017}) {
    const auto [cut, row, r] = analysed_run_like(s, {400, true, 0.008, true}, seed);
    ASSERT_TRUE(r.x_p && r.x_c && r.delta_x) << seed << ": " << r.rejection;
    ASSERT_TRUE(r.collapse_onset) << seed;
    EXPECT_LE(*r.collapse_onset, cut + row) << seed;
    EXPECT_GE(*r.collapse_onset, cut - 5 * row) << seed;
    EXPECT_LT(r.x_p->value, r.x_c->value) << seed;
    EXPECT_NEAR(r.x_p->value, t.x_p, 0.1 * t.x_p) << seed;
    EXPECT_NEAR(r.delta_x->value, t.delta(), 0.3 * t.delta()) << seed;
  }
}

// Run-like bundles that come apart 3-6 % past their force peak (the study's runs: 3-7 %), means every
// 200 steps. The collapse's first filtered samples, pinned by their padding to the first noisy one,
// stood above the loading's top and x_c's cubic was fitted round them; with the loading continued by a
// line that rises over a concave top too, x_c came out early: on these 16 curves by 2.8 % on average,
// 10 of them by more than 3 %. Now the collapse's start is held at the loading's end and the loading is
// continued by its end's tangent: mean -0.95 %, one curve (Weibull k = 2, seed 12, cut at 1.031 x_c)
// at -4.6 %.
TEST(AnalyzeCurve, TheForcePeakOfALoadingCutJustPastItIsNotPulledIntoTheCollapse) {
  using namespace calibration;
  double sum = 0.0;
  int curves = 0, far_early = 0;
  for (const Shape& s : {weibull(2), weibull(3), uniform(0.2, 1.0), power_law(-0.5)}) {
    const Truth t = truth(s);
    for (const std::uint64_t seed : {7, 12, 13, 14}) {
      const auto [cut, row, r] = analysed_run_like(s, {200, true, 0.008, true}, seed);
      ASSERT_LT(cut, 1.06 * t.x_c) << s.name << " " << seed;
      ASSERT_TRUE(r.x_c && r.collapse_onset) << s.name << " " << seed << ": " << r.rejection;
      const double error = (r.x_c->value - t.x_c) / t.x_c;
      far_early += error < -0.03;
      sum += error;
      ++curves;
    }
  }
  EXPECT_LT(std::abs(sum / curves), 0.015);
  EXPECT_LE(far_early, 2);
}

// Dem-like curves at rows every 100 steps, single samples (the tuning set's first twelve): F's ringing,
// a few rows a period, reads as white noise or as signal, and the discrepancy rule alone barely
// smoothed (curve 3: x_p 21 % of x_c late, on a spike of E_e's walk).
// The smoothing floor (a quarter of the rise to the force peak, an option) accepts all twelve and
// halves x_p's rms error (docs/analysis.md, "The smoothing floor").
TEST(AnalyzeCurve, ARingingRunAtFineRowsIsSmoothedOverAQuarterOfItsRise) {
  using namespace calibration;
  const auto set = calibration_set("tuning");
  const NoiseGroup group = dem_like_group(100, false);
  AnalysisOptions floor, rule_alone;  // the default is the rule alone
  floor.smoothing_floor_share = 0.25;
  struct Score {
    int accepted = 0;
    double squares = 0.0;
    double rms() const { return std::sqrt(squares / accepted); }
  } floor_score, rule_score;
  int floors_applied = 0;
  for (int k = 0; k < 12; ++k) {
    const auto curve_case = CalibrationCase::at(set, k);
    const Curve c = curve_case.draw(group);
    const auto t = run_like_truth(curve_case.shape, curve_case.seed, group.run);
    const auto floored = analyze_curve(c, floor), rule = analyze_curve(c, rule_alone);
    EXPECT_FALSE(rule.smoothing_floor_applied);
    if (floored.smoothing_floor_applied) {  // elsewhere the rule smoothed harder
      ++floors_applied;
      EXPECT_TRUE(floored.collapse_onset) << k;  // kept on a cut record whose peaks lie apart
    }
    if (floored.accepted) {
      EXPECT_GE(2.0 / floored.filter.cutoff, 0.2 * (floored.x_c->value - floored.x0) / floored.step) << k;
      ++floor_score.accepted;
      floor_score.squares += std::pow((floored.x_p->value - t.x_p) / t.x_c, 2);
    }
    if (rule.accepted) {
      ++rule_score.accepted;
      rule_score.squares += std::pow((rule.x_p->value - t.x_p) / t.x_c, 2);
    }
  }
  EXPECT_GE(floors_applied, 6);
  EXPECT_EQ(floor_score.accepted, 12);
  EXPECT_LE(rule_score.accepted, 10);
  EXPECT_LT(floor_score.rms(), 0.06);
  EXPECT_GT(rule_score.rms(), 0.07);
}

// Under the smoothing floor a quarter of the rise reaches from ℰ's maximum over the force peak into the
// collapse on dem-like curves of held-out 31's sharp power laws (α = 7.4 and 9.1): the floor is
// withdrawn there, and the analysis is the rule alone's, number for number. A record that goes on past
// its peak (Weibull k = 3 under 0.2 % white noise, 5,000 rows) keeps it.
TEST(AnalyzeCurve, TheSmoothingFloorIsWithdrawnWhereItReachesIntoACollapse) {
  using namespace calibration;
  const auto set = calibration_set("held-out-31");
  const NoiseGroup group = dem_like_group(400, true);
  AnalysisOptions floor;
  floor.smoothing_floor_share = 0.25;
  for (const int k : {1, 7}) {
    const auto curve_case = CalibrationCase::at(set, k);
    ASSERT_TRUE(curve_case.shape.name.starts_with("powerlaw alpha=")) << curve_case.shape.name;
    const Curve c = curve_case.draw(group);
    const auto floored = analyze_curve(c, floor), rule = analyze_curve(c, {});
    ASSERT_TRUE(rule.collapse_onset) << k;
    EXPECT_TRUE(floored.smoothing_floor_withdrawn) << k;
    EXPECT_FALSE(floored.smoothing_floor_applied) << k;
    EXPECT_EQ(floored.filter.cutoff, rule.filter.cutoff) << k;
    EXPECT_EQ(floored.accepted, rule.accepted) << k;
    ASSERT_TRUE(rule.x_p && floored.x_p) << k;
    EXPECT_EQ(floored.x_p->value, rule.x_p->value) << k;
    ASSERT_EQ(bool(floored.delay), bool(rule.delay)) << k;
    if (rule.delay) {
      EXPECT_EQ(floored.delay->ci95_high, rule.delay->ci95_high) << k;
    }
    EXPECT_TRUE(warns(floored, "the smoothing floor was withdrawn")) << k;
    auto others = floored.warnings;  // the rule alone's, and the one that says so
    std::erase_if(others,
                  [](const std::string& w) { return w.starts_with("the smoothing floor was withdrawn"); });
    EXPECT_EQ(others, rule.warnings) << k;
    EXPECT_TRUE(to_json(floored)["filter"]["smoothing_floor_withdrawn"].get<bool>()) << k;
  }
  const auto past_peak = analyze_curve(white_noise_curve(weibull(3), 5000, 0.002, 1), floor);
  ASSERT_TRUE(past_peak.accepted) << past_peak.rejection;
  EXPECT_TRUE(past_peak.smoothing_floor_applied);
  EXPECT_FALSE(past_peak.smoothing_floor_withdrawn);
}

// Dem-like curves (a force that rises to a corner and sags to the collapse, as a tissue's does; rows
// every 200 steps as means): the cubic over the filtered top puts x_c early (docs/analysis.md, "Known
// answers with a DEM-like top"); PeakForm::corner takes the corner of two lines on the rows there, and
// says so in the fit.
TEST(AnalyzeCurve, AForceThatTurnsAtACornerKeepsX_cThereWithTheCornerForm) {
  using namespace calibration;
  const auto set = calibration_set("tuning");
  const NoiseGroup group = dem_like_group(200, true);
  AnalysisOptions corner;
  corner.force_peak_form = PeakForm::corner;
  double smooth_sum = 0.0, corner_sum = 0.0;
  int corners = 0;
  for (int k = 0; k < 8; ++k) {
    const auto curve_case = CalibrationCase::at(set, k);
    const Curve c = curve_case.draw(group);
    const double x_c = run_like_truth(curve_case.shape, curve_case.seed, group.run).x_c;
    const auto smooth_result = analyze_curve(c, {}), corner_result = analyze_curve(c, corner);
    ASSERT_TRUE(smooth_result.x_c && corner_result.x_c) << k;
    EXPECT_FALSE(smooth_result.force_peak->corner);
    if (!corner_result.force_peak->corner) continue;  // no collapse found, or x_c clear of it
    smooth_sum += (smooth_result.x_c->value - x_c) / x_c;
    corner_sum += (corner_result.x_c->value - x_c) / x_c;
    ++corners;
  }
  ASSERT_GE(corners, 6);
  EXPECT_LT(smooth_sum / corners, -0.01) << "the cubic over the corner is early";
  EXPECT_LT(std::abs(corner_sum / corners), 0.5 * std::abs(smooth_sum / corners));
}

// A curve that does not come apart keeps the cubic under PeakForm::corner, to the bit, and says so.
TEST(AnalyzeCurve, TheCornerFormLeavesACurveWithoutACollapseAlone) {
  Curve c = testing::power_law_curve(2.0, 1001);
  testing::add_noise(c, 0.003, 3e-4, 11);
  AnalysisOptions corner;
  corner.force_peak_form = PeakForm::corner;
  const auto smooth_result = analyze_curve(c, {}), corner_result = analyze_curve(c, corner);
  ASSERT_TRUE(smooth_result.x_c && corner_result.x_c);
  EXPECT_FALSE(corner_result.collapse_onset);
  EXPECT_FALSE(corner_result.force_peak->corner);
  EXPECT_EQ(corner_result.x_c->value, smooth_result.x_c->value);
  EXPECT_EQ(corner_result.x_c->error, smooth_result.x_c->error);
  ASSERT_TRUE(corner_result.delay && smooth_result.delay);
  EXPECT_EQ(corner_result.delay->mean, smooth_result.delay->mean);
  const auto said =
      std::find_if(corner_result.warnings.begin(), corner_result.warnings.end(),
                   [](const std::string& w) { return w.find("corner asked for") != std::string::npos; });
  EXPECT_NE(said, corner_result.warnings.end());
  EXPECT_EQ(
      std::find_if(smooth_result.warnings.begin(), smooth_result.warnings.end(),
                   [](const std::string& w) { return w.find("corner asked for") != std::string::npos; }),
      smooth_result.warnings.end());
}

// A bundle of Weibull k = 10 fibres (x_p = 0.660, x_c = 0.794: ℰ peaks close to F) that comes apart at
// 1.02 x_c, F falling by e a row towards 7 % of its value and E_e towards 30 %, `rows_to_peak` rows up to
// x_c, 0.5 % white noise on F and 0.1 % on E_e: a DEM run's rows every 1,000 steps.
Curve sharp_bundle_collapse(std::size_t rows_to_peak, std::uint64_t seed) {
  const double k = 10.0, x_c = std::pow(1.0 / k, 1.0 / k), step = x_c / static_cast<double>(rows_to_peak);
  const auto force = [&](double x) { return x * std::exp(-std::pow(x, k)); };
  const auto energy = [&](double x) { return 0.5 * x * x * std::exp(-std::pow(x, k)); };
  const double cut = 1.02 * x_c;
  Curve c;
  c.source = "sharp bundle collapse";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (std::size_t i = 0; i < rows_to_peak * 8 / 5; ++i) {
    const double x = step * static_cast<double>(i), fall = std::exp(-(x - cut) / step);
    c.strain.push_back(x);
    c.force.push_back(x <= cut ? force(x) : force(cut) * (0.07 + 0.93 * fall));
    c.energy.push_back(x <= cut ? energy(x) : energy(cut) * (0.3 + 0.7 * fall));
  }
  add_noise(c, 0.005 * force(x_c), 0.001 * energy(cut), seed);
  return c;
}

// With 30 rows up to the peak the collapse takes ~2 rows and ℰ's search, which stops short of the onset
// by the filter's edge, ends before ℰ's maximum. The drop was not taken for a collapse (a twentieth of
// the rise is 1 row); one filter across it put x_p at its corner, 0.719 ± 0.0045 where it is 0.660, and
// δ_x 0.028 where it is 0.134, accepted. Now the curve is rejected and the reason says what to do; with
// 200 rows up to the peak the precursor is found.
TEST(AnalyzeCurve, APrecursorTooCloseToTheCollapseForTheRowsIsRejectedWithTheReason) {
  const double x_p = 0.6595;  // the maximum of d/dx (x^2/2 exp(-x^10))
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const auto coarse = analyze_curve(sharp_bundle_collapse(30, seed), {});
    EXPECT_FALSE(coarse.accepted) << seed;
    EXPECT_TRUE(coarse.collapse_onset) << seed;
    EXPECT_NE(coarse.rejection.find("the rows are too coarse to hold the precursor apart from it"),
              std::string::npos)
        << seed << ": " << coarse.rejection;
    const auto dense = analyze_curve(sharp_bundle_collapse(200, seed), {});
    ASSERT_TRUE(dense.accepted) << seed << ": " << dense.rejection;
    EXPECT_NEAR(dense.x_p->value, x_p, 0.03 * x_p) << seed;
  }
}

// The same run's rows every 100 steps without coming apart: F's ringing hid its walk (x_c's sd a third
// of its error on such curves). The walk is now read on block means; that reading is not checked on
// held-out curves, so the three intervals say they are not calibrated, and a warning says why.
TEST(AnalyzeCurve, ARingingForceIsReadOnBlockMeansAndItsIntervalsAreNotCalibrated) {
  using namespace calibration;
  const Curve c = run_like_curve(weibull(3), 10000, {100, false, 0.008, false}, 1017);
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_TRUE(ringing_read(r));
  EXPECT_GE(r.noise_model.force.ringing_block, 2u);
  // E_e carries the bundle's walk without ringing: F's walk is taken from it.
  EXPECT_EQ(r.noise_model.energy.ringing_block, 0u);
  EXPECT_TRUE(r.noise_model.force.walk_from_energy);
  EXPECT_GT(r.noise_model.force.walk, 0.0);
  EXPECT_FALSE(r.x_c_interval->scales.calibrated);
  EXPECT_FALSE(r.x_p_interval->scales.calibrated);
  EXPECT_FALSE(r.interval_scales.calibrated);
  EXPECT_TRUE(warns(r, "rings"));
  EXPECT_TRUE(warns(r, "taken from E_e's"));
}

// Replicates that all agree (a bootstrap window read as noise-free) still leave the bias's half as
// error: the interval is the normal one of that sd, not zero wide around the estimate.
TEST(BootstrapIntervalOf, ReplicatesThatAllAgreeGiveTheNormalIntervalOfTheirBias) {
  const auto s = bootstrap_interval(1.0, std::vector<double>(200, 1.2));
  EXPECT_NEAR(s.estimate, 0.9, 1e-12);
  EXPECT_NEAR(s.sd, 0.1, 1e-12);
  EXPECT_NEAR(s.ci68_low, 0.8, 1e-12);
  EXPECT_NEAR(s.ci68_high, 1.0, 1e-12);
  EXPECT_NEAR(s.ci95_low, 0.9 - 0.1 * 1.959963984540054, 1e-12);
  EXPECT_NEAR(s.ci95_high, 0.9 + 0.1 * 1.959963984540054, 1e-12);
}

// The option words both doors take (rupture analyze, rupture.analyze) name each value once and back:
// what the command line checks, what the Python keywords map and what analysis.json writes agree.
TEST(OptionWords, EveryValueHasOneWordThatNamesItBack) {
  for (const auto& w : delay_method_words) {
    EXPECT_EQ(from_word(delay_method_words, w.word), w.value) << w.word;
    EXPECT_EQ(std::string_view(to_string(w.value)), w.word);
  }
  for (const auto& w : peak_form_words) {
    EXPECT_EQ(from_word(peak_form_words, w.word), w.value) << w.word;
    EXPECT_EQ(std::string_view(to_string(w.value)), w.word);
  }
  EXPECT_FALSE(from_word(peak_form_words, "sharp"));
  EXPECT_FALSE(from_word(delay_method_words, "Fitted-Maxima"));  // words are exact, as on the command line
  EXPECT_EQ(word_list(delay_method_words), (std::vector<std::string>{"fitted-maxima", "shift-l1"}));
  EXPECT_EQ(quoted_words(peak_form_words), "\"smooth\" or \"corner\"");
  constexpr std::array<OptionWord<int>, 3> three{{{"a", 1}, {"b", 2}, {"c", 3}}};
  EXPECT_EQ(quoted_words(three), "\"a\", \"b\" or \"c\"");
  EXPECT_EQ(word_of(three, 2), "b");
}

}  // namespace
}  // namespace rupture::analysis
