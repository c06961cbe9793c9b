#include "sample/generator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "sample/formats.hpp"
#include "sample/presets.hpp"
#include "sample/stats.hpp"
#include "sample_fixture.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;
using testing::small_tissue;

// Kolmogorov-Smirnov distance between sorted values and a CDF.
template <class Cdf>
double ks_distance(std::vector<double> values, Cdf&& cdf) {
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  double d = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double f = cdf(values[k]);
    d = std::max({d, f - static_cast<double>(k) / n, static_cast<double>(k + 1) / n - f});
  }
  return d;
}
// Critical KS distance at significance 0.001 (asymptotic): 1.949 / sqrt(n).
double ks_critical(std::size_t n) { return 1.949 / std::sqrt(static_cast<double>(n)); }

TEST(Generator, NoOverlapsAndEverySphereInsideTheBox) {
  const Sample& s = small_tissue().sample;
  const SampleStats stats = compute_stats(s);
  EXPECT_LT(stats.max_overlap, 1e-9);  // mm: exact tangency up to round-off, never interpenetration
  for (std::size_t k = 0; k < s.size(); ++k) {
    const Vec3 p = s.position[k];
    const double r = s.radius[k], eps = 1e-9;
    ASSERT_TRUE(p.x - r >= s.box.lower.x - eps && p.x + r <= s.box.upper.x + eps &&
                p.y - r >= s.box.lower.y - eps && p.y + r <= s.box.upper.y + eps &&
                p.z - r >= s.box.lower.z - eps && p.z + r <= s.box.upper.z + eps)
        << "particle " << k;
  }
}

TEST(Generator, SolidFractionCoordinationAndCountsInTargetRange) {
  const SampleStats stats = compute_stats(small_tissue().sample);
  EXPECT_GE(stats.solid_fraction, 0.55);
  EXPECT_LE(stats.solid_fraction, 0.66);
  EXPECT_GE(stats.mean_coordination, 8.0);  // the paper's tissue: ~10 bonds per particle
  EXPECT_LE(stats.mean_coordination, 12.0);
  EXPECT_EQ(stats.isolated, 0u);
  EXPECT_GT(stats.particles, 1500u);
  EXPECT_LT(stats.particles, 5000u);
  EXPECT_GT(stats.bottom_layer, 50u);
  EXPECT_GT(stats.top_layer, 50u);
}

TEST(Generator, BondsAreExactlyThePairsWithinToleranceWithRestLengthTheInitialDistance) {
  const Sample& s = small_tissue().sample;
  const double tolerance = preset_params("tissue-small").bond_tolerance;
  // Reference: every pair, by brute force (fine for a test; the generator uses a cell grid).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> expected;
  for (std::uint32_t i = 0; i < s.size(); ++i)
    for (std::uint32_t j = i + 1; j < s.size(); ++j) {
      const double gap = norm(s.position[j] - s.position[i]) - s.radius[i] - s.radius[j];
      if (gap < tolerance * 0.5 * (s.radius[i] + s.radius[j])) expected.emplace_back(i, j);
    }
  ASSERT_EQ(s.bonds.size(), expected.size());
  for (std::size_t b = 0; b < s.bonds.size(); ++b) {
    const Bond& bond = s.bonds[b];
    ASSERT_EQ(std::make_pair(bond.i, bond.j), expected[b]) << "bond " << b;  // also: sorted, i < j
    EXPECT_EQ(bond.rest_length, norm(s.position[bond.j] - s.position[bond.i]));
  }
}

TEST(Generator, RadiiStayInsideTheirBounds) {
  const Sample& s = small_tissue().sample;
  const auto [lo, hi] = std::minmax_element(s.radius.begin(), s.radius.end());
  EXPECT_GE(*lo, 0.2);
  EXPECT_LE(*hi, 0.6);
}

// The generator's promise: radii are drawn from the requested truncated log-normal, and until the
// first draw that finds no place, the particles are exactly those draws.
TEST(Generator, DrawnRadiiFollowTheRequestedLogNormal) {
  const auto params = preset_params("tissue-small");
  const TruncatedLogNormal law(params.r_min, params.r_max, params.r_median, params.r_sigma);
  const auto& drawn = small_tissue().report.radii_before_first_discard;
  ASSERT_GT(drawn.size(), 300u);
  const auto cdf = [&](double r) { return law.cdf(r); };
  EXPECT_LT(ks_distance(drawn, cdf), ks_critical(drawn.size()));
  // The same check rejects a distribution the generator was not asked for.
  const TruncatedLogNormal other(params.r_min, params.r_max, 0.3, params.r_sigma);
  EXPECT_GT(ks_distance(drawn, [&](double r) { return other.cdf(r); }), ks_critical(drawn.size()));
}

TEST(Generator, SamplerMatchesTheTruncatedLogNormal) {
  const TruncatedLogNormal law(0.2, 0.6, 0.5, 0.3);
  Rng rng(9, RandomStream::sample_radii);
  std::vector<double> draws(20000);
  for (double& r : draws) r = law.draw(rng);
  EXPECT_LT(ks_distance(draws, [&](double r) { return law.cdf(r); }), ks_critical(draws.size()));
  EXPECT_DOUBLE_EQ(law.quantile(0.0), 0.2);
  EXPECT_DOUBLE_EQ(law.quantile(1.0), 0.6);
  EXPECT_NEAR(law.cdf(law.quantile(0.3)), 0.3, 1e-12);
}

// The known bias (docs/sample.md): gap filling adds small spheres, so the final histogram holds more
// small radii than the log-normal it was drawn from.
TEST(Generator, GapFillingShiftsTheFinalRadiiTowardsSmallOnes) {
  const auto params = preset_params("tissue-small");
  const TruncatedLogNormal law(params.r_min, params.r_max, params.r_median, params.r_sigma);
  const auto& s = small_tissue().sample;
  const double small =
      static_cast<double>(std::count_if(s.radius.begin(), s.radius.end(), [](double r) { return r < 0.25; }));
  EXPECT_GT(small / static_cast<double>(s.size()), 2.0 * law.cdf(0.25));
}

TEST(Generator, SameSeedSameBytesForOneOrTwoThreads) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::string one = format_own(make_preset("tissue-small", 5));
  omp_set_num_threads(2);
  const std::string two = format_own(make_preset("tissue-small", 5));
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
  EXPECT_NE(one, format_own(make_preset("tissue-small", 6)));
}

TEST(Generator, StorageFollowsASpaceFillingCurveWithIdsEqualToIndices) {
  const Sample& s = small_tissue().sample;
  double consecutive = 0.0;
  for (std::size_t k = 0; k + 1 < s.size(); ++k) consecutive += norm(s.position[k + 1] - s.position[k]);
  consecutive /= static_cast<double>(s.size() - 1);
  EXPECT_LT(consecutive, 2.0);  // mm; random order in a 20 x 10 x 5 mm box would give ~8 mm
  for (std::size_t k = 0; k < s.size(); ++k) ASSERT_EQ(s.id[k], static_cast<std::int64_t>(k));
}

TEST(Generator, GluedLayersFollowTheDocumentedRule) {
  const Sample& s = small_tissue().sample;
  const double depth = default_glue_depth(s);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double below = s.position[k].y - s.radius[k] - s.box.lower.y;
    const double above = s.box.upper.y - s.position[k].y - s.radius[k];
    const ParticleGroup expected = below <= depth && below <= above ? ParticleGroup::bottom
                                   : above <= depth                 ? ParticleGroup::top
                                                                    : ParticleGroup::free;
    ASSERT_EQ(s.group[k], expected) << "particle " << k;
  }
}

TEST(Generator, BadParametersAreRejectedNamingTheOption) {
  PackingParams p = preset_params("tissue-small");
  p.r_min = 0.7;
  EXPECT_THAT([&] { generate_sample(p, 1); }, ::testing::ThrowsMessage<InputError>(HasSubstr("--r-min")));
  p = preset_params("tissue-small");
  p.r_max = 3.0;
  EXPECT_THAT([&] { generate_sample(p, 1); }, ::testing::ThrowsMessage<InputError>(HasSubstr("--r-max")));
  p = preset_params("tissue-small");
  p.r_sigma = 0.0;
  EXPECT_THAT([&] { generate_sample(p, 1); }, ::testing::ThrowsMessage<InputError>(HasSubstr("--r-sigma")));
  p = preset_params("tissue-small");
  p.size.y = -1.0;
  EXPECT_THAT([&] { generate_sample(p, 1); }, ::testing::ThrowsMessage<InputError>(HasSubstr("--height")));
}

TEST(Presets, UnknownPresetListsTheKnownOnes) {
  EXPECT_THAT([] { make_preset("tisue", 1); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("use one of: tissue, tissue-small")));
  const auto tissue = preset_params("tissue");
  EXPECT_EQ(tissue.size, (Vec3{80.0, 25.0, 5.0}));
  EXPECT_EQ(tissue.r_min, 0.2);
  EXPECT_EQ(tissue.r_max, 0.6);
}

}  // namespace
}  // namespace rupture
