// analysis/interval_scales: which noise kind a result is scored as, the noise levels its interval
// factors follow, and the factors themselves (the tables are in analysis.hpp; how they were learned
// and checked: docs/analysis.md, "Calibration").
#include <cmath>

#include "analysis/analysis.hpp"

namespace rupture::analysis {

bool reads_random_walk(const AnalysisResult& r) { return r.force_walk || r.energy_walk; }

bool scored_as_random_walk(const AnalysisResult& r) { return reads_random_walk(r) || r.quiet; }

bool force_walk_hidden(const AnalysisResult& r) {
  const auto& force = r.noise_model.force;
  // The collapse cells were learned with F's walk taken from E_e's where it read none (held-out 39).
  if (force.walk_read_as_zero) return !r.collapse_onset;
  return scored_as_random_walk(r) && force.walk == 0.0 && r.noise_model.energy.walk > 0.0;
}

bool ringing_read(const AnalysisResult& r) {
  return r.noise_model.force.ringing_block > 0 || r.noise_model.energy.ringing_block > 0;
}

IntervalScales white_level_scales(const WhiteLevelScales& model, double energy_white_share) {
  const auto& anchors = model.anchors;
  if (!(energy_white_share >= model.calibrated_from)) return uncalibrated_scales;
  const bool calibrated = model.passed_last_check && energy_white_share <= model.calibrated_to;
  const auto at = [&](const NoiseLevelAnchor& a) { return IntervalScales{a.level68, a.level95, calibrated}; };
  if (energy_white_share <= anchors.front().share) return at(anchors.front());
  for (std::size_t i = 1; i < anchors.size(); ++i) {
    const auto &low = anchors[i - 1], &high = anchors[i];
    if (energy_white_share > high.share) continue;
    const double t = std::log(energy_white_share / low.share) / std::log(high.share / low.share);
    return {(1.0 - t) * low.level68 + t * high.level68, (1.0 - t) * low.level95 + t * high.level95,
            calibrated};
  }
  return at(anchors.back());
}

double energy_white_share(const AnalysisResult& r) {
  if (!r.E_max || r.E_max->value == 0.0) return std::nan("");
  return r.noise_model.energy.white / std::abs(r.E_max->value);
}

std::optional<double> precursor_noise_level(const AnalysisResult& r) {
  const double share = energy_white_share(r);
  if (scored_as_random_walk(r) || std::isnan(share)) return std::nullopt;
  return share;
}

std::optional<double> critical_noise_level(const AnalysisResult& r) {
  if (scored_as_random_walk(r) || !r.F_c || r.F_c->value == 0.0) return std::nullopt;
  return r.noise_model.force.white / std::abs(r.F_c->value);
}

std::optional<double> delay_noise_level(const AnalysisResult& r) {
  const auto energy = precursor_noise_level(r), force = critical_noise_level(r);
  if (!energy || !force) return energy ? energy : force;
  return std::max(*energy, *force);
}

IntervalScales precursor_scales(const AnalysisResult& r, bool walk_profile) {
  if (const auto level = precursor_noise_level(r)) return white_level_scales(precursor_white_levels, *level);
  return precursor_strain_scales.for_noise(scored_as_random_walk(r), walk_profile);
}

namespace {
// White factors are not calibrated below white_factors_checked_from, at the level that sets the
// quantity's spread (none on a walk).
IntervalScales checked_at_level(IntervalScales scales, std::optional<double> level) {
  if (level && !(*level >= white_factors_checked_from)) scales.calibrated = false;
  return scales;
}

// A kind's factors for a curve without a collapse, checked at its level.
IntervalScales kind_scales(const NoiseIntervalScales& kinds, const AnalysisResult& r, bool walk_profile,
                           std::optional<double> level) {
  return checked_at_level(kinds.for_noise(scored_as_random_walk(r), walk_profile), level);
}
}  // namespace

IntervalScales delay_scales(const AnalysisResult& r, bool walk_profile) {
  return kind_scales(delta_interval_scales, r, walk_profile, delay_noise_level(r));
}

IntervalScales critical_scales(const AnalysisResult& r, bool walk_profile) {
  return kind_scales(critical_strain_scales, r, walk_profile, critical_noise_level(r));
}

std::optional<double> collapse_closeness(const AnalysisResult& r) {
  if (!r.collapse_onset || !r.x_c || !(r.x_c->value > 0.0)) return std::nullopt;
  return *r.collapse_onset / r.x_c->value - 1.0;
}

IntervalScales collapse_scales(const CollapseIntervalScales& table, const AnalysisResult& r,
                               std::optional<double> level) {
  const auto closeness = collapse_closeness(r);
  if (!closeness) return uncalibrated_scales;
  return checked_at_level(table.for_curve(scored_as_random_walk(r), is_near_collapse(*closeness)), level);
}

std::string_view noise_name(bool random_walk) { return random_walk ? "random walk" : "white"; }

std::string noise_kind(const AnalysisResult& r) { return std::string(noise_name(scored_as_random_walk(r))); }

}  // namespace rupture::analysis
