// dem/breaks: the break ledger. The force pass flags bonds past their limit (per thread, from the
// lower-index end only, so each bond once); after the pass the flagged bonds break in bond order:
// the bond stops acting, its energy leaves the ledger as released energy, the pair becomes a contact
// candidate and a BreakEvent is logged for the caller to drain.
// Owns: flags, the break rule's bookkeeping and the events. Not: the limit test (dem/force_laws).
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.hpp"
#include "dem/bonds.hpp"
#include "dem/neighbours.hpp"
#include "dem/particles.hpp"

namespace rupture::dem {

struct BreakEvent {
  std::uint64_t step = 0;      // the step whose configuration broke it
  std::uint32_t bond = 0;      // index into Sample::bonds
  std::uint32_t i = 0, j = 0;  // sample indices of the two particles (i < j as in the sample)
  Vec3 midpoint;               // mm
  double rest_length = 0.0;    // mm
  double stretch = 0.0;        // mm: r - r0 when it broke
  double energy = 0.0;         // mJ released: k/2 s^2 half a step before (see BreakLedger::apply)
};

struct BreakLedger {
  // Room for one flag list per thread of the coming parallel pass.
  void prepare(int threads);
  // Breaks every flagged bond in bond order, adding each one's energy to `released` (mJ) in turn.
  // `half_dt` (s) is half the step whose force pass found them (0 outside a step).
  void apply(std::uint64_t step, double half_dt, const ParticleStore& particles, BondStore& bonds,
             NeighbourList& neighbours, const Params& params, double& released);
  // Breaks one intact bond now.
  void break_one(std::uint32_t bond, std::uint64_t step, double half_dt, const ParticleStore& particles,
                 BondStore& bonds, NeighbourList& neighbours, const Params& params, double& released);

  std::vector<std::vector<std::uint32_t>> flagged;  // per thread
  std::vector<BreakEvent> events;                   // since the caller last drained them

 private:
  std::vector<std::uint32_t> merged_;
};

}  // namespace rupture::dem
