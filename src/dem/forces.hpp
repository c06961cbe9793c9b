// dem/forces: the force pass, the step's hot loop. Each particle gathers its bond, contact and glue
// forces in a fixed order through the laws of dem/force_laws, flags its bonds past their limit
// (a bond over its limit gives no force in the pass that finds it: it breaks at this configuration)
// and finishes its second half-kick, so the particles are swept once; asked, it also fills each
// particle's share of the energies of the state it sees (dem/energy's EnergyParts).
// Owns: the loop. Not: the laws (dem/force_laws) or applying the breaks (dem/breaks).
#pragma once

#include "dem/bonds.hpp"
#include "dem/breaks.hpp"
#include "dem/energy.hpp"
#include "dem/neighbours.hpp"
#include "dem/particles.hpp"
#include "dem/step_context.hpp"

namespace rupture::dem {

// The pass in a parallel region of its own. With `energies` (sized to the particles), it also
// measures them.
void force_pass(const StepContext& step, ParticleStore& particles, const BondStore& bonds,
                const NeighbourList& neighbours, BreakLedger& breaks, const Params& params, bool parallel,
                EnergyParts* energies = nullptr);
// The pass's loop, called by every thread of the caller's parallel region (the step's, dem/system),
// after breaks.prepare(omp_get_max_threads()). It ends without a barrier: the caller ends its region
// with it (whose join waits) or waits itself before anything reads the forces, velocities or flags.
void force_sweep(const StepContext& step, ParticleStore& particles, const BondStore& bonds,
                 const NeighbourList& neighbours, BreakLedger& breaks, const Params& params,
                 EnergyParts* energies = nullptr);

}  // namespace rupture::dem
