// Synthetic loading curves with known answers for the analysis tests: the FBM power-law bundle
// (α = 0 is the uniform one) in closed form, finite bundles, and added Gaussian noise.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "analysis/analysis.hpp"
#include "core/random.hpp"

namespace rupture::analysis::testing {

// Per N κ = 1: F = x (1 − x^(1+α)), E_e = x² (1 − x^(1+α)) / 2 on n points over [0, x_max].
inline Curve power_law_curve(double alpha, std::size_t n, double x_max = 1.0) {
  Curve c;
  c.source = "power_law";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  for (std::size_t i = 0; i < n; ++i) {
    const double x = x_max * static_cast<double>(i) / static_cast<double>(n - 1);
    const double survive = 1.0 - std::pow(x, 1.0 + alpha);
    c.strain.push_back(x);
    c.force.push_back(x * survive);
    c.energy.push_back(0.5 * x * x * survive);
  }
  return c;
}

// The strain-controlled curve of a bundle whose fibers break at `sorted_thresholds`, per N κ = 1,
// sampled at `rows` strains on [0, x_end].
inline Curve bundle_curve(const std::vector<double>& sorted_thresholds, std::size_t rows, double x_end,
                          std::string source) {
  Curve c;
  c.source = std::move(source);
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const std::size_t fibers = sorted_thresholds.size();
  std::size_t broken = 0;
  for (std::size_t i = 0; i < rows; ++i) {
    const double x = x_end * static_cast<double>(i) / static_cast<double>(rows - 1);
    while (broken < fibers && sorted_thresholds[broken] <= x) ++broken;
    const double intact = 1.0 - static_cast<double>(broken) / static_cast<double>(fibers);
    c.strain.push_back(x);
    c.force.push_back(x * intact);
    c.energy.push_back(0.5 * x * x * intact);
  }
  return c;
}

// Strain-controlled finite bundle of `fibers` with power-law thresholds P(x) = x^(1+α) on [0, 1]
// (α = 0: uniform), per N κ = 1, sampled at n strains on [0, 1].
inline Curve finite_bundle(double alpha, std::size_t fibers, std::size_t n, std::uint64_t seed) {
  Rng rng(seed, RandomStream::analysis_noise, 1);
  std::vector<double> thresholds(fibers);
  for (auto& t : thresholds) t = std::pow(rng.uniform01(), 1.0 / (1.0 + alpha));
  std::sort(thresholds.begin(), thresholds.end());
  return bundle_curve(thresholds, n, 1.0, "finite_bundle");
}

inline void add_noise(Curve& c, double force_sigma, double energy_sigma, std::uint64_t seed) {
  Rng rng(seed, RandomStream::analysis_noise);
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    c.force[i] += force_sigma * rng.normal();
    c.energy[i] += energy_sigma * rng.normal();
  }
}

// Gaussian force peak at 0.4 and energy-rate peak at 0.5 (E_e integrates the rate exactly), 2001
// points on [0, 1]: the force maximum comes first, so the true δ_x is −0.1.
inline Curve force_first_curve() {
  Curve c;
  c.source = "force-first";
  c.strain_unit = c.force_unit = c.energy_unit = "1";
  const double width = 0.1, sqrt_pi = std::sqrt(3.14159265358979323846);
  for (int i = 0; i <= 2000; ++i) {
    const double x = i / 2000.0;
    c.strain.push_back(x);
    c.force.push_back(std::exp(-std::pow((x - 0.4) / width, 2)));
    c.energy.push_back(0.5 * sqrt_pi * width * (std::erf((x - 0.5) / width) + std::erf(0.5 / width)));
  }
  return c;
}

}  // namespace rupture::analysis::testing
