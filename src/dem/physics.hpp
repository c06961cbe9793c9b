// dem/physics: what follows from a sample and the model before anything moves: a particle's mass,
// a bond's stiffness and break limit, the strain at which the first bond breaks, the elastic wave
// speed. Owns: these formulas, so that loading/, scan/ and `rupture check` ask here instead of
// writing them again. Not: the stability bound over the assembled system (dem/system computes it
// from its stores with stability_bound below).
#pragma once

#include <cstdint>

#include "dem/params.hpp"
#include "sample/sample.hpp"

namespace rupture::dem {

// Mass (t) of a sphere of `radius` (mm) at `density` (g/mm^3).
double particle_mass(double radius, double density_g_per_mm3);
// A bond's spring constant (N/mm): k_n, or ESyS's k_n * r0 / 4 with scale_stiffness. Inline: the
// force pass derives it from the rest length instead of storing it per link.
inline double bond_stiffness(const Params& params, double rest_length) {
  return params.scale_stiffness ? params.bond_stiffness * rest_length / 4.0 : params.bond_stiffness;
}
// How far (mm) a bond of `rest_length` may stretch before it breaks: b_d, or b * r0 (relative rule).
inline double break_limit(const Params& params, double rest_length) {
  return params.break_rule == BreakRule::absolute ? params.break_distance
                                                  : params.break_distance * rest_length;
}

double mean_rest_length(const Sample& sample);                          // mm; 0 without bonds
double mean_particle_mass(const Sample& sample, const Params& params);  // t

// The nominal break strain (1): b_d / mean r0 (absolute rule) or b (relative rule). A scale, not a
// prediction: the scan's rules measure ramps and row intervals in it.
double nominal_break_strain(const Params& params, double mean_rest_length);
// The plate strain (1) at which the first bond breaks when the sample is stretched affinely along y
// (x and z held): the smallest, over bonds, of the strain that takes that bond past its limit. Bonds
// along y with long rest lengths go first, so this lies below the nominal strain; on the reduced
// tissue it is within 3 % of the first break of a run (docs/dem.md). Infinity without bonds.
double first_break_strain(const Sample& sample, const Params& params);
// The longitudinal wave speed (mm/s) of a chain of the sample's mean bond and mean mass.
double wave_speed(const Sample& sample, const Params& params);

// The largest stable dt (s) of velocity Verlet, 2 / sqrt(lambda), with lambda a Gershgorin bound on
// the largest eigenvalue of M^-1/2 K M^-1/2 over bonds and glue springs (exact for a free pair and an
// infinite chain), and where it is reached.
struct StabilityBound {
  double critical_dt = 0.0;          // s
  double stiffest_spring_sum = 0.0;  // N/mm: that particle's springs
  double stiffest_mass = 0.0;        // t
};

}  // namespace rupture::dem
