// fbm/els_theory: the equal-load-sharing bundle of infinitely many fibers (paper section 2), per
// N κ = 1: the curves F, E_e, E_d, ℰ and their maxima x_c, x_m, x_p, solved numerically for any
// distribution. Not: finite bundles and avalanches (bundle.hpp); the power-law closed forms
// (power_law.hpp) are only the test oracle here.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "fbm/distribution.hpp"

namespace rupture::fbm {

// One point of a loading curve, per N κ = 1: strain x, force F = x (1 - P), elastic energy
// E_e = x² (1 - P) / 2, damage energy E_d = ½ ∫ p y² dy, energy rate ℰ = dE_e/dx, broken fraction.
struct CurvePoint {
  double x, F, E_e, E_d, Erate, broken_fraction;
};

// The characteristic points of a curve (paper eqs. 3, 10, 13, 17, 20), per N κ = 1.
struct Characteristics {
  double x_c = 0, F_c = 0;  // force maximum
  // Elastic-energy maximum; not observed under load control, where the bundle collapses at x_c.
  std::optional<double> x_m, E_max;
  double x_p = 0, Erate_max = 0;  // energy-rate maximum (the precursor)
  double delta_x = 0;             // x_c - x_p
  std::optional<double> Gamma;    // (x_m - x_c) / δ_x; undefined when δ_x = 0 or x_m is
  std::optional<double> A_r;      // E_max / (x_p ℰ_max); undefined when x_p ℰ_max = 0 or E_max is
  double E_d_at_x_c = 0;
  // True when ℰ is largest just below a lower cut-off of the support, where p jumps from 0 and ℰ
  // drops: then x_p is the cut-off and ℰ_max the supremum (the left limit), not an attained value.
  bool Erate_max_at_cutoff = false;
};

// Fills δ_x, Γ and A_r from the maxima.
void derive_ratios(Characteristics& c);

// The characteristics as `rupture fbm theory --json` and the Python module give them (null where
// undefined).
nlohmann::json to_json(const Characteristics& c);

// The theory of one continuous distribution. Root finding and quadrature to ~1e-10 relative.
class ElsTheory {
 public:
  explicit ElsTheory(const ContinuousDistribution& distribution) : dist_(distribution) {}

  double force(double x) const;
  double elastic_energy(double x) const;
  double damage_energy(double x) const;  // Gauss-Kronrod quadrature
  double energy_rate(double x) const;    // ℰ(x); at a lower cut-off the value just above it

  // Global maxima of F, E_e and ℰ (not the first local ones), with the cut-off rule above.
  Characteristics characteristics() const;
  // `points` equally spaced strains on [0, x_end], x_end = upper end of the support, or the
  // 1 - 1e-9 quantile for an unbounded one.
  std::vector<CurvePoint> curve(std::size_t points) const;
  double curve_end() const;

 private:
  const ContinuousDistribution& dist_;
};

// Theory for any distribution: ElsTheory for a continuous one; for an Empirical one the exact
// curve of the finite bundle of exactly those thresholds (see bundle.hpp), ℰ by central
// differences on a grid of `points` strains.
Characteristics theory_characteristics(const StrengthDistribution& distribution, std::size_t points = 2001);
std::vector<CurvePoint> theory_curve(const StrengthDistribution& distribution, std::size_t points);

// Exact ELS burst-size distribution under quasi-static load control (Hemmer and Hansen 1992):
// D(Δ)/N = Δ^(Δ-1)/Δ! ∫_0^x_c p (1 - λ) λ^(Δ-1) e^(-Δλ) dx with λ = x p / (1 - P), the mean number
// of further breaks one break triggers. Element Δ - 1 is the expected number of bursts of size Δ
// per fiber, for Δ = 1 .. max_size.
std::vector<double> burst_size_distribution(const ContinuousDistribution& distribution, std::size_t max_size);

}  // namespace rupture::fbm
