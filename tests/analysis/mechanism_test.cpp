// The breaking-mechanism classifier (paper section 5.2): one curve and break log per class, built
// with known features, through the whole pipeline; and the crack measurement on break logs.
#include "analysis/mechanism.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/analysis.hpp"
#include "core/random.hpp"

namespace rupture::analysis {
namespace {

// ELS bundle of Weibull thresholds (shape k, scale 1), per N κ = 1, 2001 rows on [0, x_end]: a
// large k collapses within a few % of x_c, a small k decays slowly.
Curve weibull_curve(double k, double x_end, double undulation = 0.0) {
  Curve c;
  c.source = "weibull";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const double x_c = std::pow(1.0 / k, 1.0 / k);
  for (int i = 0; i <= 2000; ++i) {
    const double x = x_end * i / 2000.0;
    const double intact = std::exp(-std::pow(x, k));
    // Acoustic waves in the loading phase: a standing oscillation of the load, before x_c only.
    const double wave =
        x < 0.8 * x_c ? undulation * std::sin(12.0 * 3.14159265358979 * x / x_c) * x / x_c : 0.0;
    c.strain.push_back(x);
    c.force.push_back(x * intact * (1.0 + wave));
    c.energy.push_back(0.5 * x * x * intact);
  }
  return c;
}

// `n` breaks at strains uniform in [from, to], at heights around the given crack planes (σ = 0.01).
BreakLog breaks_at(double from, double to, std::initializer_list<double> planes, int n = 300) {
  Rng rng(7, RandomStream::analysis_noise);
  BreakLog log;
  const std::vector<double> heights(planes);
  for (int i = 0; i < n; ++i) {
    log.strain.push_back(from + (to - from) * rng.uniform01());
    log.height.push_back(heights[static_cast<std::size_t>(i) % heights.size()] + 0.01 * rng.normal());
  }
  return log;
}

double x_c_of(double k) { return std::pow(1.0 / k, 1.0 / k); }

TEST(MechanismClass, FastCollapseTearingLayersOffAPlateIsBrittle) {
  const double x_c = x_c_of(20.0);
  const auto r = analyze_curve(weibull_curve(20.0, 1.4), {}, breaks_at(x_c, 1.1 * x_c, {0.06}));
  ASSERT_TRUE(r.accepted) << r.rejection;
  ASSERT_TRUE(r.mechanism);
  EXPECT_EQ(r.mechanism->mechanism, Mechanism::brittle) << r.mechanism->reason;
  ASSERT_TRUE(r.features.crack);
  EXPECT_NEAR(r.features.crack->to_plate, 0.06, 0.01);
  EXPECT_EQ(r.features.crack->planes, 1);
  EXPECT_LT(*r.features.post_peak_decay, 0.2);
  EXPECT_EQ(to_json(r)["mechanism"]["class"], "brittle");
}

TEST(MechanismClass, FastCollapseThroughTheBodyIsHyperElastic) {
  const double x_c = x_c_of(20.0);
  const auto r = analyze_curve(weibull_curve(20.0, 1.4), {}, breaks_at(x_c, 1.1 * x_c, {0.45}));
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_EQ(r.mechanism->mechanism, Mechanism::hyper_elastic) << r.mechanism->reason;
  EXPECT_NEAR(r.features.crack->height, 0.45, 0.01);
  EXPECT_GT(r.features.crack->localisation, 0.9);
}

TEST(MechanismClass, GradualDecayWithTwoCracksIsSemiDuctile) {
  const double x_c = x_c_of(4.0);
  const auto r = analyze_curve(weibull_curve(4.0, 2.0), {}, breaks_at(0.6 * x_c, 1.6 * x_c, {0.3, 0.7}));
  ASSERT_TRUE(r.accepted) << r.rejection;
  EXPECT_EQ(r.mechanism->mechanism, Mechanism::semi_ductile) << r.mechanism->reason;
  EXPECT_EQ(r.features.crack->planes, 2);
  EXPECT_GT(*r.features.post_peak_decay, 0.2);
}

TEST(MechanismClass, AcousticWavesInTheLoadingPhaseAreSemiDuctile) {
  // The same fast collapse as the brittle case, but the load dips ~10 % of F_c before the peak.
  const double x_c = x_c_of(20.0);
  const auto r = analyze_curve(weibull_curve(20.0, 1.4, 0.12), {}, breaks_at(x_c, 1.1 * x_c, {0.06}));
  ASSERT_TRUE(r.mechanism);
  EXPECT_EQ(r.mechanism->mechanism, Mechanism::semi_ductile) << r.mechanism->reason;
  EXPECT_GE(*r.features.loading_undulation, 0.05);
}

TEST(MechanismClass, ManyForceMaximaAreDuctileAndRejectedWithoutAClass) {
  // Slow continuous destruction: three load peaks of falling height, each a partial failure.
  Curve c;
  c.source = "ductile";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (int i = 0; i <= 3000; ++i) {
    const double x = 3.0 * i / 3000.0;
    double intact = 1.0;
    for (double at : {0.5, 1.2, 2.0}) intact -= (0.3 / (1.0 + std::exp(-(x - at) / 0.02)));
    intact = std::max(intact, 0.0);
    c.strain.push_back(x);
    c.force.push_back(x * intact);
    c.energy.push_back(0.5 * x * x * intact);
  }
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.mechanism);
  EXPECT_EQ(r.mechanism->mechanism, Mechanism::ductile) << r.mechanism->reason;
  EXPECT_FALSE(r.accepted);
  EXPECT_TRUE(to_json(r)["mechanism"]["class"].is_null());
  EXPECT_EQ(to_json(r)["mechanism"]["features_say"], "ductile");
}

TEST(MechanismClass, AWideEnergyPeakWithOneSmoothForcePeakIsSemiDuctileAndAccepted) {
  // A bundle of two fiber populations (60/40 Weibull, shape 3, scales 1 and 2): the force has one
  // clear maximum, the stronger population keeps E_e up long after it and slows the decay. The
  // paper (section 5.2) calls a wide E_e with a smoothly decaying force semi-ductile; x_c is
  // identifiable, so the curve is analysed, not rejected as ductile.
  Curve c;
  c.source = "two populations";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const auto broken = [](double x) {
    return 0.6 * (1.0 - std::exp(-std::pow(x, 3.0))) + 0.4 * (1.0 - std::exp(-std::pow(x / 2.0, 3.0)));
  };
  for (int i = 0; i <= 2000; ++i) {
    const double x = 4.0 * i / 2000.0;
    c.strain.push_back(x);
    c.force.push_back(x * (1.0 - broken(x)));
    c.energy.push_back(0.5 * x * x * (1.0 - broken(x)));
  }
  const auto r = analyze_curve(c, {});
  ASSERT_TRUE(r.mechanism);
  ASSERT_TRUE(r.features.energy_peak_width && r.features.post_peak_decay);
  EXPECT_GE(*r.features.energy_peak_width, 1.0);  // what the old rule read as a flat top
  EXPECT_GT(*r.features.post_peak_decay, 1.0);
  EXPECT_EQ(r.features.force_maxima, 1);
  EXPECT_EQ(r.mechanism->mechanism, Mechanism::semi_ductile) << r.mechanism->reason;
  EXPECT_TRUE(r.accepted) << r.rejection;
}

TEST(MechanismClass, FastCollapseAtSmallStrainIsBrittleWhereverTheCrackIs) {
  MechanismFeatures f;
  f.post_peak_decay = 0.1;
  f.break_spread = 0.2;
  f.critical_strain_percent = 0.6;
  f.crack = CrackFeatures{.height = 0.4, .to_plate = 0.4, .localisation = 0.5, .planes = 1};
  EXPECT_EQ(classify(f).mechanism, Mechanism::brittle);
  f.critical_strain_percent = 6.0;  // a long elastic build-up
  EXPECT_EQ(classify(f).mechanism, Mechanism::hyper_elastic);
  f.crack->planes = 2;  // two cracks: multi-crack failure
  EXPECT_EQ(classify(f).mechanism, Mechanism::semi_ductile);
}

TEST(MechanismClass, WithoutBreakHeightsTheCriticalStrainDecides) {
  MechanismFeatures f;
  f.post_peak_decay = 0.1;
  f.break_spread = 0.2;
  f.critical_strain_percent = 0.5;
  EXPECT_EQ(classify(f).mechanism, Mechanism::brittle);
  f.critical_strain_percent = 5.0;
  EXPECT_EQ(classify(f).mechanism, Mechanism::hyper_elastic);
  f.break_spread = 0.8;  // breaks spread over most of the loading: not a single release
  EXPECT_EQ(classify(f).mechanism, Mechanism::semi_ductile);
}

TEST(CrackFeatures, NeedHeightsAndTenBreaksAfterThePeak) {
  EXPECT_FALSE(crack_features(BreakLog{{1.0, 2.0}, {}}, 0.5));
  EXPECT_FALSE(crack_features(breaks_at(0.0, 0.4, {0.5}), 0.5));  // all before x_c
  const auto c = crack_features(breaks_at(0.5, 0.6, {0.9}), 0.5);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->height, 0.9, 0.01);
  EXPECT_NEAR(c->to_plate, 0.1, 0.01);
  EXPECT_EQ(c->planes, 1);
}

TEST(CrackFeatures, DiffuseBreakingHasNoDominantPlane) {
  Rng rng(3, RandomStream::analysis_noise);
  BreakLog log;
  for (int i = 0; i < 1000; ++i) {
    log.strain.push_back(1.0);
    log.height.push_back(rng.uniform01());
  }
  const auto c = crack_features(log, 0.5);
  ASSERT_TRUE(c);
  EXPECT_LT(c->localisation, 0.25);  // 3 bands of 20 hold ~15 %
}

}  // namespace
}  // namespace rupture::analysis

namespace rupture::analysis {
namespace {

TEST(MechanismHelpers, DeepestDipAndBreaksUntil) {
  const std::vector<double> rising{0.0, 1.0, 2.0, 3.0};
  EXPECT_EQ(deepest_dip(rising), 0.0);
  const std::vector<double> wavy{0.0, 2.0, 1.5, 3.0, 2.0, 4.0};
  EXPECT_DOUBLE_EQ(deepest_dip(wavy), 1.0);
  const BreakLog log{{0.1, 0.5, 0.9}, {0.2, 0.4, 0.6}};
  const auto kept = breaks_until(log, 0.5);
  EXPECT_EQ(kept.strain, (std::vector<double>{0.1, 0.5}));
  EXPECT_EQ(kept.height, (std::vector<double>{0.2, 0.4}));
  EXPECT_TRUE(breaks_until(BreakLog{{0.1, 0.9}, {}}, 0.5).height.empty());  // heights unknown stay unknown
}

}  // namespace
}  // namespace rupture::analysis
