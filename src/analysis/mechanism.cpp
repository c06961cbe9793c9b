#include "analysis/mechanism.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace rupture::analysis {

namespace {
std::string show(const std::optional<double>& v) {
  return v ? fmt::format("{:.3g}", *v) : std::string("n/a");
}

std::string crack_text(const std::optional<CrackFeatures>& c) {
  if (!c) return "crack position unknown";
  return fmt::format(
      "main crack at height {:.2f} of l0 ({:.2f} from a plate, {:.0f} % of the collapse's breaks, "
      "{} crack plane{})",
      c->height, c->to_plate, 100.0 * c->localisation, c->planes, c->planes == 1 ? "" : "s");
}
}  // namespace

MechanismClass classify(const MechanismFeatures& f, const MechanismRules& rules) {
  if (f.force_maxima >= rules.ductile_force_maxima) {
    return {Mechanism::ductile,
            fmt::format("{} significant force maxima (>= {})", f.force_maxima, rules.ductile_force_maxima)};
  }
  // A wide E_e peak with a smoothly decaying force is not ductile: the paper (section 5.2) names
  // exactly that the semi-ductile class; x_c stays identifiable. Only a force without one clear
  // maximum makes x_c unidentifiable, so the rule above is the only ductile one.
  if (f.loading_undulation && *f.loading_undulation >= rules.acoustic_undulation) {
    return {
        Mechanism::semi_ductile,
        fmt::format("acoustic waves in the loading phase: the force dips {} F_c (>= {}) below its running "
                    "maximum before x_c; post-peak decay {} x_c; {}",
                    show(f.loading_undulation), rules.acoustic_undulation, show(f.post_peak_decay),
                    crack_text(f.crack))};
  }
  const bool fast = f.post_peak_decay && *f.post_peak_decay <= rules.fast_decay;
  const bool concentrated = !f.break_spread || *f.break_spread <= rules.concentrated_breaks;
  const bool one_crack = !f.crack || f.crack->planes <= 1;
  if (fast && concentrated && one_crack) {
    const auto how = fmt::format("force halves within {} x_c (<= {}), break spread {} x_c (<= {})",
                                 show(f.post_peak_decay), rules.fast_decay, show(f.break_spread),
                                 rules.concentrated_breaks);
    // The cleavage the paper saw: layers torn off a glued layer.
    if (f.crack && f.crack->to_plate <= rules.near_plate)
      return {Mechanism::brittle, fmt::format("{}; {} (<= {}: layers torn off a glued layer)", how,
                                              crack_text(f.crack), rules.near_plate)};
    // Otherwise the length of the elastic build-up decides: a collapse soon after the start of
    // loading is brittle, one after a long build-up hyper-elastic.
    if (f.critical_strain_percent && *f.critical_strain_percent < rules.brittle_strain_percent)
      return {Mechanism::brittle,
              fmt::format("{}; collapse at x_c = {} % (< {} %); {}", how, show(f.critical_strain_percent),
                          rules.brittle_strain_percent, crack_text(f.crack))};
    return {Mechanism::hyper_elastic,
            fmt::format("{}; long elastic build-up, x_c = {} % (>= {} % or unknown); {}", how,
                        show(f.critical_strain_percent), rules.brittle_strain_percent, crack_text(f.crack))};
  }
  return {Mechanism::semi_ductile,
          fmt::format(
              "single force peak, gradual or multi-crack failure: post-peak decay {} x_c (fast <= {}), break "
              "spread {} x_c (concentrated <= {}), {}; E_e peak width {} x_c; Γ = {}",
              show(f.post_peak_decay), rules.fast_decay, show(f.break_spread), rules.concentrated_breaks,
              crack_text(f.crack), show(f.energy_peak_width), show(f.gamma))};
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

BreakLog breaks_until(const BreakLog& breaks, double strain) {
  BreakLog kept;
  const bool heights = breaks.height.size() == breaks.strain.size();
  for (std::size_t i = 0; i < breaks.strain.size(); ++i) {
    if (!(breaks.strain[i] <= strain)) continue;
    kept.strain.push_back(breaks.strain[i]);
    if (heights) kept.height.push_back(breaks.height[i]);
  }
  return kept;
}

double deepest_dip(std::span<const double> values) {
  double running_max = -INFINITY, dip = 0.0;
  for (double v : values) {
    running_max = std::max(running_max, v);
    dip = std::max(dip, running_max - v);
  }
  return dip;
}

std::optional<CrackFeatures> crack_features(const BreakLog& breaks, double x_c) {
  if (breaks.height.size() != breaks.strain.size()) return std::nullopt;
  constexpr int bands = 20;
  std::array<double, bands> count{};
  std::array<double, bands> height_sum{};
  double total = 0.0;
  for (std::size_t i = 0; i < breaks.strain.size(); ++i) {
    if (!(breaks.strain[i] >= x_c) || !std::isfinite(breaks.height[i])) continue;
    const double h = std::clamp(breaks.height[i], 0.0, 1.0);
    const int band = std::min(bands - 1, static_cast<int>(h * bands));
    count[band] += 1.0;
    height_sum[band] += h;
    total += 1.0;
  }
  if (total < 10.0) return std::nullopt;
  // The main crack: the densest band with its two neighbours (a crack plane is rough on the scale of
  // a particle, a band is l0/20).
  const int top = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
  double in_main = 0.0, sum_main = 0.0;
  for (int b = std::max(0, top - 1); b <= std::min(bands - 1, top + 1); ++b)
    in_main += count[b], sum_main += height_sum[b];
  CrackFeatures c;
  c.height = sum_main / in_main;
  c.to_plate = std::min(c.height, 1.0 - c.height);
  c.localisation = in_main / total;
  // Planes: runs of bands each holding >= 5 % of the breaks, counted when the run holds >= 15 %.
  double run = 0.0;
  for (int b = 0; b <= bands; ++b) {
    if (b < bands && count[b] >= 0.05 * total) {
      run += count[b];
      continue;
    }
    if (run >= 0.15 * total) ++c.planes;
    run = 0.0;
  }
  return c;
}

const char* to_string(Mechanism mechanism) {
  switch (mechanism) {
    case Mechanism::brittle:
      return "brittle";
    case Mechanism::hyper_elastic:
      return "hyper-elastic";
    case Mechanism::semi_ductile:
      return "semi-ductile";
    case Mechanism::ductile:
      return "ductile";
  }
  return "?";
}

}  // namespace rupture::analysis
