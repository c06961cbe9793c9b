// ELS theory: the numerical solver against the closed forms (uniform, power law), the paper's
// monotonicity claims checked one by one, the work balance, finite-difference cross-checks for
// distributions without a closed form, and the lower cut-off rule.
#include "fbm/els_theory.hpp"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <memory>
#include <vector>

#include "fbm/distribution.hpp"
#include "fbm/power_law.hpp"

namespace rupture::fbm {
namespace {

Characteristics solve(const ContinuousDistribution& d) { return ElsTheory(d).characteristics(); }

void expect_relative(double value, double expected, double tolerance, const char* what) {
  EXPECT_NEAR(value, expected, tolerance * std::abs(expected)) << what;
}

TEST(ElsTheory, UniformMatchesThePaperTo1e9) {
  const auto c = solve(Uniform(0.0, 1.0));
  EXPECT_NEAR(c.x_c, 0.5, 1e-9);
  EXPECT_NEAR(c.F_c, 0.25, 1e-9);
  EXPECT_NEAR(*c.x_m, 2.0 / 3.0, 1e-9);
  EXPECT_NEAR(*c.E_max, 4.0 / 27.0 / 2.0, 1e-9);  // x_m² (1 - x_m) / 2
  EXPECT_NEAR(c.x_p, 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(c.Erate_max, 1.0 / 6.0, 1e-9);
  EXPECT_NEAR(c.delta_x, 1.0 / 6.0, 1e-9);
  EXPECT_NEAR(*c.Gamma, 1.0, 1e-9);
  EXPECT_NEAR(*c.A_r, 4.0 / 3.0, 1e-9);
  EXPECT_NEAR(c.E_d_at_x_c, 1.0 / 48.0, 1e-9);  // x_c³ / 6 (eq. 9)
  EXPECT_FALSE(c.Erate_max_at_cutoff);
}

TEST(ElsTheory, PowerLawMatchesTheClosedFormsTo1e9) {
  for (double alpha : {-0.9, -0.5, -0.2, 0.0, 0.5, 1.0, 2.0, 5.0, 10.0}) {
    const auto c = solve(PowerLaw(alpha));
    const auto m = power_law::maxima(alpha);
    SCOPED_TRACE(alpha);
    expect_relative(c.x_c, m.x_c, 1e-9, "x_c");
    expect_relative(c.F_c, m.F_c, 1e-9, "F_c");
    expect_relative(*c.x_m, m.x_m, 1e-9, "x_m");
    expect_relative(*c.E_max, m.E_max, 1e-9, "E_max");
    expect_relative(c.x_p, m.x_p, 1e-9, "x_p");
    expect_relative(c.Erate_max, m.Erate_max, 1e-9, "Erate_max");
    expect_relative(c.delta_x, m.delta_x, 1e-9, "delta_x");
    expect_relative(*c.Gamma, m.Gamma, 1e-9, "Gamma");
    expect_relative(*c.A_r, m.A_r, 1e-9, "A_r");
    expect_relative(c.E_d_at_x_c, m.E_d_at_x_c, 1e-9, "E_d_at_x_c");
    // The paper's ratio forms (eqs. 16, 19, 23) agree with the maxima.
    expect_relative(c.x_c / c.x_p, power_law::critical_to_precursor_ratio(alpha), 1e-9, "eq. 16 x_c");
    expect_relative(*c.x_m / c.x_p, power_law::energy_max_to_precursor_ratio(alpha), 1e-9, "eq. 16 x_m");
    expect_relative(*c.Gamma, power_law::gamma(alpha), 1e-9, "eq. 19");
    expect_relative(*c.A_r, power_law::energy_ratio(alpha), 1e-9, "eq. 23");
  }
  EXPECT_NEAR(*solve(PowerLaw(0.0)).A_r, 4.0 / 3.0, 1e-12);
  EXPECT_NEAR(power_law::energy_ratio(0.0), 4.0 / 3.0, 1e-15);
}

std::vector<double> alpha_grid() {
  return {-0.95, -0.8, -0.5, -0.2, 0.0, 0.3, 0.75, 1.0, 2.0, 3.5, 5.0, 8.0};
}

TEST(ElsTheory, GammaArAndRelativeDelayDecreaseWithAlpha) {
  double previous_gamma = INFINITY, previous_ar = INFINITY, previous_ratio = INFINITY;
  for (double alpha : alpha_grid()) {
    const auto c = solve(PowerLaw(alpha));
    SCOPED_TRACE(alpha);
    EXPECT_LT(*c.Gamma, previous_gamma);
    EXPECT_LT(*c.A_r, previous_ar);
    EXPECT_LT(c.delta_x / c.x_p, previous_ratio);
    previous_gamma = *c.Gamma;
    previous_ar = *c.A_r;
    previous_ratio = c.delta_x / c.x_p;
  }
}

// The paper (after eq. 19) says δ_x decreases monotonically in α with its maximum 1/6 at α = 0.
// It does not: δ_x rises from e^-1 - e^-1.5 at α → -1 to a maximum of 0.169288 near α = 0.754,
// and only then falls. δ_x / x_p (eq. 18 divided by x_p) is the monotone quantity.
TEST(ElsTheory, DelayIsNotMonotoneInAlpha) {
  const auto delta = [](double alpha) { return solve(PowerLaw(alpha)).delta_x; };
  EXPECT_LT(delta(-0.5), delta(0.0));
  EXPECT_GT(delta(0.5), delta(0.0));
  EXPECT_GT(delta(1.0), 1.0 / 6.0);
  EXPECT_NEAR(delta(0.7543802), 0.169288399, 1e-8);
  EXPECT_GT(delta(0.7543802), delta(0.70));
  EXPECT_GT(delta(0.7543802), delta(0.80));
  EXPECT_LT(delta(5.0), delta(0.0));
  EXPECT_NEAR(delta(-1.0 + 1e-7), std::exp(-1.0) - std::exp(-1.5), 1e-6);
}

// ∫_0^x F dy = E_e(x) + E_d(x): work of the load = stored + released energy.
TEST(ElsTheory, WorkEqualsElasticPlusDamageEnergy) {
  const std::vector<std::shared_ptr<ContinuousDistribution>> dists{
      std::make_shared<Uniform>(0.0, 1.0), std::make_shared<Uniform>(0.2, 1.0),
      std::make_shared<PowerLaw>(-0.5),    std::make_shared<PowerLaw>(3.0),
      std::make_shared<Weibull>(2.0, 1.0), std::make_shared<Weibull>(0.7, 1.5)};
  for (const auto& d : dists) {
    const ElsTheory theory(*d);
    for (double u : {0.1, 0.5, 0.9, 0.999}) {
      const double x = d->quantile(u);
      auto force = [&](double y) { return theory.force(y); };
      // Split at the cut-off, where F has a kink.
      double work =
          boost::math::quadrature::gauss_kronrod<double, 31>::integrate(force, 0.0, d->lower(), 12, 1e-11);
      work += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(force, d->lower(), x, 12, 1e-11);
      EXPECT_NEAR(work, theory.elastic_energy(x) + theory.damage_energy(x), 1e-10 * work)
          << d->spec() << " x=" << x;
    }
  }
}

// Distributions without closed forms: the maxima are stationary points of the analytic curves
// (checked by finite differences of F, E_e and ℰ), ℰ is the finite-difference slope of E_e, and
// the Weibull values agree with the roots of eqs. 3 and 10 worked out by hand.
TEST(ElsTheory, WeibullAndUniformCutoffCrossCheckedByFiniteDifferences) {
  const std::vector<std::shared_ptr<ContinuousDistribution>> dists{
      std::make_shared<Weibull>(2.0, 1.0), std::make_shared<Weibull>(0.7, 1.5),
      std::make_shared<Weibull>(5.0, 0.3), std::make_shared<Uniform>(0.2, 1.0),
      std::make_shared<Uniform>(0.1, 2.0)};
  for (const auto& d : dists) {
    const ElsTheory t(*d);
    const auto c = t.characteristics();
    SCOPED_TRACE(d->spec());
    const double h = 1e-4 * c.x_c;
    const auto slope = [h](auto f, double x) { return (f(x + h) - f(x - h)) / (2 * h); };
    const auto F = [&](double x) { return t.force(x); };
    const auto E = [&](double x) { return t.elastic_energy(x); };
    const auto R = [&](double x) { return t.energy_rate(x); };
    EXPECT_NEAR(slope(F, c.x_c), 0.0, 1e-7);
    EXPECT_NEAR(slope(E, *c.x_m), 0.0, 1e-7);
    EXPECT_NEAR(slope(R, c.x_p), 0.0, 1e-7);
    for (double x : {c.x_p, c.x_c, *c.x_m}) EXPECT_NEAR(slope(E, x), t.energy_rate(x), 1e-7);
    EXPECT_LT(c.x_p, c.x_c);
    EXPECT_LT(c.x_c, *c.x_m);
  }
  // Weibull: x_c = λ k^(-1/k) (eq. 3), x_m = λ (2/k)^(1/k) (eq. 10).
  for (double k : {0.7, 2.0, 5.0}) {
    const auto c = solve(Weibull(k, 1.5));
    EXPECT_NEAR(c.x_c, 1.5 * std::pow(k, -1.0 / k), 1e-10 * c.x_c);
    EXPECT_NEAR(*c.x_m, 1.5 * std::pow(2.0 / k, 1.0 / k), 1e-10 * *c.x_m);
  }
  // Uniform on [a, b], a < b/3: x_c = b/2, x_m = 2b/3, x_p = b/3 as for [0, 1] scaled.
  const auto c = solve(Uniform(0.1, 2.0));
  EXPECT_NEAR(c.x_c, 1.0, 1e-10);
  EXPECT_NEAR(*c.x_m, 4.0 / 3.0, 1e-10);
  EXPECT_NEAR(c.x_p, 2.0 / 3.0, 1e-10);
  EXPECT_NEAR(c.Erate_max, (2.0 * 2.0 / 3.0 - 1.5 * 4.0 / 9.0) / 1.9, 1e-10);
}

// With a lower cut-off a, ℰ = x rises to a, then drops by a² p(a)/2. For uniform[0.2, 1] the first
// local maximum (the left limit 0.2 at the cut-off) is beaten by the interior one at 1/3; for
// uniform[0.25, 1] the cut-off wins and ℰ_max is the supremum 0.25, not attained.
TEST(ElsTheory, CutoffJumpTakesTheGlobalMaximumAndSaysSo) {
  const auto inside = solve(Uniform(0.2, 1.0));
  EXPECT_NEAR(inside.x_p, 1.0 / 3.0, 1e-10);
  EXPECT_NEAR(inside.Erate_max, (1.0 / 3.0 - 1.5 / 9.0) / 0.8, 1e-10);
  EXPECT_GT(inside.Erate_max, 0.2);
  EXPECT_FALSE(inside.Erate_max_at_cutoff);

  const auto at_cutoff = solve(Uniform(0.25, 1.0));
  EXPECT_EQ(at_cutoff.x_p, 0.25);
  EXPECT_EQ(at_cutoff.Erate_max, 0.25);
  EXPECT_TRUE(at_cutoff.Erate_max_at_cutoff);
  EXPECT_GT(at_cutoff.Erate_max, ElsTheory(Uniform(0.25, 1.0)).energy_rate(1.0 / 3.0));
  EXPECT_NEAR(at_cutoff.x_c, 0.5, 1e-10);

  // a > b/2: the force peaks at the kink x_c = a; the precursor sits there too, so δ_x = 0 and Γ
  // is undefined.
  const auto brittle = solve(Uniform(0.6, 1.0));
  EXPECT_EQ(brittle.x_c, 0.6);
  EXPECT_EQ(brittle.F_c, 0.6);
  EXPECT_EQ(brittle.x_p, 0.6);
  EXPECT_TRUE(brittle.Erate_max_at_cutoff);
  EXPECT_EQ(brittle.delta_x, 0.0);
  EXPECT_FALSE(brittle.Gamma.has_value());
}

TEST(ElsTheory, CurveColumnsAreTheAnalyticCurves) {
  const Uniform d(0.0, 1.0);
  const auto curve = ElsTheory(d).curve(11);
  ASSERT_EQ(curve.size(), 11u);
  EXPECT_EQ(curve.front().x, 0.0);
  EXPECT_EQ(curve.back().x, 1.0);
  for (const auto& p : curve) {
    EXPECT_NEAR(p.F, p.x * (1 - p.x), 1e-15);
    EXPECT_NEAR(p.E_e, 0.5 * p.x * p.x * (1 - p.x), 1e-15);
    EXPECT_NEAR(p.E_d, p.x * p.x * p.x / 6, 1e-14);                  // eq. 9
    EXPECT_NEAR(p.Erate, p.x * (1 - p.x) - 0.5 * p.x * p.x, 1e-15);  // eq. 12
    EXPECT_NEAR(p.broken_fraction, p.x, 1e-15);
  }
}

// The exact burst-size distribution: Σ_Δ D(Δ)/N = ∫ p (1 - λ) dx = 1 - ln 2 bursts per fiber for
// the uniform bundle, Σ Δ D(Δ) → P(x_c) = 1/2 fibers, and the tail approaches Δ^(-5/2).
TEST(ElsTheory, BurstDistributionIsNormalisedAndHasTheMeanFieldTail) {
  const auto D = burst_size_distribution(Uniform(0.0, 1.0), 20000);
  double bursts = 0.0, fibers = 0.0;
  for (std::size_t size = 1; size <= 4000; ++size) {
    bursts += D[size - 1];
    fibers += static_cast<double>(size) * D[size - 1];
  }
  // The tail beyond 4000 is ≈ C ∫ Δ^(-5/2) ≈ 1e-6.
  EXPECT_NEAR(bursts, 1.0 - std::log(2.0), 1e-5);
  // Fibers broken in bursts → P(x_c) = 1/2, slowly: the tail of Δ D(Δ) falls only as Δ^(-1/2).
  EXPECT_LT(fibers, 0.5);
  EXPECT_GT(fibers, 0.5 - 0.05);
  const double slope = std::log(D[19999] / D[1999]) / std::log(10.0);
  EXPECT_NEAR(slope, -2.5, 0.02);
  // Nearer the bulk the effective exponent is steeper: about -2.6 over sizes 10..100.
  const double local = std::log(D[99] / D[9]) / std::log(10.0);
  EXPECT_LT(local, -2.5);
  EXPECT_GT(local, -2.8);
}

}  // namespace
}  // namespace rupture::fbm
