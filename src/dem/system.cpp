#include "dem/system.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/hash.hpp"
#include "dem/forces.hpp"
#include "dem/integrator.hpp"
#include "dem/step_context.hpp"

namespace rupture::dem {

namespace {

using Clock = std::chrono::steady_clock;

// Adds the seconds `stage` takes to `total`.
template <class Stage>
auto timed(double& total, Stage&& stage) {
  const auto start = Clock::now();
  if constexpr (std::is_void_v<decltype(stage())>) {
    stage();
    total += std::chrono::duration<double>(Clock::now() - start).count();
  } else {
    auto result = stage();
    total += std::chrono::duration<double>(Clock::now() - start).count();
    return result;
  }
}

const Params& validated(const Sample& sample, const Params& p) {
  const std::size_t n = sample.size();
  if (sample.radius.size() != n || sample.group.size() != n || sample.id.size() != n)
    throw InputError("sample", "particle arrays differ in length", "regenerate or re-export the sample");
  if (!(p.bond_stiffness > 0.0))
    throw InputError("bonds.stiffness", "must be > 0 (N/mm)", "give a positive k_n");
  if (!(p.break_distance > 0.0))
    throw InputError("bonds.break_distance", "must be > 0", "give a positive b_d");
  if (!(p.density > 0.0))
    throw InputError("sample.density", "must be > 0 (g/mm^3)", "give a positive density");
  return p;
}

// Gershgorin bound of the mass-weighted stiffness matrix: for particle a,
// lambda_a = sum_b k_ab (1/m_a + 1/sqrt(m_a m_b)) + k_glue/m_a.
StabilityBound stability_bound(const ParticleStore& particles, const BondStore& bonds, const Params& params) {
  const auto& inv_mass = particles.hot.inv_mass;
  const auto& mass = particles.cold.mass;
  StabilityBound bound;
  double lambda_max = 0.0;
  for (std::uint32_t a = 0; a < particles.size(); ++a) {
    double lambda = 0.0, spring_sum = 0.0;
    for (std::uint32_t l = bonds.link_start[a]; l < bonds.link_start[a + 1]; ++l) {
      const double k = bond_stiffness(params, bonds.link_r0[l]);
      lambda += k * (inv_mass[a] + 1.0 / std::sqrt(mass[a] * mass[bonds.link_other[l]]));
      spring_sum += k;
    }
    if (particles.hot.plate[a] != plate_none && params.glue_mode == GlueMode::spring) {
      lambda += params.glue_stiffness * inv_mass[a];
      spring_sum += params.glue_stiffness;
    }
    if (lambda > lambda_max) {
      lambda_max = lambda;
      bound.stiffest_spring_sum = spring_sum;
      bound.stiffest_mass = mass[a];
    }
  }
  bound.critical_dt =
      lambda_max > 0.0 ? 2.0 / std::sqrt(lambda_max) : std::numeric_limits<double>::infinity();
  return bound;
}

}  // namespace

System::System(const Sample& sample, const Params& params)
    : params_(validated(sample, params)),
      particles_(sample, params_),
      bonds_(sample, particles_.storage_of_sample),
      stability_(stability_bound(particles_, bonds_, params_)),
      parallel_(sample.size() >= 2048),
      widest_skin_(4.0 * params_.skin) {
  neighbours_.skin = params_.skin;
  energy_parts_.resize(size());  // a run asks for energies on its row steps: counted from the start
  rebuild_neighbours();
  refresh_forces();
}

void System::rebuild_neighbours() {
  timed(times_.neighbours,
        [&] { neighbours_.build(particles_.hot, bonds_, particles_.max_radius, parallel_); });
}

void System::refresh_forces() {
  const StepContext here = StepContext::at(0.0, 0.0, top_);
  timed(times_.forces,
        [&] { force_pass(here, particles_, bonds_, neighbours_, breaks_, params_, parallel_); });
  timed(times_.plates, [&] { ledger_.update_plate_forces(here, particles_, params_); });
  timed(times_.breaks,
        [&] { breaks_.apply(step_, 0.0, particles_, bonds_, neighbours_, params_, ledger_.released); });
}

void System::step(double dt, const PlateMotion& top, bool measure_energies) {
  measured_.reset();
  if (forces_stale_) {
    refresh_forces();
    forces_stale_ = false;
  }
  const double force_before = ledger_.plate_force[plate_top];
  const double u_before = top_.displacement;
  top_ = top;
  const StepContext step = StepContext::at(dt, 0.5 * dt, top);
  EnergyParts* const parts = measure_energies ? &energy_parts_ : nullptr;
  // Drift and force pass in one parallel region: on small samples the cost of opening a region is a
  // good part of each pass (docs/performance.md). When the drift leaves the neighbour list stale,
  // the threads leave before the pass, and it runs after the rebuild.
  drift_shares_.resize(std::size_t(omp_get_max_threads()));
  breaks_.prepare(omp_get_max_threads());
  DriftResult drift;
  bool list_kept = true;
  const auto start = Clock::now();
  auto drifted = start;
#pragma omp parallel if (parallel_)
  {
    const DriftResult moved = kick_drift(step, particles_, neighbours_, params_, drift_shares_);
    const bool keep = !neighbours_.stale(moved.largest_move, moved.second_move);
#pragma omp master
    {
      drift = moved;
      list_kept = keep;
      drifted = Clock::now();
    }
    if (keep) force_sweep(step, particles_, bonds_, neighbours_, breaks_, params_, parts);
  }
  times_.integrate += std::chrono::duration<double>(drifted - start).count();
  last_move_ = {std::sqrt(drift.move2), particles_.sample_of_storage[drift.mover]};
  time_ += dt;
  ++step_;
  if (list_kept) {
    times_.forces += std::chrono::duration<double>(Clock::now() - drifted).count();
  } else {
    neighbours_.adapt_skin(step_, params_.skin, widest_skin_);
    rebuild_neighbours();
    timed(times_.forces,
          [&] { force_pass(step, particles_, bonds_, neighbours_, breaks_, params_, parallel_, parts); });
  }
  timed(times_.plates, [&] { ledger_.update_plate_forces(step, particles_, params_); });
  const std::size_t events_before = breaks_.events.size();
  timed(times_.breaks, [&] {
    breaks_.apply(step_, step.half_dt, particles_, bonds_, neighbours_, params_, ledger_.released);
  });
  if (parts) {
    // A break changed its two particles' links and contact slices after the pass: their shares are
    // measured again, so that the total is what a fresh sum gives.
    for (std::size_t e = events_before; e < breaks_.events.size(); ++e)
      for (const std::uint32_t a : {bonds_.i[breaks_.events[e].bond], bonds_.j[breaks_.events[e].bond]})
        parts->measure(a, particles_, bonds_, neighbours_, top_, params_);
    measured_ = parts->total();
  }
  ledger_.add_plate_work(force_before, top_.displacement - u_before);
  if (params_.damping > 0.0) ledger_.sum_damping(particles_);
}

void System::break_bond(std::size_t bond) {
  if (!bonds_.intact[bond]) return;
  measured_.reset();
  breaks_.break_one(static_cast<std::uint32_t>(bond), step_, 0.0, particles_, bonds_, neighbours_, params_,
                    ledger_.released);
  forces_stale_ = true;
}

Energies System::energies() const {
  if (measured_) return *measured_;
  return measure_energies(particles_, bonds_, neighbours_, top_, params_, parallel_);
}

std::size_t System::state_bytes() const {
  const std::size_t n = size();
  return n * (13 * sizeof(double) + 3 * sizeof(std::uint32_t)) + (n + 1) * sizeof(std::uint32_t) +
         bonds_.intact.size() + (bonds_.link_bond.size() + neighbours_.list.size()) * sizeof(std::uint32_t);
}

std::size_t System::memory_bytes() const {
  return particles_.bytes() + bonds_.bytes() + neighbours_.bytes() + energy_parts_.bytes();
}

Vec3 System::position(std::size_t sample_index) const {
  const auto a = particles_.storage_of_sample[sample_index];
  return {particles_.hot.x[a], particles_.hot.y[a], particles_.hot.z[a]};
}

Vec3 System::velocity(std::size_t sample_index) const {
  const auto a = particles_.storage_of_sample[sample_index];
  return {particles_.hot.vx[a], particles_.hot.vy[a], particles_.hot.vz[a]};
}

Vec3 System::force(std::size_t sample_index) const {
  const auto a = particles_.storage_of_sample[sample_index];
  return {particles_.hot.fx[a], particles_.hot.fy[a], particles_.hot.fz[a]};
}

void System::set_velocity(std::size_t sample_index, const Vec3& v) {
  const auto a = particles_.storage_of_sample[sample_index];
  measured_.reset();
  particles_.hot.vx[a] = v.x;
  particles_.hot.vy[a] = v.y;
  particles_.hot.vz[a] = v.z;
}

double System::bond_extension(std::size_t bond) const {
  if (!bonds_.intact[bond]) return std::numeric_limits<double>::quiet_NaN();
  const auto i = bonds_.i[bond], j = bonds_.j[bond];
  const HotParticles& p = particles_.hot;
  const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i], dz = p.z[j] - p.z[i];
  return std::sqrt(dx * dx + dy * dy + dz * dz) - bonds_.r0[bond];
}

std::uint64_t System::state_hash() const {
  const HotParticles& p = particles_.hot;
  Fnv1a h;
  for (const std::uint32_t a : particles_.storage_of_sample)
    for (double v : {p.x[a], p.y[a], p.z[a], p.vx[a], p.vy[a], p.vz[a]}) h.add_value(v);
  return h.hash;
}

std::size_t System::sample_index_of_largest_speed() const {
  const HotParticles& p = particles_.hot;
  std::size_t best = 0;
  double best_v2 = -1.0;
  for (std::size_t a = 0; a < size(); ++a) {
    const double v2 = p.vx[a] * p.vx[a] + p.vy[a] * p.vy[a] + p.vz[a] * p.vz[a];
    if (!(v2 <= best_v2)) {  // NaN wins: it is the particle to report
      best = a;
      best_v2 = v2;
      if (std::isnan(v2)) break;
    }
  }
  return particles_.sample_of_storage[best];
}

}  // namespace rupture::dem
