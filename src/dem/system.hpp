// dem/system: the DEM engine. Owns the particle state (structure of arrays in space-filling-curve
// order), the bonds (flat list + per-particle CSR links), the contact neighbour list, one velocity
// Verlet step as named stages, bond breaking, and the energy ledger (plate work, released and damped
// energy). Not: how plates move over time, stop rules, recording or files (loading/).
//
// Units: mm, N, s, tonne (so energy is mJ); density is given in g/mm^3 as users write it.
// Determinism: every particle sums its own forces in a fixed order (each bond and contact is
// evaluated from both ends), breaks are flagged in the parallel pass and applied serially in bond
// order, and every reduction is a serial sum of per-particle values, so results are bit-identical
// for any thread count.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/vec3.hpp"
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
  double density = 2.5e-4;  // g/mm^3
  double damping = 0.0;     // 1/s: viscous damping rate, force -damping * m * v
  double skin = 0.05;       // mm: Verlet-list skin
};

// Which plate a particle is glued to; doubles as the index into per-plate arrays.
enum Plate : std::uint8_t { plate_none = 0, plate_bottom = 1, plate_top = 2 };

// The top plate's prescribed motion at one instant (the bottom plate is fixed).
struct PlateMotion {
  double displacement = 0.0;  // mm, along +y from the start
  double velocity = 0.0;      // mm/s
  double acceleration = 0.0;  // mm/s^2
};

struct BreakEvent {
  std::uint64_t step = 0;      // the step whose configuration broke it
  std::uint32_t bond = 0;      // index into Sample::bonds
  std::uint32_t i = 0, j = 0;  // sample indices of the two particles (i < j as in the sample)
  Vec3 midpoint;               // mm
  double rest_length = 0.0;    // mm
  double stretch = 0.0;        // mm: r - r0 when it broke
  double energy = 0.0;         // mJ released: k/2 s^2 half a step before (see apply_breaks)
};

// Energies of the current state (mJ) and the contact count.
struct Energies {
  double elastic = 0.0;  // intact bonds
  double kinetic = 0.0;
  double contact = 0.0;
  double glue = 0.0;
  std::uint64_t contacts = 0;  // overlapping unbonded pairs
};

// Seconds spent in each stage since construction (for profiles and `rupture bench`).
struct StageTimes {
  double neighbours = 0.0, integrate = 0.0, forces = 0.0, plates = 0.0, breaks = 0.0;
};

// The farthest any particle moved in the last step, relative to its own radius (1); a non-finite
// position or velocity counts as an infinite move. Ties go to the lower storage index.
struct StepMove {
  double fraction = 0.0;          // |dt v| / r (1)
  std::size_t sample_index = 0;  // the particle
};

// Everything that changes while the engine steps, in storage order: with the same sample and
// Params it fixes every later step bit for bit. That includes what only fixes the order of
// floating-point sums: each particle's link order (breaks permute it), the neighbour list with its
// slice capacities, and the positions the list was built at (they decide the next rebuild).
// Constants (masses, anchors, bond constants, storage order) are rebuilt from the sample.
struct EngineState {
  std::uint64_t step = 0;
  double time = 0.0;  // s
  PlateMotion top;
  std::array<double, 3> plate_force{};  // N, per Plate
  double plate_work = 0.0, released = 0.0, damped = 0.0;  // mJ
  std::uint64_t neighbour_rebuilds = 0;
  bool forces_stale = false;
  StageTimes stage_times;                        // s, carried over so reports cover the whole run
  std::vector<std::uint32_t> sample_of_storage;  // the storage order it was saved in (checked)
  std::vector<double> x, y, z;                   // mm
  std::vector<double> vx, vy, vz;                // mm/s
  std::vector<double> fx, fy, fz;                // N: velocity Verlet's first half-kick needs them
  std::vector<double> xb, yb, zb;                // mm: positions at the last neighbour-list build
  std::vector<double> damped_per_particle;       // mJ
  std::vector<std::uint8_t> intact;              // per bond: 1 intact, 0 broken
  std::vector<std::uint32_t> link_count;         // per particle: intact links at the slice start
  std::vector<std::uint32_t> link_bond;          // per link slot: its bond (slot order = sum order)
  std::vector<std::uint32_t> nb_start;           // n + 1: neighbour slice starts (capacities)
  std::vector<std::uint32_t> nb_count;           // per particle: used part of its slice
  std::vector<std::uint32_t> nb;                 // neighbour slices, unused slots zero
};

class System {
 public:
  System(const Sample& sample, const Params& params);

  // --- stability ---
  // Largest stable dt (s) of velocity Verlet: 2 / sqrt(lambda), lambda a Gershgorin bound on the
  // largest eigenvalue of M^-1/2 K M^-1/2 over bonds and glue springs (exact for a free pair and an
  // infinite chain).
  double critical_dt() const { return critical_dt_; }
  // Where that bound is reached: the stiffest particle's spring sum (N/mm) and mass (t).
  double stiffest_spring_sum() const { return stiffest_spring_sum_; }
  double stiffest_mass() const { return stiffest_mass_; }

  // --- stepping ---
  // One velocity-Verlet step of length dt (s) to a state where the top plate has `top`.
  void step(double dt, const PlateMotion& top);

  // --- state ---
  std::size_t size() const { return x_.size(); }
  std::size_t bond_count() const { return bond_i_.size(); }
  std::size_t intact_bonds() const { return intact_count_; }
  std::uint64_t steps_done() const { return step_; }
  double time() const { return time_; }
  const Params& params() const { return params_; }

  Energies energies() const;
  double plate_work() const { return plate_work_; }     // mJ done by the plates
  double released_energy() const { return released_; }  // mJ taken out by broken bonds
  double damping_energy() const { return damped_; }     // mJ removed by viscous damping
  // Force the top plate exerts on the sample (N, +y pulls), and the bottom plate's pull (N, -y
  // pulls, reported positive in tension).
  double force_top() const { return plate_force_[plate_top]; }
  double force_bottom() const { return -plate_force_[plate_bottom]; }
  const PlateMotion& top_plate() const { return top_; }
  // Initial distance between the mean y of the top and bottom glued layers (mm).
  double initial_plate_separation() const { return plate_separation0_; }

  // Breaks applied since the last call, in bond order per step; the caller drains them.
  std::vector<BreakEvent>& break_events() { return events_; }

  // Particle data in sample order (for outputs), and bond extension r - r0 (mm, NaN when broken).
  Vec3 position(std::size_t sample_index) const;
  Vec3 velocity(std::size_t sample_index) const;
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
  double radius(std::size_t sample_index) const { return radius_[storage_of_sample_[sample_index]]; }
  double mass(std::size_t sample_index) const { return mass_[storage_of_sample_[sample_index]]; }

  // FNV-1a hash of positions and velocities in sample order: equal states, equal hashes.
  std::uint64_t state_hash() const;
  double bond_extension(std::size_t bond) const;
  bool bond_intact(std::size_t bond) const { return intact_[bond] != 0; }
  std::size_t sample_index_of_largest_speed() const;

  // Calls f(a, b) (storage indices) for every intact bond and every overlapping unbonded pair
  // with a < b, and g(a, plate) for every glued particle: the connectivity of the sample.
  template <class PairFn>
  void for_each_connection(PairFn&& f) const;
  std::uint8_t plate_of_storage(std::size_t a) const { return plate_[a]; }

  const StageTimes& stage_times() const { return times_; }
  std::size_t neighbour_rebuilds() const { return rebuilds_; }
  // Bytes of the state save_state() returns (the bulk of a checkpoint).
  std::size_t state_bytes() const;
  // Bytes held by the engine's arrays (capacity), for memory reports.
  std::size_t memory_bytes() const;

 private:
  void compute_forces(double half_dt);
  template <bool damped>
  void compute_forces_impl(double half_dt);
  struct DriftResult {
    double max_d2 = 0.0;  // mm^2: largest squared displacement since the last list build
    double move2 = 0.0;   // 1: largest (|dt v| / r)^2 of this step (inf when non-finite)
    std::uint32_t mover = 0;  // storage index reaching it
  };
  template <bool damped>
  DriftResult kick_drift(double dt);
  void rebuild_neighbours();
  void update_plate_forces();
  void apply_breaks();
  void break_one(std::uint32_t bond);
  bool bonded_intact(std::uint32_t a, std::uint32_t b) const;
  void set_link(std::uint32_t l, std::uint32_t a, std::uint32_t b);
  void add_neighbour(std::uint32_t a, std::uint32_t b);

  Params params_;
  // Hot per-particle state (storage order = Morton order of the initial positions).
  std::vector<double> x_, y_, z_, vx_, vy_, vz_, fx_, fy_, fz_, inv_mass_, radius_;
  // Cold per-particle data.
  std::vector<double> mass_, ax_, ay_, az_;  // t; anchor = initial position (mm)
  std::vector<std::uint8_t> plate_;
  std::vector<double> xb_, yb_, zb_;         // positions at the last neighbour-list build (mm)
  std::vector<double> damped_per_particle_;  // mJ
  std::vector<std::uint32_t> storage_of_sample_, sample_of_storage_;
  std::vector<std::uint32_t> glued_;  // storage indices of glued particles, ascending

  // Bonds in sample order (storage indices), and per-particle links (CSR): each bond seen from
  // both ends, as arrays the force loop reads with SIMD. A particle's intact links occupy
  // [link_start_[a], link_start_[a] + link_count_[a]); a break moves its link past the end, so
  // broken bonds cost nothing.
  std::vector<std::uint32_t> bond_i_, bond_j_;
  std::vector<double> bond_r0_, bond_k_;
  std::vector<std::uint8_t> intact_;
  std::vector<std::uint32_t> link_start_, link_count_;
  std::vector<std::uint32_t> link_other_, link_bond_;
  std::vector<double> link_r0_, link_k_, link_limit_;  // mm, N/mm, mm
  std::size_t intact_count_ = 0;

  // Contact neighbour list: per particle a slice [start, start + count) with room for the pairs
  // its intact bonds may release before the next rebuild.
  std::vector<std::uint32_t> nb_start_, nb_count_, nb_;
  std::vector<std::uint32_t> cell_start_, cell_particles_;
  std::size_t rebuilds_ = 0;
  double max_radius_ = 0.0;

  // Breaks flagged per thread in the force pass.
  std::vector<std::vector<std::uint32_t>> flagged_;
  std::vector<std::uint32_t> flagged_merged_;
  std::vector<BreakEvent> events_;

  PlateMotion top_;
  std::array<double, 3> plate_force_{};  // N, force of each plate on the sample along y
  double plate_work_ = 0.0, released_ = 0.0, damped_ = 0.0;
  double plate_separation0_ = 0.0;
  double critical_dt_ = 0.0, stiffest_spring_sum_ = 0.0, stiffest_mass_ = 0.0;
  double time_ = 0.0;
  std::uint64_t step_ = 0;
  bool forces_stale_ = false;
  double last_half_dt_ = 0.0;  // s: half the step whose breaks are being applied (0 outside a step)
  // Small systems run on one thread: a parallel region costs more than their whole step.
  bool parallel_ = false;
  StageTimes times_;
  StepMove last_move_;
};

template <class PairFn>
void System::for_each_connection(PairFn&& f) const {
  for (std::size_t b = 0; b < bond_i_.size(); ++b)
    if (intact_[b]) f(bond_i_[b], bond_j_[b]);
  for (std::uint32_t a = 0; a < x_.size(); ++a) {
    for (std::uint32_t n = nb_start_[a]; n < nb_start_[a] + nb_count_[a]; ++n) {
      const std::uint32_t b = nb_[n];
      if (b <= a) continue;
      const double dx = x_[b] - x_[a], dy = y_[b] - y_[a], dz = z_[b] - z_[a];
      const double touch = radius_[a] + radius_[b];
      if (dx * dx + dy * dy + dz * dz < touch * touch) f(a, b);
    }
  }
}

}  // namespace rupture::dem
