// fbm/power_law: closed forms of the equal-load-sharing bundle for p(x) = (1+α) x^α on [0, 1]
// (paper eqs. 16-23), per N κ = 1. They serve two purposes: the test oracle for the general
// numerical solver, and the FBM relations the analysis uses to read an exponent α off measured
// ratios (δ_x/x_p, A_r, Γ) and to predict x_c and E_max from (x_p, ℰ_max).
// Derivation: with P = x^(1+α), dF/dx = 0, dE_e/dx = 0 and dℰ/dx = 0 each reduce to
// x^(1+α) = constant, giving the three maxima below.
#pragma once

#include <cmath>

namespace rupture::fbm::power_law {

struct Maxima {
  double x_c, F_c, x_m, E_max, x_p, Erate_max, delta_x, Gamma, A_r, E_d_at_x_c;
};

// Valid for α > -1.
inline Maxima maxima(double alpha) {
  const double e = 1.0 / (1.0 + alpha);
  Maxima m{};
  m.x_c = std::pow(1.0 / (2.0 + alpha), e);                    // 1 - (2+α) x^(1+α) = 0
  m.x_m = std::pow(2.0 / (3.0 + alpha), e);                    // 2 - (3+α) x^(1+α) = 0
  m.x_p = std::pow(2.0 / ((2.0 + alpha) * (3.0 + alpha)), e);  // 2 - (2+α)(3+α) x^(1+α) = 0
  m.F_c = m.x_c * (1.0 + alpha) / (2.0 + alpha);
  m.E_max = 0.5 * m.x_m * m.x_m * (1.0 + alpha) / (3.0 + alpha);
  m.Erate_max = m.x_p * (1.0 + alpha) / (2.0 + alpha);
  m.delta_x = m.x_c - m.x_p;
  m.Gamma = (m.x_m - m.x_c) / m.delta_x;
  m.A_r = m.E_max / (m.x_p * m.Erate_max);
  m.E_d_at_x_c = 0.5 * (1.0 + alpha) / (3.0 + alpha) * std::pow(m.x_c, 3.0 + alpha);
  return m;
}

// x_c / x_p (eq. 16); δ_x / x_p = ratio - 1 (eq. 18).
inline double critical_to_precursor_ratio(double alpha) {
  return std::pow((3.0 + alpha) / 2.0, 1.0 / (1.0 + alpha));
}
// x_m / x_p (eq. 16).
inline double energy_max_to_precursor_ratio(double alpha) {
  return std::pow(2.0 + alpha, 1.0 / (1.0 + alpha));
}
// Γ (eq. 19).
inline double gamma(double alpha) {
  const double c = critical_to_precursor_ratio(alpha);
  return (energy_max_to_precursor_ratio(alpha) - c) / (c - 1.0);
}
// A_r (eq. 23).
inline double energy_ratio(double alpha) {
  return 0.5 * std::pow(2.0 + alpha, (3.0 + alpha) / (1.0 + alpha)) / (3.0 + alpha);
}

}  // namespace rupture::fbm::power_law
