#include "dem/forces.hpp"

#include <omp.h>

#include <cmath>

#include "dem/energy.hpp"
#include "dem/force_laws.hpp"
#include "dem/integrator.hpp"
#include "dem/physics.hpp"

namespace rupture::dem {

namespace {

// One function on purpose (~100 lines): the step's hot loop, with bonds, contacts, glue, the half-kick
// and, when asked, the energies in one sweep over the particles; split, the compiler no longer keeps
// the sums in registers across the parts. The energies use measure_energies' formulas in its order
// (dem/energy), so either gives the same bits.
template <bool damped, bool measure>
void force_sweep_impl(const StepContext& step, ParticleStore& particles, const BondStore& bonds,
                      const NeighbourList& neighbours, BreakLedger& breaks, const Params& params,
                      EnergyParts* energies) {
  HotParticles& p = particles.hot;
  ColdParticles& cold = particles.cold;
  const std::uint32_t n = static_cast<std::uint32_t>(p.x.size());
  const double kc = params.contact_stiffness;
  const GlueSpring glue{params.glue_mode == GlueMode::spring ? params.glue_stiffness : 0.0};
  const bool rigid = params.glue_mode == GlueMode::rigid;
  const double half_dt = step.half_dt, damping = params.damping;
  const double* __restrict x = p.x.data();
  const double* __restrict y = p.y.data();
  const double* __restrict z = p.z.data();
  const double* __restrict rad = p.radius.data();
  const std::uint32_t* __restrict link_other = bonds.link_other.data();
  const double* __restrict link_r0 = bonds.link_r0.data();
  const Params bond_params = params;  // a local copy: its fields stay in registers across the loop
  const std::uint32_t* __restrict link_start = bonds.link_start.data();
  const std::uint32_t* __restrict link_count = bonds.link_count.data();
  const std::uint32_t* __restrict nb_start = neighbours.start.data();
  const std::uint32_t* __restrict nb_count = neighbours.count.data();
  const std::uint32_t* __restrict nb = neighbours.list.data();
  {
    auto& flags = breaks.flagged[std::size_t(omp_get_thread_num())];
    // No barrier of its own: every caller ends its parallel region with this sweep, whose join waits.
#pragma omp for schedule(static) nowait
    for (std::uint32_t a = 0; a < n; ++a) {
      const double xa = x[a], ya = y[a], za = z[a];
      double fx = 0.0, fy = 0.0, fz = 0.0, elastic = 0.0, contact_energy = 0.0;
      std::uint32_t touching = 0;
      const std::uint32_t begin = link_start[a], end = begin + link_count[a];
      int over = 0;
      // Scalar on purpose: vectorised across a particle's ~10 links this loop is 1.8x slower
      // (docs/performance.md, "Tried and dropped"). A bond over its limit is flagged below.
      for (std::uint32_t l = begin; l < end; ++l) {
        const std::uint32_t j = link_other[l];
        const double dx = x[j] - xa, dy = y[j] - ya, dz = z[j] - za;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double r0 = link_r0[l];
        const BreakableBond bond{{bond_stiffness(bond_params, r0), r0}, break_limit(bond_params, r0)};
        const double c = bond.force_over_r(r);
        fx += c * dx;
        fy += c * dy;
        fz += c * dz;
        over |= int(!bond.holds(r));
        if constexpr (measure)
          if (j > a) elastic += bond.law.energy(r);
      }
      if (over) [[unlikely]] {
        for (std::uint32_t l = begin; l < end; ++l) {
          const std::uint32_t j = link_other[l];
          const double dx = x[j] - xa, dy = y[j] - ya, dz = z[j] - za;
          const double r0 = link_r0[l];
          const BreakableBond bond{{bond_stiffness(bond_params, r0), r0}, break_limit(bond_params, r0)};
          if (j > a && bond.breaks(std::sqrt(dx * dx + dy * dy + dz * dz)))
            flags.push_back(bonds.link_bond[l]);
        }
      }
      // Touching pairs only, in the slice's sorted order, so that the sum does not depend on which
      // candidates the list holds (its skin). Most candidates are apart: a squared-distance test
      // rejects them before the square root (its margin keeps every pair with r < touch).
      const double ra = rad[a];
      for (std::uint32_t q = nb_start[a]; q < nb_start[a] + nb_count[a]; ++q) {
        const std::uint32_t b = nb[q];
        const double dx = x[b] - xa, dy = y[b] - ya, dz = z[b] - za;
        const double r2 = dx * dx + dy * dy + dz * dz;
        const LinearContact contact{kc, ra + rad[b]};
        if (!(r2 < contact.touch * contact.touch * (1.0 + 1e-12))) continue;
        const double r = std::sqrt(r2);
        if (!contact.touching(r)) continue;
        const double c = contact.force_over_r(r);
        fx += c * dx;
        fy += c * dy;
        fz += c * dz;
        if constexpr (measure)
          if (b > a) {
            contact_energy += contact.energy(r);
            ++touching;
          }
      }
      const std::uint8_t plate = p.plate[a];
      double glue_energy = 0.0;
      if (plate != plate_none) {
        const double ox = xa - cold.ax[a], oy = ya - cold.ay[a] - step.plate_u[plate], oz = za - cold.az[a];
        fx += glue.force(ox);
        fy += glue.force(oy);
        fz += glue.force(oz);
        if constexpr (measure) glue_energy = glue.energy(ox, oy, oz);
      }
      p.fx[a] = fx;
      p.fy[a] = fy;
      p.fz[a] = fz;
      double vx = p.vx[a], vy = p.vy[a], vz = p.vz[a];
      if (plate == plate_none || !rigid) {  // rigid mode: the plate moves its particles (dem/integrator)
        half_kick<damped>(vx, vy, vz, fx, fy, fz, half_dt, p.inv_mass[a], cold.mass[a], damping,
                          cold.damped[a]);
        p.vx[a] = vx;
        p.vy[a] = vy;
        p.vz[a] = vz;
      }
      if constexpr (measure) {
        energies->per[a] = {elastic, kinetic_energy(cold.mass[a], vx, vy, vz), contact_energy, glue_energy};
        energies->contacts[a] = touching;
      }
    }
  }
}

}  // namespace

void force_sweep(const StepContext& step, ParticleStore& particles, const BondStore& bonds,
                 const NeighbourList& neighbours, BreakLedger& breaks, const Params& params,
                 EnergyParts* energies) {
  const bool damped = params.damping > 0.0;
  if (damped && energies)
    force_sweep_impl<true, true>(step, particles, bonds, neighbours, breaks, params, energies);
  else if (damped)
    force_sweep_impl<true, false>(step, particles, bonds, neighbours, breaks, params, nullptr);
  else if (energies)
    force_sweep_impl<false, true>(step, particles, bonds, neighbours, breaks, params, energies);
  else
    force_sweep_impl<false, false>(step, particles, bonds, neighbours, breaks, params, nullptr);
}

void force_pass(const StepContext& step, ParticleStore& particles, const BondStore& bonds,
                const NeighbourList& neighbours, BreakLedger& breaks, const Params& params, bool parallel,
                EnergyParts* energies) {
  breaks.prepare(omp_get_max_threads());
#pragma omp parallel if (parallel)
  force_sweep(step, particles, bonds, neighbours, breaks, params, energies);
}

}  // namespace rupture::dem
