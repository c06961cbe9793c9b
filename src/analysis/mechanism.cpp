#include "analysis/mechanism.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

namespace rupture::analysis {

namespace {
std::string show(const std::optional<double>& v) { return v ? fmt::format("{:.3g}", *v) : std::string("n/a"); }
}  // namespace

MechanismClass classify(const MechanismFeatures& f, const MechanismRules& rules) {
  if (f.force_maxima >= rules.ductile_force_maxima) {
    return {Mechanism::ductile, fmt::format("{} significant force maxima (>= {})", f.force_maxima, rules.ductile_force_maxima)};
  }
  const bool slow_decay = !f.post_peak_decay || *f.post_peak_decay > rules.ductile_decay;
  if (f.energy_peak_width && *f.energy_peak_width >= rules.ductile_energy_width && slow_decay) {
    return {Mechanism::ductile, fmt::format("E_e peak width {} x_c (>= {}) and post-peak decay {} x_c (> {})",
                                            show(f.energy_peak_width), rules.ductile_energy_width,
                                            show(f.post_peak_decay), rules.ductile_decay)};
  }
  const bool fast = f.post_peak_decay && *f.post_peak_decay <= rules.fast_decay;
  const bool concentrated = !f.break_spread || *f.break_spread <= rules.concentrated_breaks;
  if (fast && concentrated) {
    const auto breaks = fmt::format("break spread {} x_c (<= {})", show(f.break_spread), rules.concentrated_breaks);
    if (f.critical_strain_percent && *f.critical_strain_percent < rules.brittle_strain_percent) {
      return {Mechanism::brittle, fmt::format("x_c = {} % (< {} %), force halves within {} x_c, {}",
                                              show(f.critical_strain_percent), rules.brittle_strain_percent,
                                              show(f.post_peak_decay), breaks)};
    }
    return {Mechanism::hyper_elastic, fmt::format("x_c = {} % (>= {} % or unknown), force halves within {} x_c, {}",
                                                  show(f.critical_strain_percent), rules.brittle_strain_percent,
                                                  show(f.post_peak_decay), breaks)};
  }
  return {Mechanism::semi_ductile,
          fmt::format("single force peak with gradual decay: post-peak decay {} x_c (> {}) or break spread {} x_c "
                      "(> {}); Γ = {}",
                      show(f.post_peak_decay), rules.fast_decay, show(f.break_spread), rules.concentrated_breaks,
                      show(f.gamma))};
}

std::optional<double> break_spread(std::span<const double> break_strains, double x_c) {
  if (break_strains.size() < 10 || x_c == 0.0) return std::nullopt;
  std::vector<double> sorted(break_strains.begin(), break_strains.end());
  std::sort(sorted.begin(), sorted.end());
  const auto at = [&](double q) {
    const double pos = q * static_cast<double>(sorted.size() - 1);
    const auto k = static_cast<std::size_t>(pos);
    const double t = pos - static_cast<double>(k);
    return k + 1 < sorted.size() ? sorted[k] + t * (sorted[k + 1] - sorted[k]) : sorted[k];
  };
  return (at(0.9) - at(0.1)) / std::abs(x_c);
}

const char* to_string(Mechanism mechanism) {
  switch (mechanism) {
    case Mechanism::brittle: return "brittle";
    case Mechanism::hyper_elastic: return "hyper-elastic";
    case Mechanism::semi_ductile: return "semi-ductile";
    case Mechanism::ductile: return "ductile";
  }
  return "?";
}

}  // namespace rupture::analysis
