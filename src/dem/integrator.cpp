#include "dem/integrator.hpp"

#include <algorithm>
#include <limits>

namespace rupture::dem {

namespace {

// The farthest mover of a step: larger (|dt v| / r)^2 wins, ties go to the lower storage index, so
// the result is the same for any split of the loop over threads.
struct MoveMax {
  double move2;
  std::uint32_t index;
};
inline MoveMax farther(const MoveMax& a, const MoveMax& b) {
  return (a.move2 > b.move2 || (a.move2 == b.move2 && a.index < b.index)) ? a : b;
}
#pragma omp declare reduction(farther : MoveMax : omp_out = farther(omp_out, omp_in)) \
    initializer(omp_priv = MoveMax{-1.0, 0xffffffffu})

template <bool damped>
DriftResult kick_drift_impl(const StepContext& step, ParticleStore& particles, const NeighbourList& list,
                            const Params& params, bool parallel) {
  HotParticles& p = particles.hot;
  ColdParticles& cold = particles.cold;
  const std::uint32_t n = static_cast<std::uint32_t>(p.x.size());
  const double dt = step.dt, half = step.half_dt, damping = params.damping;
  const bool rigid = params.glue_mode == GlueMode::rigid;
  double max_d2 = 0.0;
  MoveMax mover{-1.0, 0xffffffffu};
#pragma omp parallel for schedule(static) reduction(max : max_d2) reduction(farther : mover) if (parallel)
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint8_t plate = p.plate[a];
    if (rigid && plate != plate_none) {
      p.x[a] = cold.ax[a];
      p.y[a] = cold.ay[a] + step.plate_u[plate];
      p.z[a] = cold.az[a];
      p.vx[a] = 0.0;
      p.vy[a] = step.plate_v[plate];
      p.vz[a] = 0.0;
    } else {
      half_kick<damped>(p.vx[a], p.vy[a], p.vz[a], p.fx[a], p.fy[a], p.fz[a], half, p.inv_mass[a],
                        cold.mass[a], damping, cold.damped[a]);
      p.x[a] += dt * p.vx[a];
      p.y[a] += dt * p.vy[a];
      p.z[a] += dt * p.vz[a];
      const double v2 = p.vx[a] * p.vx[a] + p.vy[a] * p.vy[a] + p.vz[a] * p.vz[a];
      double move2 = dt * dt * v2 / (p.radius[a] * p.radius[a]);
      if (!(move2 <= std::numeric_limits<double>::max())) move2 = std::numeric_limits<double>::infinity();
      mover = farther(mover, MoveMax{move2, a});
    }
    const double dx = p.x[a] - list.xb[a], dy = p.y[a] - list.yb[a], dz = p.z[a] - list.zb[a];
    max_d2 = std::max(max_d2, dx * dx + dy * dy + dz * dz);
  }
  return {max_d2, std::max(mover.move2, 0.0), mover.index == 0xffffffffu ? 0u : mover.index};
}

}  // namespace

DriftResult kick_drift(const StepContext& step, ParticleStore& particles, const NeighbourList& neighbours,
                       const Params& params, bool parallel) {
  return params.damping > 0.0 ? kick_drift_impl<true>(step, particles, neighbours, params, parallel)
                              : kick_drift_impl<false>(step, particles, neighbours, params, parallel);
}

}  // namespace rupture::dem
