// dem/energy: the energy ledger and the plates' forces. What went in (the plates' work, by the
// trapezoid rule on their force), what went out (released by breaks, removed by damping), and the
// energies stored in the current state; the balance of the two is the engine's correctness check.
// Owns: these sums and the plate force. Not: how plates move (loading/).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "dem/bonds.hpp"
#include "dem/neighbours.hpp"
#include "dem/particles.hpp"
#include "dem/step_context.hpp"

namespace rupture::dem {

// Energies of the current state (mJ) and the contact count.
struct Energies {
  double elastic = 0.0;  // intact bonds
  double kinetic = 0.0;
  double contact = 0.0;
  double glue = 0.0;
  std::uint64_t contacts = 0;  // overlapping unbonded pairs
};

// Each particle's share of the energies: its bonds and touching contacts to higher storage indices,
// its kinetic and glue energy (mJ), and its contacts. Filled by measure_energies, or by the force
// pass of a step asked to measure (dem/forces, with the same formulas in the same order), and
// summed serially in storage order, so the total is the same for any thread count.
struct EnergyParts {
  std::vector<std::array<double, 4>> per;  // mJ: elastic, kinetic, contact, glue
  std::vector<std::uint32_t> contacts;

  void resize(std::size_t particles) {
    per.resize(particles);
    contacts.resize(particles);
  }
  // Particle a's share in the current state, where the top plate is at `top`.
  void measure(std::uint32_t a, const ParticleStore& particles, const BondStore& bonds,
               const NeighbourList& neighbours, const PlateMotion& top, const Params& params);
  Energies total() const;
  std::size_t bytes() const {
    return per.capacity() * sizeof(per[0]) + contacts.capacity() * sizeof(contacts[0]);
  }
};

inline double kinetic_energy(double mass, double vx, double vy, double vz) {
  return 0.5 * mass * (vx * vx + vy * vy + vz * vz);
}

// Per-particle values summed serially in storage order: the same for any thread count.
Energies measure_energies(const ParticleStore& particles, const BondStore& bonds,
                          const NeighbourList& neighbours, const PlateMotion& top, const Params& params,
                          bool parallel);

struct EnergyLedger {
  // Force of each plate on the sample along y (N): the glue springs' pull, or in rigid mode what the
  // plate must supply so that its particles follow it (m a - internal force).
  void update_plate_forces(const StepContext& step, const ParticleStore& particles, const Params& params);
  // Adds the top plate's work over a step that moved it by `du` (mm) from a force `force_before` (N):
  // the trapezoid rule, consistent with the velocity-Verlet energy to O(dt^2).
  void add_plate_work(double force_before, double du);
  // Re-sums the damping energy from the per-particle tallies (serially: thread-count independent).
  void sum_damping(const ParticleStore& particles);

  std::array<double, 3> plate_force{};  // N, per Plate
  double plate_work = 0.0;              // mJ
  double released = 0.0;                // mJ, by broken bonds
  double damped = 0.0;                  // mJ, by viscous damping
};

}  // namespace rupture::dem
