// core/units: the one internal unit system and the conversions from the units users write.
// Internally: length mm, force N, time s, mass tonne (t), so energy is N*mm = mJ and
// stiffness N/mm. 1 N = 1 t*mm/s^2 holds exactly, so F = m*a needs no factor.
// Users write density in g/mm^3 (as the paper does); everything else is already internal.
#pragma once

namespace rupture::units {

inline constexpr double tonne_per_gram = 1e-6;

// g/mm^3 -> t/mm^3
constexpr double density_from_g_per_mm3(double rho_g_per_mm3) { return rho_g_per_mm3 * tonne_per_gram; }
// t -> g, for reporting masses
constexpr double mass_to_grams(double mass_t) { return mass_t / tonne_per_gram; }

inline constexpr double pi = 3.14159265358979323846;

// Volume of a sphere of radius r (mm^3).
constexpr double sphere_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

}  // namespace rupture::units
