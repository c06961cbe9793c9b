#include "dem/integrator.hpp"

#include <algorithm>
#include <cmath>
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
#pragma omp declare reduction(farther:MoveMax                       \
                              : omp_out = farther(omp_out, omp_in)) \
    initializer(omp_priv = MoveMax{-1.0, 0xffffffffu})

// The two largest squared displacements since the list build (a max: the same for any split).
struct TopTwo {
  double first = 0.0, second = 0.0;
  void add(double d2) {
    if (d2 > first) {
      second = first;
      first = d2;
    } else if (d2 > second) {
      second = d2;
    }
  }
};
inline TopTwo merged(TopTwo a, const TopTwo& b) {
  a.add(b.first);
  a.add(b.second);
  return a;
}
#pragma omp declare reduction(top_two:TopTwo \
                              : omp_out = merged(omp_out, omp_in)) initializer(omp_priv = TopTwo{})

template <bool damped>
DriftResult kick_drift_impl(const StepContext& step, ParticleStore& particles, const NeighbourList& list,
                            const Params& params, bool parallel) {
  HotParticles& p = particles.hot;
  ColdParticles& cold = particles.cold;
  const std::uint32_t n = static_cast<std::uint32_t>(p.x.size());
  const double dt = step.dt, half = step.half_dt, damping = params.damping;
  const bool rigid = params.glue_mode == GlueMode::rigid;
  TopTwo moved;
  MoveMax mover{-1.0, 0xffffffffu};
#pragma omp parallel for schedule(static) reduction(top_two : moved) reduction(farther : mover) if (parallel)
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
    const double d2 = dx * dx + dy * dy + dz * dz;
    // A non-finite position counts as an infinite move (the list must be rebuilt; the step's
    // stability check then reports the state).
    moved.add(d2 <= std::numeric_limits<double>::max() ? d2 : std::numeric_limits<double>::infinity());
  }
  return {std::sqrt(moved.first), std::sqrt(moved.second), std::max(mover.move2, 0.0),
          mover.index == 0xffffffffu ? 0u : mover.index};
}

}  // namespace

DriftResult kick_drift(const StepContext& step, ParticleStore& particles, const NeighbourList& neighbours,
                       const Params& params, bool parallel) {
  return params.damping > 0.0 ? kick_drift_impl<true>(step, particles, neighbours, params, parallel)
                              : kick_drift_impl<false>(step, particles, neighbours, params, parallel);
}

}  // namespace rupture::dem
