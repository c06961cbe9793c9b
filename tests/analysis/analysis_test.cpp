// The pipeline on curves with known answers: analytic FBM bundles (uniform and power law), a curve
// whose force peaks before its energy rate (negative δ_x), rejected shapes, messy sampling, and
// the calibration of the δ_x posterior over many noise seeds.
#include "analysis/analysis.hpp"

#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "fbm/power_law.hpp"
#include "synthetic_curves.hpp"

namespace rupture::analysis {
namespace {

using testing::add_noise;
using testing::power_law_curve;
using testing::force_first_curve;

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
    // Eq. 26 aligns peaks of different shapes; for these skewed peaks the l1 alignment over the
    // default window (F >= 0.8 F_c) sits 2-3 % above x_c − x_p (docs/analysis.md). The direct
    // difference of the fitted maxima is exact.
    EXPECT_NEAR(r.delta_x->value, expected.delta_x, 0.035 * expected.delta_x) << alpha;
    EXPECT_GT(r.delta_x->value, expected.delta_x) << alpha;
    EXPECT_NEAR(r.delta_x_direct->value, expected.delta_x, 2e-4 * expected.delta_x) << alpha;
    EXPECT_NEAR(r.Gamma->value, expected.Gamma, 0.05 * expected.Gamma) << alpha;
    EXPECT_NEAR(r.A_r->value, expected.A_r, 2e-4 * expected.A_r) << alpha;
    ASSERT_TRUE(r.alpha.alpha);
    EXPECT_NEAR(*r.alpha.alpha, alpha, 0.2 * alpha) << alpha;
    EXPECT_TRUE(*r.alpha.energy_ratio_in_band) << alpha;
  }
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
  EXPECT_LT(r.delay->prior_low, -0.1);
}

TEST(AnalyzeCurve, RisingCurveIsRejectedBecauseTheForceMaximumIsAtTheEnd) {
  auto c = power_law_curve(0.0, 1001, 0.45);  // stops before x_c = 0.5
  const auto r = analyze_curve(c, {});
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.rejection.find("force peak: the maximum lies at the end"), std::string::npos) << r.rejection;
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
  EXPECT_EQ(r.force_maxima, 2);
}

TEST(AnalyzeCurve, UnsortedDuplicatedAndUnevenSamplesAreResampled) {
  // Uneven strains x = u^1.5, listed backwards, with every tenth row repeated.
  Curve c;
  c.source = "messy";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (int i = 3000; i >= 0; --i) {
    const double x = std::pow(i / 3000.0, 1.5);
    for (int copy = 0; copy < (i % 10 == 0 ? 2 : 1); ++copy) {
      c.strain.push_back(x);
      c.force.push_back(x * (1.0 - x));
      c.energy.push_back(0.5 * x * x * (1.0 - x));
    }
  }
  const auto r = analyze_curve(c, {});
  EXPECT_FALSE(r.resample.was_sorted);
  EXPECT_EQ(r.resample.duplicates_merged, 301u);
  EXPECT_FALSE(r.resample.was_uniform);
  EXPECT_TRUE(r.resample.resampled);
  EXPECT_EQ(r.resample.output_rows, 3001u);
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_NEAR(r.x_c->value, 0.5, 1e-4);
  EXPECT_NEAR(r.x_p->value, 1.0 / 3.0, 1e-4);
  EXPECT_NEAR(r.delta_x->value, 1.0 / 6.0, 1e-3);
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

// Over many noise seeds the 68 % and 95 % credible intervals must cover the true δ_x = 1/6 of the
// uniform bundle at their nominal rates. With 200 seeds the number covered is binomial: the bounds
// below are the nominal rate ± 4 standard deviations, so a calibrated method fails with
// probability ~1e-4 (and the seeds are fixed, so the outcome is reproducible).
TEST(DelayCalibration, CredibleIntervalsCoverAtTheirNominalRates) {
  const int seeds = 200;
  int covered68 = 0, covered95 = 0;
  std::vector<double> errors;
  for (int seed = 0; seed < seeds; ++seed) {
    auto c = power_law_curve(0.0, 801);
    add_noise(c, 0.004, 0.00002, static_cast<std::uint64_t>(seed));
    const auto r = analyze_curve(c, {});
    ASSERT_TRUE(r.delay) << seed << ": " << r.rejection;
    const double truth = 1.0 / 6.0;
    covered68 += r.delay->ci68_low <= truth && truth <= r.delay->ci68_high;
    covered95 += r.delay->ci95_low <= truth && truth <= r.delay->ci95_high;
    errors.push_back(r.delay->mean - truth);
  }
  const auto bound = [&](double p) { return 4.0 * std::sqrt(seeds * p * (1.0 - p)); };
  RecordProperty("covered68", covered68);
  RecordProperty("covered95", covered95);
  EXPECT_NEAR(covered68, 0.6827 * seeds, bound(0.6827)) << "68 % interval coverage";
  EXPECT_NEAR(covered95, 0.9545 * seeds, bound(0.9545)) << "95 % interval coverage";
  std::printf("coverage 68%%: %d/%d, 95%%: %d/%d\n", covered68, seeds, covered95, seeds);
}

}  // namespace
}  // namespace rupture::analysis
