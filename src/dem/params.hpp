// dem/params: the model a run simulates, as the engine takes it: bond, contact and glue laws with
// their constants, density, damping and the contact list's skin; the plates and their motion.
// Owns: the engine's input types and defaults. Not: reading them from a config (loading/config).
//
// Units: mm, N, s, tonne (so energy is mJ); density is given in g/mm^3 as users write it.
#pragma once

#include <cstdint>

#include "sample/sample.hpp"

namespace rupture::dem {

enum class BreakRule : std::uint8_t {
  absolute,  // breaks when r - r0 > b_d (mm): the paper's text
  relative,  // breaks when r - r0 > b * r0 (b a strain): ESyS-Particle's rule
};
enum class GlueMode : std::uint8_t {
  spring,  // each glued particle is tied to its anchor on the plate by a stiff isotropic spring
  rigid,   // glued particles move exactly with their plate
};

struct Params {
  double bond_stiffness = 1e3;   // N/mm: k_n; with scale_stiffness, ESyS normalK (N/mm^2)
  double break_distance = 0.05;  // mm for BreakRule::absolute, a strain (1) for ::relative
  BreakRule break_rule = BreakRule::absolute;
  bool scale_stiffness = false;    // ESyS scaling: k = normalK * r0 / 4 per bond
  double contact_stiffness = 1e3;  // N/mm: repulsion between overlapping unbonded particles
  double glue_stiffness = 1e4;     // N/mm: glue spring (GlueMode::spring only)
  GlueMode glue_mode = GlueMode::spring;
  double density = default_density;  // g/mm^3 (sample/sample.hpp: the paper's)
  double damping = 0.0;              // 1/s: viscous damping rate, force -damping * m * v
  double skin = 0.05;                // mm: Verlet-list skin
};

// Which plate a particle is glued to; doubles as the index into per-plate arrays.
enum Plate : std::uint8_t { plate_none = 0, plate_bottom = 1, plate_top = 2 };

// The top plate's prescribed motion at one instant (the bottom plate is fixed).
struct PlateMotion {
  double displacement = 0.0;  // mm, along +y from the start
  double velocity = 0.0;      // mm/s
  double acceleration = 0.0;  // mm/s^2
};

}  // namespace rupture::dem
