// analysis/mechanism: the breaking-mechanism class (paper section 5.2: brittle, hyper-elastic,
// semi-ductile, ductile) from measured features of the loading curves and, when available, of the
// bond-breaking history (when and where bonds broke). Not: measuring the peaks (the pipeline passes
// them in). The thresholds and how they were chosen: docs/analysis.md, "Mechanism class".
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace rupture::analysis {

// The bond breaks of a run, as the classifier reads them.
struct BreakLog {
  std::vector<double> strain;  // strain of each break, in the curve's strain unit
  std::vector<double> height;  // where it broke between the glued layers: 0 bottom, 1 top; empty if unknown
};

// Where the sample came apart, from the breaks after the force maximum (the collapse).
struct CrackFeatures {
  double height = 0.0;        // 0..1: mean height of the breaks in the densest band (the main crack)
  double to_plate = 0.0;      // 0..0.5: distance of the main crack to the nearer glued layer
  double localisation = 0.0;  // share of the collapse's breaks within the main crack's band
  int planes = 0;             // separate height bands holding >= 15 % of the collapse's breaks each
};

struct MechanismFeatures {
  std::optional<double> critical_strain_percent;  // x_c in %, when the strain unit is % or 1
  std::optional<double> energy_peak_width;        // strain width where E_e >= 0.9 E_max, over x_c
  int force_maxima = 0;                           // local force maxima with prominence >= 5 % of F_c
  std::optional<double> break_spread;             // (q90 − q10) of the bond-break strains, over x_c
  std::optional<double>
      post_peak_decay;  // (x at F = F_c/2 after the peak − x_c) / x_c; none if F stays above
  std::optional<double>
      loading_undulation;              // deepest dip of F below its running maximum before x_c, over F_c
  std::optional<CrackFeatures> crack;  // from the break heights (none without heights or < 10 breaks)
  std::optional<double> gamma;         // Γ
};

struct MechanismRules {
  int ductile_force_maxima = 3;       // this many significant force maxima: ductile (x_c not identifiable)
  double acoustic_undulation = 0.05;  // semi-ductile: the loading force dips this far (over F_c) before x_c
  double fast_decay = 0.2;            // brittle/hyper-elastic: F halves within this (relative to x_c)
  double concentrated_breaks = 0.5;   // brittle/hyper-elastic: central 80 % of breaks within this (over x_c)
  double near_plate = 0.2;            // brittle: the main crack this close to a glued layer (of l0) ...
  double brittle_strain_percent = 2.0;  // ... or the collapse below this x_c (%); above: hyper-elastic
};

enum class Mechanism { brittle, hyper_elastic, semi_ductile, ductile };

struct MechanismClass {
  Mechanism mechanism;
  std::string reason;  // which rule decided, with the numbers
};

MechanismClass classify(const MechanismFeatures& features, const MechanismRules& rules = {});

// (q90 − q10) / x_c of the strains at which bonds broke; none for fewer than 10 breaks.
std::optional<double> break_spread(std::span<const double> break_strains, double x_c);

// The breaks at strains <= `strain` (with their heights, when known).
BreakLog breaks_until(const BreakLog& breaks, double strain);

// How far a rising curve falls back below its running maximum at most (0 for a monotone one).
double deepest_dip(std::span<const double> values);

// The crack of the collapse: the breaks at strains >= x_c, binned by height into 20 bands; none
// without heights or with fewer than 10 such breaks.
std::optional<CrackFeatures> crack_features(const BreakLog& breaks, double x_c);

const char* to_string(Mechanism mechanism);

}  // namespace rupture::analysis
