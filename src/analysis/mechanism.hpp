// analysis/mechanism: the breaking-mechanism class (paper section 5.2: brittle, hyper-elastic,
// semi-ductile, ductile) from measured features of the loading curves and, when available, of the
// bond-breaking history. Not: measuring the peaks (the pipeline passes them in).
// The thresholds are first choices documented in docs/analysis.md; they are to be refined against
// DEM parameter scans.
#pragma once

#include <optional>
#include <span>
#include <string>

namespace rupture::analysis {

struct MechanismFeatures {
  std::optional<double> critical_strain_percent;  // x_c in %, when the strain unit is % or 1
  std::optional<double> energy_peak_width;    // strain width where E_e >= 0.9 E_max, over x_c
  int force_maxima = 0;                       // local force maxima with prominence >= 5 % of F_c
  std::optional<double> break_spread;         // (q90 − q10) of the bond-break strains, over x_c
  std::optional<double> post_peak_decay;      // (x at F = F_c/2 after the peak − x_c) / x_c; none if F stays above
  std::optional<double> gamma;                // Γ
};

struct MechanismRules {
  int ductile_force_maxima = 3;          // this many significant force maxima: ductile
  double ductile_energy_width = 1.0;     // or an E_e peak this wide (relative to x_c) with slow decay
  double ductile_decay = 1.0;            // "slow": F needs more than this (relative to x_c) to halve
  double fast_decay = 0.2;               // brittle/hyper-elastic: F halves within this (relative to x_c)
  double concentrated_breaks = 0.5;      // brittle/hyper-elastic: central 80 % of breaks within this
  double brittle_strain_percent = 2.0;   // brittle: x_c below this (%); above it, hyper-elastic
};

enum class Mechanism { brittle, hyper_elastic, semi_ductile, ductile };

struct MechanismClass {
  Mechanism mechanism;
  std::string reason;  // which rule decided, with the numbers
};

MechanismClass classify(const MechanismFeatures& features, const MechanismRules& rules = {});

// (q90 − q10) / x_c of the strains at which bonds broke; none for fewer than 10 breaks.
std::optional<double> break_spread(std::span<const double> break_strains, double x_c);

const char* to_string(Mechanism mechanism);

}  // namespace rupture::analysis
