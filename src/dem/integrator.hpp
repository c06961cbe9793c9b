// dem/integrator: velocity Verlet. The half-kick (with viscous damping and its energy), and the
// first half of a step: half-kick, drift and the glued particles' rigid motion, which also measures
// how far particles moved since the neighbour list was built and this step's largest move. It runs
// inside the step's one parallel region (dem/system), before the force pass.
// The second half-kick is fused into the force pass (dem/forces), which calls half_kick below.
// Owns: the integration formulas. Not: forces.
#pragma once

#include <cstdint>
#include <vector>

#include "dem/neighbours.hpp"
#include "dem/particles.hpp"
#include "dem/step_context.hpp"

namespace rupture::dem {

// v <- v (1 - c h) + h f / m over a half step h (s) for damping rate c (1/s); with damping, the work of
// -c m v over the half step (with the mean of the old and new velocity) is added to `damped` (mJ).
template <bool damped>
inline void half_kick(double& vx, double& vy, double& vz, double fx, double fy, double fz, double half,
                      double inv_mass, double mass, double damping, double& damped_energy) {
  const double h = half * inv_mass;
  if constexpr (damped) {
    const double keep = 1.0 - damping * half;
    const double vx0 = vx, vy0 = vy, vz0 = vz;
    vx = vx0 * keep + h * fx;
    vy = vy0 * keep + h * fy;
    vz = vz0 * keep + h * fz;
    damped_energy +=
        damping * half * mass * 0.5 * (vx0 * vx0 + vy0 * vy0 + vz0 * vz0 + vx * vx0 + vy * vy0 + vz * vz0);
  } else {
    vx += h * fx;
    vy += h * fy;
    vz += h * fz;
  }
}

struct DriftResult {
  double largest_move = 0.0;  // mm: largest displacement since the last list build
  double second_move = 0.0;   // mm: second largest
  double move2 = 0.0;         // 1: largest (|dt v| / r)^2 of this step (inf when non-finite)
  std::uint32_t mover = 0;    // storage index reaching it
};

// One thread's share of a DriftResult: squared moves, merged by kick_drift.
struct DriftShare {
  double first = 0.0, second = 0.0;  // mm^2: two largest squared moves since the list build
  double move2 = -1.0;               // largest (|dt v| / r)^2 of this step
  std::uint32_t mover = 0xffffffffu;
};

// First half-kick and drift to the step's end; glued particles in rigid mode follow their plate.
// Called by every thread of the enclosing parallel region (or outside one): each sweeps its static
// share of the particles into shares[thread], and after a barrier each merges all shares, so every
// thread returns the same result, whatever the split. `shares` has a slot per thread.
DriftResult kick_drift(const StepContext& step, ParticleStore& particles, const NeighbourList& neighbours,
                       const Params& params, std::vector<DriftShare>& shares);

}  // namespace rupture::dem
