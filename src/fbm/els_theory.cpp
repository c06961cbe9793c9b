#include "fbm/els_theory.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <limits>

#include "fbm/bundle.hpp"

namespace rupture::fbm {

namespace {

// Relative tolerance of the adaptive quadratures. Boost's Gauss-Kronrod error estimate has a
// round-off floor near 1e-12 relative, so asking for less makes it subdivide to the depth limit.
constexpr double quadrature_tolerance = 1e-11;
constexpr unsigned quadrature_depth = 12;
// Nodes of the bracketing grid, per family (uniform in x, uniform in probability).
constexpr std::size_t bracket_nodes = 4000;

struct Maximum {
  double x = 0, value = -std::numeric_limits<double>::infinity();
};

// Nodes that resolve both the bulk of the distribution (equally spaced in probability) and its
// tails (equally spaced in strain), including the lower cut-off itself.
std::vector<double> bracketing_grid(const ContinuousDistribution& dist, double x_end) {
  const double lo = dist.lower();
  std::vector<double> nodes{lo, x_end};
  for (std::size_t i = 1; i < bracket_nodes; ++i) {
    const double f = static_cast<double>(i) / bracket_nodes;
    nodes.push_back(lo + (x_end - lo) * f);
    const double q = dist.quantile(f);
    if (q > lo && q < x_end) nodes.push_back(q);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

// Global maximum of g on [lo, x_end] given its derivative dg: every +/- sign change of dg between
// grid nodes is refined by TOMS 748 to ~1e-14 relative; the cut-off lo itself is a candidate with
// value g(lo) (callers make g(lo) the left limit). The largest candidate wins, so a first local
// maximum never hides a higher one further on.
template <class G, class DG>
Maximum global_maximum(const std::vector<double>& nodes, double lo, G&& g, DG&& dg) {
  Maximum best;
  if (lo > 0.0) best = {lo, g(lo)};
  const boost::math::tools::eps_tolerance<double> tolerance(std::numeric_limits<double>::digits - 6);
  double a = nodes.front(), da = dg(a);
  for (std::size_t i = 1; i < nodes.size(); ++i) {
    const double b = nodes[i], db = dg(b);
    if (da > 0.0 && db <= 0.0) {
      double root = b;
      if (db < 0.0) {
        std::uintmax_t iterations = 200;
        const auto bracket = boost::math::tools::toms748_solve(dg, a, b, da, db, tolerance, iterations);
        root = 0.5 * (bracket.first + bracket.second);
      }
      const double value = g(root);
      if (value > best.value) best = {root, value};
    }
    a = b;
    da = db;
  }
  return best;
}

}  // namespace

nlohmann::json to_json(const Characteristics& c) {
  const auto optional = [](const std::optional<double>& v) {
    return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  };
  return {{"x_c", c.x_c},
          {"F_c", c.F_c},
          {"x_m", optional(c.x_m)},
          {"E_max", optional(c.E_max)},
          {"x_p", c.x_p},
          {"Erate_max", c.Erate_max},
          {"delta_x", c.delta_x},
          {"Gamma", optional(c.Gamma)},
          {"A_r", optional(c.A_r)},
          {"E_d_at_x_c", c.E_d_at_x_c},
          {"Erate_max_at_cutoff", c.Erate_max_at_cutoff}};
}

void derive_ratios(Characteristics& c) {
  c.delta_x = c.x_c - c.x_p;
  c.Gamma = c.x_m && c.delta_x != 0.0 ? std::optional<double>((*c.x_m - c.x_c) / c.delta_x) : std::nullopt;
  const double scale = c.x_p * c.Erate_max;
  c.A_r = c.E_max && scale > 0.0 ? std::optional<double>(*c.E_max / scale) : std::nullopt;
}

double ElsTheory::force(double x) const { return x * (1.0 - dist_.cdf(x)); }

double ElsTheory::elastic_energy(double x) const { return 0.5 * x * x * (1.0 - dist_.cdf(x)); }

double ElsTheory::damage_energy(double x) const {
  const double lo = dist_.lower(), hi = std::min(x, dist_.upper());
  if (hi <= lo) return 0.0;
  auto integrand = [this](double y) { return 0.5 * y * y * dist_.pdf(y); };
  return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(integrand, lo, hi, quadrature_depth,
                                                                       quadrature_tolerance);
}

double ElsTheory::energy_rate(double x) const {
  if (x < dist_.lower()) return x;
  return x * (1.0 - dist_.cdf(x)) - 0.5 * x * x * dist_.pdf(x);
}

double ElsTheory::curve_end() const {
  return std::isfinite(dist_.upper()) ? dist_.upper() : dist_.quantile(1.0 - 1e-9);
}

Characteristics ElsTheory::characteristics() const {
  const double lo = dist_.lower();
  const double x_end = std::isfinite(dist_.upper()) ? dist_.upper() : dist_.quantile(1.0 - 1e-12);
  const auto nodes = bracketing_grid(dist_, x_end);
  // Below and at the cut-off no fiber has broken (P = 0, p = 0): derivatives there are the
  // left-hand ones, and ℰ(lo) is its left limit lo.
  const auto below = [lo](double x) { return x <= lo; };
  auto dF = [&](double x) { return below(x) ? 1.0 : 1.0 - dist_.cdf(x) - x * dist_.pdf(x); };  // eq. 3
  auto dE = [&](double x) { return below(x) ? x : energy_rate(x); };                           // eq. 10
  auto dR = [&](double x) {                                                                    // eq. 13
    if (below(x)) return 1.0;
    return 1.0 - dist_.cdf(x) - 2.0 * x * dist_.pdf(x) - 0.5 * x * x * dist_.pdf_derivative(x);
  };
  auto R = [&](double x) { return below(x) ? x : energy_rate(x); };
  auto F = [this](double x) { return force(x); };
  auto E = [this](double x) { return elastic_energy(x); };

  Characteristics c;
  const Maximum fmax = global_maximum(nodes, lo, F, dF);
  const Maximum emax = global_maximum(nodes, lo, E, dE);
  const Maximum rmax = global_maximum(nodes, lo, R, dR);
  c.x_c = fmax.x;
  c.F_c = fmax.value;
  c.x_m = emax.x;
  c.E_max = emax.value;
  c.x_p = rmax.x;
  c.Erate_max = rmax.value;
  c.Erate_max_at_cutoff = lo > 0.0 && rmax.x == lo && dist_.pdf(lo) > 0.0;
  c.E_d_at_x_c = damage_energy(c.x_c);
  derive_ratios(c);
  return c;
}

std::vector<CurvePoint> ElsTheory::curve(std::size_t points) const {
  std::vector<CurvePoint> curve;
  if (points < 2) points = 2;
  const double x_end = curve_end();
  double E_d = 0.0, previous = 0.0;
  for (std::size_t i = 0; i < points; ++i) {
    const double x = x_end * static_cast<double>(i) / static_cast<double>(points - 1);
    // Cumulative quadrature, interval by interval, so the whole curve costs one integral.
    const double lo = std::max(previous, dist_.lower()), hi = std::min(x, dist_.upper());
    if (hi > lo) {
      auto integrand = [this](double y) { return 0.5 * y * y * dist_.pdf(y); };
      E_d += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
          integrand, lo, hi, quadrature_depth, quadrature_tolerance);
    }
    previous = x;
    curve.push_back({x, force(x), elastic_energy(x), E_d, energy_rate(x), dist_.cdf(x)});
  }
  return curve;
}

Characteristics theory_characteristics(const StrengthDistribution& distribution, std::size_t points) {
  if (const auto* empirical = dynamic_cast<const Empirical*>(&distribution))
    return strain_controlled(empirical->sorted_thresholds(), points).measured;
  return ElsTheory(dynamic_cast<const ContinuousDistribution&>(distribution)).characteristics();
}

std::vector<CurvePoint> theory_curve(const StrengthDistribution& distribution, std::size_t points) {
  if (const auto* empirical = dynamic_cast<const Empirical*>(&distribution))
    return strain_controlled(empirical->sorted_thresholds(), points).curve;
  return ElsTheory(dynamic_cast<const ContinuousDistribution&>(distribution)).curve(points);
}

std::vector<double> burst_size_distribution(const ContinuousDistribution& distribution,
                                            std::size_t max_size) {
  std::vector<double> density(max_size, 0.0);
  const double lo = distribution.lower(), x_c = ElsTheory(distribution).characteristics().x_c;
  if (x_c <= lo) return density;  // the bundle fails at once: no bursts before the final one
  for (std::size_t size = 1; size <= max_size; ++size) {
    const double delta = static_cast<double>(size);
    // log(Δ^(Δ-1) / Δ!), kept in logs: both factors overflow long before the product does.
    const double log_prefactor = (delta - 1.0) * std::log(delta) - std::lgamma(delta + 1.0);
    auto integrand = [&](double x) {
      const double survivors = 1.0 - distribution.cdf(x), p = distribution.pdf(x);
      if (!(p > 0.0) || !(survivors > 0.0)) return 0.0;
      const double lambda = x * p / survivors;
      if (lambda >= 1.0) return 0.0;
      if (!(lambda > 0.0)) return size == 1 ? p : 0.0;
      return p * (1.0 - lambda) * std::exp(log_prefactor + (delta - 1.0) * std::log(lambda) - delta * lambda);
    };
    density[size - 1] = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
        integrand, lo, x_c, quadrature_depth, 1e-10);
  }
  return density;
}

}  // namespace rupture::fbm
