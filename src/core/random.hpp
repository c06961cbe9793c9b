// core/random: reproducible random numbers. The same (seed, stream, item) gives the same numbers on
// every platform and for every thread count: generators are PCG (pcg-cpp, whose output is
// specified) and every transform below is written out here rather than taken from
// std::*_distribution, whose output differs between standard libraries.
// Stream ids live in one place (RandomStream) so that no two uses of a seed collide.
#pragma once

#include <cmath>
#include <cstdint>
#include <pcg_random.hpp>

namespace rupture {

// Each consumer of randomness draws from its own stream of the user's seed.
enum class RandomStream : std::uint64_t {
  fbm_thresholds = 1,
  sample_radii = 2,
  sample_packing = 3,
  analysis_noise = 4,  // synthetic noise in tests and calibration studies
  dem_bond_order = 5,
  analysis_bootstrap = 6,  // noise replicates of the analysis's parametric bootstrap
};

// SplitMix64 finaliser: spreads (seed, item) over all 64 bits before seeding PCG.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A generator for one (seed, stream, item): counter-based use, independent of call order elsewhere.
class Rng {
 public:
  Rng(std::uint64_t seed, RandomStream stream, std::uint64_t item = 0)
      : engine_(mix64(seed ^ mix64(item)), static_cast<std::uint64_t>(stream)) {}

  std::uint64_t next_u64() { return engine_(); }

  // Uniform on [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform on (0, 1]: safe under log().
  double uniform01_open_zero() { return 1.0 - uniform01(); }
  double uniform(double a, double b) { return a + (b - a) * uniform01(); }

  // Standard normal by Box-Muller (both values used; the cache makes the sequence deterministic).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double r = std::sqrt(-2.0 * std::log(uniform01_open_zero()));
    const double phi = 2.0 * 3.14159265358979323846 * uniform01();
    spare_ = r * std::sin(phi);
    has_spare_ = true;
    return r * std::cos(phi);
  }

  // Unbiased integer in [0, n) by rejection (Lemire's method would need 128-bit products; this is
  // simple and exact).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    std::uint64_t v;
    do v = engine_();
    while (v >= limit);
    return v % n;
  }

 private:
  pcg64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace rupture
