// How the analysis's first step reads the noise of the calibration curves (docs/analysis.md,
// "Calibration", held-out 7 and 8): the noise model's verdict "a random walk dominates" (2σ_r² > 6σ_w²
// for F or E_e: random_walk_dominates) from the whole curve, as the analysis decides it, beside the
// number of the curve's quarters where it holds (walk_dominated_quarters; a walk in at least 2 of the
// 4 finds the bundles the whole curve misses), and the whole curve's verdict for F and for E_e apart (where
// they differ the analysis warns; docs/analysis.md, "A filter per curve"), for the noise groups and the
// mixed (DEM-like) groups. Prints one CSV row per curve: set, group, shape, rows,
// whole (0/1), quarters (0-4), force (0/1), energy (0/1). The curves are those of bench/analysis_calibration
// (same shapes, rows and seeds). Usage: noise_kind_votes [curves per group = 36] [set ... as
// analysis_calibration names them; default tuning, held-out-5, held-out-6, held-out-7].
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "analysis/bootstrap.hpp"
#include "calibration_set.hpp"

using namespace rupture::analysis;
using namespace rupture::analysis::calibration;

int main(int argc, char** argv) {
  const int per_group = argc > 1 ? std::atoi(argv[1]) : 36;
  std::vector<std::string> names(argv + std::min(argc, 2), argv + argc);
  if (names.empty()) names = {"tuning", "held-out-5", "held-out-6", "held-out-7"};
  std::printf("set,group,shape,rows,whole,quarters,force,energy\n");
  for (const auto& name : names) {
    const std::vector<Shape> set = calibration_set(name);
    if (set.empty()) {
      std::fprintf(stderr, "noise_kind_votes: unknown set '%s'; see the usage at the top of %s\n",
                   name.c_str(), __FILE__);
      return 2;
    }
    auto groups = noise_groups();
    for (auto& g : mixed_noise_groups()) groups.push_back(g);
    for (const auto& g : groups) {
      for (int k = 0; k < per_group; ++k) {
        const auto curve_case = CalibrationCase::at(set, k);
        const Curve c = curve_case.draw(g);
        const std::size_t n = c.force.size();
        const int quarters = walk_dominated_quarters(c.force, c.energy, 0, n - 1);
        const NoiseModel noise = estimate_noise(c.force, c.energy, 0, n - 1);
        std::printf("%s,%s,\"%s\",%zu,%d,%d,%d,%d\n", name.c_str(), g.name.c_str(),
                    curve_case.shape.name.c_str(), curve_case.rows, random_walk_dominates(noise) ? 1 : 0,
                    quarters, random_walk_dominates(noise.force) ? 1 : 0,
                    random_walk_dominates(noise.energy) ? 1 : 0);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
