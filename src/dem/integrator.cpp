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
  // Unaliased views: through the vectors the compiler must assume that every store may change every
  // other array and reloads each value it has just written (a third of this pass's time).
  double* __restrict x = p.x.data();
  double* __restrict y = p.y.data();
  double* __restrict z = p.z.data();
  double* __restrict vx = p.vx.data();
  double* __restrict vy = p.vy.data();
  double* __restrict vz = p.vz.data();
  const double* __restrict fx = p.fx.data();
  const double* __restrict fy = p.fy.data();
  const double* __restrict fz = p.fz.data();
  const double* __restrict inv_mass = p.inv_mass.data();
  const double* __restrict radius = p.radius.data();
  const std::uint8_t* __restrict plate = p.plate.data();
  const double* __restrict mass = cold.mass.data();
  double* __restrict damped_energy = cold.damped.data();
  const double* __restrict xb = list.xb.data();
  const double* __restrict yb = list.yb.data();
  const double* __restrict zb = list.zb.data();
  TopTwo moved;
  MoveMax mover{-1.0, 0xffffffffu};
#pragma omp parallel for schedule(static) reduction(top_two : moved) reduction(farther : mover) if (parallel)
  for (std::uint32_t a = 0; a < n; ++a) {
    double px, py, pz;
    if (rigid && plate[a] != plate_none) {
      px = cold.ax[a];
      py = cold.ay[a] + step.plate_u[plate[a]];
      pz = cold.az[a];
      vx[a] = 0.0;
      vy[a] = step.plate_v[plate[a]];
      vz[a] = 0.0;
    } else {
      double ux = vx[a], uy = vy[a], uz = vz[a];
      half_kick<damped>(ux, uy, uz, fx[a], fy[a], fz[a], half, inv_mass[a], mass[a], damping,
                        damped_energy[a]);
      vx[a] = ux;
      vy[a] = uy;
      vz[a] = uz;
      px = x[a] + dt * ux;
      py = y[a] + dt * uy;
      pz = z[a] + dt * uz;
      const double v2 = ux * ux + uy * uy + uz * uz;
      double move2 = dt * dt * v2 / (radius[a] * radius[a]);
      if (!(move2 <= std::numeric_limits<double>::max())) move2 = std::numeric_limits<double>::infinity();
      mover = farther(mover, MoveMax{move2, a});
    }
    x[a] = px;
    y[a] = py;
    z[a] = pz;
    const double dx = px - xb[a], dy = py - yb[a], dz = pz - zb[a];
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
