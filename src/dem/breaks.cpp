#include "dem/breaks.hpp"

#include <algorithm>
#include <cmath>

#include "dem/force_laws.hpp"
#include "dem/physics.hpp"

namespace rupture::dem {

void BreakLedger::prepare(int threads) {
  if (flagged.size() < std::size_t(threads)) flagged.resize(std::size_t(threads));
}

void BreakLedger::apply(std::uint64_t step, double half_dt, const ParticleStore& particles, BondStore& bonds,
                        NeighbourList& neighbours, const Params& params, double& released) {
  merged_.clear();
  for (auto& flags : flagged) {
    merged_.insert(merged_.end(), flags.begin(), flags.end());
    flags.clear();
  }
  std::sort(merged_.begin(), merged_.end());
  for (const std::uint32_t b : merged_)
    break_one(b, step, half_dt, particles, bonds, neighbours, params, released);
}

void BreakLedger::break_one(std::uint32_t b, std::uint64_t step, double half_dt,
                            const ParticleStore& particles, BondStore& bonds, NeighbourList& neighbours,
                            const Params& params, double& released) {
  const HotParticles& p = particles.hot;
  const std::uint32_t i = bonds.i[b], j = bonds.j[b];
  const double dx = p.x[j] - p.x[i], dy = p.y[j] - p.y[i], dz = p.z[j] - p.z[i];
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  const HookeBond bond{bond_stiffness(params, bonds.r0[b]), bonds.r0[b]};
  const LinearContact contact{params.contact_stiffness, p.radius[i] + p.radius[j]};
  // The bond acted in the previous kick and not in this one, so for the integrator it vanished half a
  // step ago: its energy there (r moved back by half a step of the pair's relative velocity) is what
  // leaves the ledger. Using the energy at r instead would leave an O(dt) gap.
  const double closing = ((p.vx[j] - p.vx[i]) * dx + (p.vy[j] - p.vy[i]) * dy + (p.vz[j] - p.vz[i]) * dz) / r;
  const double r_break = r - half_dt * closing;
  const double energy = bond.energy(r_break) - contact.energy(r);
  bonds.unlink(b);
  neighbours.add_pair(i, j);
  released += energy;
  const std::uint32_t si = particles.sample_of_storage[i], sj = particles.sample_of_storage[j];
  events.push_back({step,
                    b,
                    std::min(si, sj),
                    std::max(si, sj),
                    {0.5 * (p.x[i] + p.x[j]), 0.5 * (p.y[i] + p.y[j]), 0.5 * (p.z[i] + p.z[j])},
                    bonds.r0[b],
                    bond.stretch(r),
                    energy});
}

}  // namespace rupture::dem
