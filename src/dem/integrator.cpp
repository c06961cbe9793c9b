#include "dem/integrator.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace rupture::dem {

namespace {

// The two largest squared displacements since the list build, and the farthest mover of the step
// (larger (|dt v| / r)^2 wins, ties go to the lower storage index): maxima, so the merge of the
// threads' shares is the same for any split of the loop.
void add_move(DriftShare& share, double d2) {
  if (d2 > share.first) {
    share.second = share.first;
    share.first = d2;
  } else if (d2 > share.second) {
    share.second = d2;
  }
}
void add_mover(DriftShare& share, double move2, std::uint32_t index) {
  if (move2 > share.move2 || (move2 == share.move2 && index < share.mover)) {
    share.move2 = move2;
    share.mover = index;
  }
}

template <bool damped>
DriftShare kick_drift_share(const StepContext& step, ParticleStore& particles, const NeighbourList& list,
                            const Params& params, std::uint32_t begin, std::uint32_t end) {
  HotParticles& p = particles.hot;
  ColdParticles& cold = particles.cold;
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
  DriftShare share;
  for (std::uint32_t a = begin; a < end; ++a) {
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
      add_mover(share, move2, a);
    }
    x[a] = px;
    y[a] = py;
    z[a] = pz;
    const double dx = px - xb[a], dy = py - yb[a], dz = pz - zb[a];
    const double d2 = dx * dx + dy * dy + dz * dz;
    // A non-finite position counts as an infinite move (the list must be rebuilt; the step's
    // stability check then reports the state).
    add_move(share, d2 <= std::numeric_limits<double>::max() ? d2 : std::numeric_limits<double>::infinity());
  }
  return share;
}

}  // namespace

DriftResult kick_drift(const StepContext& step, ParticleStore& particles, const NeighbourList& neighbours,
                       const Params& params, std::vector<DriftShare>& shares) {
  const auto n = static_cast<std::uint64_t>(particles.hot.x.size());
  const auto thread = static_cast<std::uint64_t>(omp_get_thread_num()),
             threads = static_cast<std::uint64_t>(omp_get_num_threads());
  const auto begin = static_cast<std::uint32_t>(n * thread / threads),
             end = static_cast<std::uint32_t>(n * (thread + 1) / threads);
  shares[thread] = params.damping > 0.0
                       ? kick_drift_share<true>(step, particles, neighbours, params, begin, end)
                       : kick_drift_share<false>(step, particles, neighbours, params, begin, end);
#pragma omp barrier
  DriftShare all;
  for (std::uint64_t t = 0; t < threads; ++t) {
    add_move(all, shares[t].first);
    add_move(all, shares[t].second);
    add_mover(all, shares[t].move2, shares[t].mover);
  }
  return {std::sqrt(all.first), std::sqrt(all.second), std::max(all.move2, 0.0),
          all.mover == 0xffffffffu ? 0u : all.mover};
}

}  // namespace rupture::dem
