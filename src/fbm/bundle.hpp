// fbm/bundle: finite bundles of N fibers with drawn thresholds: the exact strain-controlled ELS
// curve, quasi-static load-controlled ELS loading with its bursts (avalanches), and local load
// sharing (LLS) on a ring. All per N κ = 1. Not: the N → ∞ theory (els_theory.hpp) or any I/O.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "fbm/distribution.hpp"
#include "fbm/els_theory.hpp"

namespace rupture::fbm {

// N thresholds in ring order: fiber i gets quantile(u_i), u_i from Rng(seed, fbm_thresholds,
// block) with blocks of 2^16 fibers, so the bundle is the same for every thread count and platform.
std::vector<double> draw_thresholds(const StrengthDistribution& distribution, std::size_t fibers,
                                    std::uint64_t seed);

// A measured curve: `curve` is decimated to at most the requested number of points; the
// characteristics are measured on the full data for F and E_e, and for ℰ (which a finite bundle
// has only as a difference quotient) on the decimated curve by central differences with a
// parabola through the top three points.
struct BundleCurve {
  std::vector<CurvePoint> curve;
  Characteristics measured;
};

// Strain-controlled ELS, exact: a fiber breaks when the strain exceeds its threshold, so with the
// thresholds sorted the curve is known everywhere. `curve` samples `points` equally spaced strains
// on [0, largest threshold]. O(N log N) for the sort, then one pass.
BundleCurve strain_controlled(std::vector<double> thresholds, std::size_t points);

// Load-controlled loading: the load is raised quasi-statically to the weakest surviving fiber's
// breaking load, then held while the redistributed load breaks more fibers, until stable. The
// curve interpolates the stable states just before each burst onto `points` equally spaced
// strains up to x_c, where the bundle collapses (so x_m, E_max are not observed). Bursts are
// counted by size, except the final one that breaks the rest of the bundle.
struct LoadControlled {
  BundleCurve result;
  std::map<std::size_t, std::size_t> burst_counts;  // burst size -> number of bursts
  std::size_t final_burst = 0;                      // fibers broken by the last, catastrophic burst
  std::size_t load_steps = 0;                       // bursts in all, the final one included
};

// ELS: O(N log N) through the sorted thresholds.
LoadControlled load_controlled_els(std::vector<double> thresholds, std::size_t points);

// LLS on a ring (thresholds in ring order): a surviving fiber next to broken runs of n_left and
// n_right fibers carries σ (1 + (n_left + n_right)/2), each broken run's load split equally between
// the two survivors bounding it (the last survivor carries everything). Its strain column is the
// mean strain of the intact fibers, F / n_intact. O(N log N) with a heap and a list of survivors.
LoadControlled load_controlled_lls(const std::vector<double>& thresholds, std::size_t points);

// ℰ = dE_e/dx of a sampled curve by central differences (one-sided at the ends), in place.
void fill_energy_rate(std::vector<CurvePoint>& curve);

}  // namespace rupture::fbm
