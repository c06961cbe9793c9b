// dem/force_laws: the three interaction laws as tiny evaluator types, each giving the energy of one
// pair and the scalar that turns the separation vector into a force. Owns: the formulas and their
// units (lengths mm, stiffness N/mm, force N, energy mJ). Not: loops, storage or breaking decisions.
//
// Convention: for a pair with separation d = x_other - x_self (mm) and distance r = |d|,
// `force_over_r(r)` returns c such that the force on `self` is c * d (N); c > 0 pulls self towards
// the other particle (attraction), c < 0 pushes it away.
#pragma once

namespace rupture::dem {

// Elastic bond: E = k/2 (r - r0)^2, F_self = k (r - r0) d/r (a stretched bond pulls the pair together).
struct HookeBond {
  double k;   // N/mm
  double r0;  // mm, rest length

  double stretch(double r) const { return r - r0; }
  double energy(double r) const { return 0.5 * k * (r - r0) * (r - r0); }
  double force_over_r(double r) const { return k * (r - r0) / r; }
};

// A bond that holds up to a stretch `limit` (mm) and gives no force past it: at that configuration
// it breaks (dem/breaks removes it after the force pass that finds it). At a non-finite distance it
// neither holds nor breaks: no force and no break, and the step's stability check stops the run.
struct BreakableBond {
  HookeBond law;
  double limit;  // mm

  bool holds(double r) const { return law.stretch(r) <= limit; }
  bool breaks(double r) const { return law.stretch(r) > limit; }
  double force_over_r(double r) const { return holds(r) ? law.force_over_r(r) : 0.0; }
};

// Repulsion between overlapping unbonded spheres: overlap h = r_i + r_j - r > 0,
// E = k/2 h^2, F_self = -k h d/r; nothing (no attraction) when h <= 0.
struct LinearContact {
  double k;      // N/mm
  double touch;  // mm, r_i + r_j

  double overlap(double r) const { return touch - r; }
  bool touching(double r) const { return r < touch; }
  double energy(double r) const { return r < touch ? 0.5 * k * (touch - r) * (touch - r) : 0.0; }
  double force_over_r(double r) const { return r < touch ? -k * (touch - r) / r : 0.0; }
};

// Glue: an isotropic spring from a particle to its anchor point on a plate, rest length 0:
// E = k/2 |x - a|^2, F = -k (x - a).
struct GlueSpring {
  double k;  // N/mm

  double energy(double dx, double dy, double dz) const { return 0.5 * k * (dx * dx + dy * dy + dz * dz); }
  // Force component on the particle for an offset component (x - a) (mm).
  double force(double offset) const { return -k * offset; }
};

}  // namespace rupture::dem
