// dem/system: the DEM engine as one object. Composes the particle store, the bond store, the contact
// neighbour list, the break ledger and the energy ledger, and runs one velocity-Verlet step as named
// stages over a StepContext: kick and drift (dem/integrator), a neighbour-list build when particles
// moved far enough (dem/neighbours), the force pass with the second half-kick (dem/forces), the
// plates' forces and work (dem/energy), the breaks the pass found (dem/breaks).
// Owns: the stage order, the step counter and clock, the stability bound, the state's public views
// and checkpoints. Not: how plates move over time, stop rules, recording or files (loading/).
//
// Units: mm, N, s, tonne (so energy is mJ); density is given in g/mm^3 as users write it.
// Determinism: every particle sums its own forces in a fixed order (each bond and contact is
// evaluated from both ends), breaks are flagged in the parallel pass and applied serially in bond
// order, and every reduction is a serial sum of per-particle values, so results are bit-identical
// for any thread count.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "dem/bonds.hpp"
#include "dem/breaks.hpp"
#include "dem/energy.hpp"
#include "dem/engine_state.hpp"
#include "dem/integrator.hpp"
#include "dem/neighbours.hpp"
#include "dem/params.hpp"
#include "dem/particles.hpp"
#include "dem/physics.hpp"
#include "sample/sample.hpp"

namespace rupture::dem {

// The farthest any particle moved in the last step, relative to its own radius (1); a non-finite
// position or velocity counts as an infinite move. Ties go to the lower storage index.
struct StepMove {
  double fraction = 0.0;         // |dt v| / r (1)
  std::size_t sample_index = 0;  // the particle
};

class System {
 public:
  System(const Sample& sample, const Params& params);

  // --- stability (see StabilityBound) ---
  double critical_dt() const { return stability_.critical_dt; }
  double stiffest_spring_sum() const { return stability_.stiffest_spring_sum; }
  double stiffest_mass() const { return stability_.stiffest_mass; }

  // --- stepping ---
  // One velocity-Verlet step of length dt (s) to a state where the top plate has `top`. With
  // `measure_energies`, its force pass also sums the energies of the state it ends in, so that
  // energies() right after the step costs nothing (the same bits either way).
  void step(double dt, const PlateMotion& top, bool measure_energies = false);

  // --- state ---
  std::size_t size() const { return particles_.size(); }
  std::size_t bond_count() const { return bonds_.size(); }
  std::size_t intact_bonds() const { return bonds_.intact_count; }
  std::uint64_t steps_done() const { return step_; }
  double time() const { return time_; }
  const Params& params() const { return params_; }

  Energies energies() const;  // a sum over the particles, unless the last step measured them
  // Whether the last step measured the energies of the current state (it was asked to, and the
  // state was not changed since), so that energies() costs nothing.
  bool energies_measured() const { return measured_.has_value(); }
  double plate_work() const { return ledger_.plate_work; }     // mJ done by the plates
  double released_energy() const { return ledger_.released; }  // mJ taken out by broken bonds
  double damping_energy() const { return ledger_.damped; }     // mJ removed by viscous damping
  // Force the top plate exerts on the sample (N, +y pulls), and the bottom plate's pull (N, -y
  // pulls, reported positive in tension).
  double force_top() const { return ledger_.plate_force[plate_top]; }
  double force_bottom() const { return -ledger_.plate_force[plate_bottom]; }
  const PlateMotion& top_plate() const { return top_; }
  // Initial distance between the mean y of the top and bottom glued layers (mm).
  double initial_plate_separation() const { return particles_.plate_separation0; }

  // Breaks applied since the last call, in bond order per step; the caller drains them.
  std::vector<BreakEvent>& break_events() { return breaks_.events; }

  // Particle data in sample order (for outputs), and bond extension r - r0 (mm, NaN when broken).
  Vec3 position(std::size_t sample_index) const;
  Vec3 velocity(std::size_t sample_index) const;
  Vec3 force(std::size_t sample_index) const;  // N: the net force of the last force pass
  // Initial condition (before the first step): velocity of one particle (mm/s).
  void set_velocity(std::size_t sample_index, const Vec3& v);
  // Breaks one intact bond now, exactly as a break found in a force pass (logged, energy released).
  void break_bond(std::size_t bond);
  // Checkpoints: the evolving state, and its restoration into an engine built from the same
  // sample and Params. restore_state checks every size, index and invariant first and throws
  // InputError (naming `source` and the field) without changing the engine if one fails.
  EngineState save_state() const;
  void restore_state(const EngineState& state, const std::string& source);

  // The largest move of the last step relative to the particle's radius: the run stops as
  // unstable when a particle jumps a sizeable part of itself in one step.
  const StepMove& last_step_move() const { return last_move_; }
  // Radius (mm) and mass (t) of a particle, by sample index.
  double radius(std::size_t sample_index) const {
    return particles_.hot.radius[particles_.storage_of_sample[sample_index]];
  }
  double mass(std::size_t sample_index) const {
    return particles_.cold.mass[particles_.storage_of_sample[sample_index]];
  }

  // FNV-1a hash of positions and velocities in sample order: equal states, equal hashes.
  std::uint64_t state_hash() const;
  double bond_extension(std::size_t bond) const;
  bool bond_intact(std::size_t bond) const { return bonds_.intact[bond] != 0; }
  std::size_t sample_index_of_largest_speed() const;

  // Calls f(a, b) (storage indices) for every intact bond and every overlapping unbonded pair
  // with a < b: the connectivity of the sample.
  template <class PairFn>
  void for_each_connection(PairFn&& f) const;
  std::uint8_t plate_of_storage(std::size_t a) const { return particles_.hot.plate[a]; }

  const StageTimes& stage_times() const { return times_; }
  std::size_t neighbour_rebuilds() const { return neighbours_.builds; }
  // Bytes of the state save_state() returns (the bulk of a checkpoint).
  std::size_t state_bytes() const;
  // Bytes held by the engine's arrays (capacity), for memory reports.
  std::size_t memory_bytes() const;

 private:
  // A force pass at the current configuration without a kick, its plate forces and breaks.
  void refresh_forces();
  void rebuild_neighbours();

  Params params_;
  ParticleStore particles_;
  BondStore bonds_;
  NeighbourList neighbours_;
  BreakLedger breaks_;
  std::vector<DriftShare> drift_shares_;  // one per thread of the step's parallel region
  EnergyLedger ledger_;
  StabilityBound stability_;
  PlateMotion top_;
  double time_ = 0.0;
  std::uint64_t step_ = 0;
  bool forces_stale_ = false;  // bonds were broken by hand since the last force pass
  // Small systems run on one thread: a parallel region costs more than their whole step.
  bool parallel_ = false;
  double widest_skin_;  // mm: how far the neighbour list's skin may widen (Params::skin is the narrowest)
  StageTimes times_;
  StepMove last_move_;
  EnergyParts energy_parts_;          // filled by a step asked to measure energies
  std::optional<Energies> measured_;  // the energies of the current state, where that step found them
};

template <class PairFn>
void System::for_each_connection(PairFn&& f) const {
  for (std::size_t b = 0; b < bonds_.size(); ++b)
    if (bonds_.intact[b]) f(bonds_.i[b], bonds_.j[b]);
  const HotParticles& p = particles_.hot;
  for (std::uint32_t a = 0; a < p.x.size(); ++a) {
    for (std::uint32_t q = neighbours_.start[a]; q < neighbours_.start[a] + neighbours_.count[a]; ++q) {
      const std::uint32_t b = neighbours_.list[q];
      if (b <= a) continue;
      const double dx = p.x[b] - p.x[a], dy = p.y[b] - p.y[a], dz = p.z[b] - p.z[a];
      const double touch = p.radius[a] + p.radius[b];
      if (dx * dx + dy * dy + dz * dz < touch * touch) f(a, b);
    }
  }
}

}  // namespace rupture::dem
