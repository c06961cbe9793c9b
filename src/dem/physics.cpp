#include "dem/physics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/units.hpp"

namespace rupture::dem {

double particle_mass(double radius, double density_g_per_mm3) {
  return units::density_from_g_per_mm3(density_g_per_mm3) * units::sphere_volume(radius);
}

double mean_rest_length(const Sample& sample) {
  double sum = 0.0;
  for (const auto& bond : sample.bonds) sum += bond.rest_length;
  return sample.bonds.empty() ? 0.0 : sum / double(sample.bonds.size());
}

double mean_particle_mass(const Sample& sample, const Params& params) {
  double sum = 0.0;
  for (const double r : sample.radius) sum += particle_mass(r, params.density);
  return sum / double(std::max<std::size_t>(1, sample.size()));
}

double nominal_break_strain(const Params& params, double mean_rest_length) {
  return params.break_rule == BreakRule::absolute ? params.break_distance / mean_rest_length
                                                  : params.break_distance;
}

double first_break_strain(const Sample& sample, const Params& params) {
  double first = std::numeric_limits<double>::infinity();
  for (const auto& bond : sample.bonds) {
    const Vec3 d = sample.position[bond.j] - sample.position[bond.i];
    if (d.y == 0.0) continue;  // a bond across the pull axis is not stretched by it
    // Stretched by (1 + e) along y, the bond reaches r0 + limit when dx^2 + ((1 + e) dy)^2 + dz^2
    // equals (r0 + limit)^2.
    const double reach = bond.rest_length + break_limit(params, bond.rest_length);
    const double across = d.x * d.x + d.z * d.z;
    if (reach * reach <= across) return 0.0;  // already past its limit
    first = std::min(first, std::sqrt((reach * reach - across) / (d.y * d.y)) - 1.0);
  }
  return std::max(first, 0.0);
}

double wave_speed(const Sample& sample, const Params& params) {
  const double r0 = mean_rest_length(sample);
  return r0 * std::sqrt(bond_stiffness(params, r0) / mean_particle_mass(sample, params));
}

}  // namespace rupture::dem
