// The calibrated intervals' coverage in CI (δ_x's, and x_c's and x_p's on random walks): two shares of the
// calibration table (bench/analysis_calibration has the whole of it). Statistical and long (a minute in
// Release), so labelled `long`: they run in the Release test run, not again under the sanitizers (which
// execute the same code in the shorter analysis tests).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/analysis.hpp"
#include "calibration_set.hpp"
#include "synthetic_curves.hpp"

namespace rupture::analysis {
namespace {

using testing::add_noise;
using testing::power_law_curve;

// How often a calibrated interval holds the truth, at both levels, over the curves it was given on.
struct Coverage {
  int curves = 0, covered68 = 0, covered95 = 0;
  void add(double truth, double low68, double high68, double low95, double high95) {
    ++curves;
    covered68 += low68 <= truth && truth <= high68;
    covered95 += low95 <= truth && truth <= high95;
  }
  void add(double truth, const StrainInterval& i) {
    add(truth, i.ci68_low, i.ci68_high, i.ci95_low, i.ci95_high);
  }
  // Both levels at their nominal rates within ± 4 binomial sd (at least 2 curves at 95 %). On tens of
  // curves that is a guard against gross miscalibration (an interval a third too narrow), not a
  // calibration: the 95 % level can only fail from below, since nominal + 4 sd exceeds the count.
  void expect_nominal(const char* what) const {
    const auto bound = [&](double p) { return 4.0 * std::sqrt(curves * p * (1.0 - p)); };
    EXPECT_NEAR(covered68, 0.6827 * curves, bound(0.6827)) << what << ": 68 % interval coverage";
    EXPECT_NEAR(covered95, 0.95 * curves, std::max(bound(0.95), 2.0)) << what << ": 95 % interval coverage";
    ::testing::Test::RecordProperty(std::string(what) + "_covered68", covered68);
    ::testing::Test::RecordProperty(std::string(what) + "_covered95", covered95);
    std::printf("%s: %d curves; covered 68 %%: %d, 95 %%: %d\n", what, curves, covered68, covered95);
  }
};

// Over many noise seeds the 68 % and 95 % intervals must cover the true δ_x = 1/6 of the
// uniform bundle at their nominal rates. With 200 seeds the number covered is binomial: the bounds
// below are the nominal rate ± 4 standard deviations, so a calibrated method fails with
// probability ~1e-4 (and the seeds are fixed, so the outcome is reproducible).
TEST(DelayCalibration, IntervalsCoverAtTheirNominalRatesOnTheUniformBundle) {
  Coverage delta;
  for (int seed = 0; seed < 200; ++seed) {
    auto c = power_law_curve(0.0, 801);
    add_noise(c, 0.004, 0.00002, static_cast<std::uint64_t>(seed));
    const auto r = analyze_curve(c, {});
    ASSERT_TRUE(r.delay) << seed << ": " << r.rejection;
    const auto& d = *r.delay;
    delta.add(1.0 / 6.0, d.ci68_low, d.ci68_high, d.ci95_low, d.ci95_high);
  }
  // White noise: both levels are held to their nominal rates from both sides; each interval is
  // scaled by its level's factor (analysis.hpp, delta_interval_scales), learned on other shapes.
  delta.expect_nominal("delta_x");
}

// The CI share of the calibration table (bench/analysis_calibration has the whole of it): finite
// bundles of 10^5 fibers, whose noise is a random walk, over five shapes other than the uniform law
// and 300-1000 rows. 60 curves: the bounds are the nominal rate ± 4 binomial sd, so they catch an
// interval that is too narrow by a third or more (the l1 posterior covered 0-10 % of such curves).
TEST(DelayCalibration, IntervalsCoverOnFiniteBundlesOfOtherShapes) {
  using namespace calibration;
  const std::vector<Shape> set = {weibull(3), weibull(5), power_law(3), uniform(0.2, 1.0), power_law(-0.5)};
  const int curves = 60;
  Coverage delta, x_c, x_p;
  for (int k = 0; k < curves; ++k) {
    const Shape& s = set[static_cast<std::size_t>(k) % set.size()];
    const std::size_t rows = k % 2 == 0 ? 300 : 1000;
    const auto c = finite_bundle_curve(s, rows, 100000, static_cast<std::uint64_t>(k + 1));
    AnalysisOptions options;
    options.uncertainty.replicates = 100;
    const auto r = analyze_curve(c, options);
    if (!r.accepted) continue;
    const auto exact = calibration::truth(s);
    const auto& d = *r.delay;
    delta.add(exact.delta(), d.ci68_low, d.ci68_high, d.ci95_low, d.ci95_high);
    // x_c's and x_p's intervals count where their walk factors apply, calibrated or not.
    if (scored_as_random_walk(r)) {
      x_c.add(exact.x_c, *r.x_c_interval);
      x_p.add(exact.x_p, *r.x_p_interval);
    }
  }
  EXPECT_GE(delta.curves, curves - 1);
  // On random-walk noise the intervals follow the walk's step profile, scaled by their factors
  // (analysis.hpp, delta_interval_scales, critical_strain_scales, precursor_strain_scales): δ_x's and
  // x_p's, learned again, and x_c's passed held-out 35; all are guarded here.
  delta.expect_nominal("delta_x");
  for (const auto& [name, coverage] : {std::pair{"x_c", x_c}, std::pair{"x_p", x_p}}) {
    EXPECT_GE(coverage.curves, delta.curves - 6) << name << ": most bundles read as a random walk";
    coverage.expect_nominal(name);
  }
}

// The CI share of the white-noise groups: five shapes of the table at 300 and 1000 rows with white noise of
// 0.5 % and 2 % of each peak, levels between the calibration table's (x_p's factors interpolate
// there, analysis.hpp precursor_white_levels). 60 curves, bounds ± 4 binomial sd as above: a guard
// against an interval a third too narrow or too wide, for every interval whose factors are applied.
TEST(DelayCalibration, IntervalsCoverUnderWhiteNoiseBetweenTheTablesLevels) {
  using namespace calibration;
  const std::vector<Shape> set = {weibull(3), weibull(5), power_law(3), log_normal(0.3), weibull_mixture()};
  const int curves = 60;
  Coverage delta, x_c, x_p;
  for (int k = 0; k < curves; ++k) {
    const Shape& s = set[static_cast<std::size_t>(k) % set.size()];
    const std::size_t rows = (k / 5) % 2 == 0 ? 300 : 1000;
    const double level = (k / 10) % 2 == 0 ? 0.005 : 0.02;  // all 20 shape, rows and level combinations
    AnalysisOptions options;
    options.uncertainty.replicates = 100;
    const auto r =
        analyze_curve(white_noise_curve(s, rows, level, static_cast<std::uint64_t>(k + 101)), options);
    if (!r.accepted) continue;
    ASSERT_FALSE(scored_as_random_walk(r)) << s.name << ", " << rows << " rows: white noise read as a walk";
    const auto exact = calibration::truth(s);
    const auto& d = *r.delay;
    ASSERT_TRUE(r.interval_scales.calibrated)
        << s.name << ": δ_x's white intervals at these levels are calibrated";
    // x_c's white factors and x_p's level model, learned again, passed held-out 35.
    EXPECT_TRUE(r.x_c_interval->scales.calibrated) << s.name;
    EXPECT_TRUE(r.x_p_interval->scales.calibrated) << s.name;
    delta.add(exact.delta(), d.ci68_low, d.ci68_high, d.ci95_low, d.ci95_high);
    x_c.add(exact.x_c, *r.x_c_interval);
    x_p.add(exact.x_p, *r.x_p_interval);
  }
  EXPECT_GE(delta.curves, curves - 1);
  delta.expect_nominal("delta_x");
  x_c.expect_nominal("x_c");
  x_p.expect_nominal("x_p");
}

}  // namespace
}  // namespace rupture::analysis
