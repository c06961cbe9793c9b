#include "dem/energy.hpp"

#include <cmath>
#include <numeric>
#include <vector>

#include "dem/force_laws.hpp"
#include "dem/physics.hpp"

namespace rupture::dem {

void EnergyParts::measure(std::uint32_t a, const ParticleStore& particles, const BondStore& bonds,
                          const NeighbourList& neighbours, const PlateMotion& top, const Params& params) {
  const HotParticles& p = particles.hot;
  const ColdParticles& cold = particles.cold;
  double elastic = 0.0, contact = 0.0;
  std::uint32_t count = 0;
  for (std::uint32_t l = bonds.link_start[a]; l < bonds.link_start[a] + bonds.link_count[a]; ++l) {
    const std::uint32_t b = bonds.link_other[l];
    if (b < a) continue;
    const double dx = p.x[b] - p.x[a], dy = p.y[b] - p.y[a], dz = p.z[b] - p.z[a];
    const double r0 = bonds.link_r0[l];
    elastic += HookeBond{bond_stiffness(params, r0), r0}.energy(std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  for (std::uint32_t q = neighbours.start[a]; q < neighbours.start[a] + neighbours.count[a]; ++q) {
    const std::uint32_t b = neighbours.list[q];
    if (b < a) continue;
    const double dx = p.x[b] - p.x[a], dy = p.y[b] - p.y[a], dz = p.z[b] - p.z[a];
    const LinearContact law{params.contact_stiffness, p.radius[a] + p.radius[b]};
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (r < law.touch) {
      contact += law.energy(r);
      ++count;
    }
  }
  double glue_energy = 0.0;
  if (const std::uint8_t plate = p.plate[a]; plate != plate_none) {
    const GlueSpring glue{params.glue_mode == GlueMode::spring ? params.glue_stiffness : 0.0};
    const double plate_u = StepContext::at(0.0, 0.0, top).plate_u[plate];
    glue_energy = glue.energy(p.x[a] - cold.ax[a], p.y[a] - cold.ay[a] - plate_u, p.z[a] - cold.az[a]);
  }
  per[a] = {elastic, kinetic_energy(cold.mass[a], p.vx[a], p.vy[a], p.vz[a]), contact, glue_energy};
  contacts[a] = count;
}

Energies measure_energies(const ParticleStore& particles, const BondStore& bonds,
                          const NeighbourList& neighbours, const PlateMotion& top, const Params& params,
                          bool parallel) {
  const auto n = static_cast<std::uint32_t>(particles.size());
  EnergyParts parts;
  parts.resize(n);
#pragma omp parallel for schedule(static) if (parallel)
  for (std::uint32_t a = 0; a < n; ++a) parts.measure(a, particles, bonds, neighbours, top, params);
  return parts.total();
}

Energies EnergyParts::total() const {
  Energies e;
  for (std::size_t a = 0; a < per.size(); ++a) {
    e.elastic += per[a][0];
    e.kinetic += per[a][1];
    e.contact += per[a][2];
    e.glue += per[a][3];
    e.contacts += contacts[a];
  }
  return e;
}

void EnergyLedger::update_plate_forces(const StepContext& step, const ParticleStore& particles,
                                       const Params& params) {
  const HotParticles& p = particles.hot;
  std::array<double, 3> force{};
  for (const std::uint32_t a : particles.glued) {
    const std::uint8_t plate = p.plate[a];
    if (params.glue_mode == GlueMode::spring)
      force[plate] += params.glue_stiffness * (particles.cold.ay[a] + step.plate_u[plate] - p.y[a]);
    else
      force[plate] += particles.cold.mass[a] * step.plate_a[plate] - p.fy[a];
  }
  plate_force = force;
}

void EnergyLedger::add_plate_work(double force_before, double du) {
  plate_work += 0.5 * (force_before + plate_force[plate_top]) * du;
}

void EnergyLedger::sum_damping(const ParticleStore& particles) {
  damped = std::accumulate(particles.cold.damped.begin(), particles.cold.damped.end(), 0.0);
}

}  // namespace rupture::dem
