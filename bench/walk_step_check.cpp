// How well the noise model's random-walk step matches a finite bundle's true step where the maxima
// are measured (docs/analysis.md, "The walk's steps from the falling stiffness"): for each bundle
// group, curves of a calibration set analysed with default options, the model's step of E_e at the
// true x_p and of F at the true x_c, stationary and with the profile of add_walk_profiles, divided by
// the bundle's analytic step there, (x²/2)·√(p(x) h / N) and x·√(p(x) h / N) (per N κ = 1). Prints
// the ratio's median, 10 % and 90 % quantiles and the sd of its logarithm, over the curves whose
// noise a walk dominates.
// Usage: walk_step_check [curves per group = 24] [set = tuning]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "calibration_set.hpp"

using namespace rupture::analysis;
using namespace rupture::analysis::calibration;

namespace {

void print_ratios(const std::string& group, const char* what, std::vector<double> ratios) {
  std::vector<double> logs;
  for (double r : ratios)
    if (std::isfinite(r) && r > 0.0) logs.push_back(std::log(r));
  if (logs.empty()) return;
  std::sort(logs.begin(), logs.end());
  double mean = 0.0, square = 0.0;
  for (double l : logs) mean += l / static_cast<double>(logs.size());
  for (double l : logs) square += (l - mean) * (l - mean) / static_cast<double>(logs.size());
  const auto at = [&](double q) { return std::exp(logs[static_cast<std::size_t>(q * (logs.size() - 1))]); };
  std::printf("| %s | %s | %zu | %.3f | %.3f | %.3f | %.3f |\n", group.c_str(), what, logs.size(), at(0.5),
              at(0.1), at(0.9), std::sqrt(square));
}

}  // namespace

int main(int argc, char** argv) {
  const int per_group = argc > 1 ? std::atoi(argv[1]) : 24;
  const std::string which = argc > 2 ? argv[2] : "tuning";
  const auto set = calibration_set(which);
  if (set.empty() || per_group < 1) {
    std::fprintf(stderr,
                 "walk_step_check: name a positive curve count and a set (tuning, held-out-13, ...)\n");
    return 2;
  }
  AnalysisOptions options;
  options.uncertainty.replicates = 10;  // the noise model does not depend on the replicates
  std::printf(
      "| group | step (model / true) | curves | median | 10 %% | 90 %% | log sd "
      "|\n|---|---|---|---|---|---|---|\n");
  for (const auto& g : noise_groups()) {
    if (g.fibers == 0) continue;
    std::vector<double> energy_flat, energy_profile, force_flat, force_profile;
    for (int k = 0; k < per_group; ++k) {
      const auto curve_case = CalibrationCase::at(set, k);
      const Curve c = curve_case.draw(g);
      const Truth t = truth(curve_case.shape);
      const auto r = analyze_curve(c, options);
      if (!r.accepted) continue;
      const double h = c.strain[1] - c.strain[0];
      const auto index = [&](double x) { return static_cast<std::size_t>(std::lround(x / h)); };
      const std::size_t low = index(r.bootstrap_window_low),
                        high = std::min(index(r.bootstrap_window_high), c.strain.size() - 1);
      const std::size_t at_p = index(t.x_p), at_c = index(t.x_c);
      if (at_p < low || at_p > high || at_c < low || at_c > high) continue;
      const auto true_step = [&](double x, int power) {
        return std::pow(x, power) / (power == 2 ? 2.0 : 1.0) *
               std::sqrt(curve_case.shape.pdf(x) * h / static_cast<double>(g.fibers));
      };
      NoiseModel model = r.noise_model;
      add_walk_profiles(model, c.strain, c.force, low, high);
      const auto step = [](const NoiseComponents& n, std::size_t j) {
        return j < n.walk_profile.size() ? n.walk * n.walk_profile[j] : n.walk;
      };
      if (random_walk_dominates(model.energy)) {
        energy_flat.push_back(model.energy.walk / true_step(t.x_p, 2));
        energy_profile.push_back(step(model.energy, at_p - low) / true_step(t.x_p, 2));
      }
      if (random_walk_dominates(model.force)) {
        force_flat.push_back(model.force.walk / true_step(t.x_c, 1));
        force_profile.push_back(step(model.force, at_c - low) / true_step(t.x_c, 1));
      }
    }
    print_ratios(g.name, "E_e at x_p, stationary", energy_flat);
    print_ratios(g.name, "E_e at x_p, profile", energy_profile);
    print_ratios(g.name, "F at x_c, stationary", force_flat);
    print_ratios(g.name, "F at x_c, profile", force_profile);
    std::fflush(stdout);
  }
  return 0;
}
