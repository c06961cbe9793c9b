// Each force law alone: force = -dE/dr (central difference), signs, and no contact attraction.
#include "dem/force_laws.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rupture::dem {
namespace {

// The force on `self` is c d with d pointing to the other particle; its component along the
// direction in which r grows (-d/r) is -c r, which must equal -dE/dr.
template <class Law>
void expect_force_is_minus_energy_gradient(const Law& law, double r) {
  const double h = 1e-6 * r;
  const double dE_dr = (law.energy(r + h) - law.energy(r - h)) / (2.0 * h);
  EXPECT_NEAR(law.force_over_r(r) * r, dE_dr, 1e-6 * std::max(1.0, std::abs(dE_dr))) << "r = " << r;
}

TEST(ForceLaws, HookeBondForceIsMinusEnergyGradient) {
  const HookeBond bond{1e3, 0.8};
  for (double r : {0.5, 0.79, 0.8, 0.81, 1.3}) expect_force_is_minus_energy_gradient(bond, r);
  EXPECT_GT(bond.force_over_r(0.9), 0.0) << "a stretched bond pulls the pair together";
  EXPECT_LT(bond.force_over_r(0.7), 0.0) << "a compressed bond pushes the pair apart";
  EXPECT_DOUBLE_EQ(bond.energy(0.9), 0.5 * 1e3 * 0.01);
}

TEST(ForceLaws, LinearContactRepelsOnlyWhenOverlapping) {
  const LinearContact contact{2e3, 1.0};
  for (double r : {0.7, 0.95, 0.999}) expect_force_is_minus_energy_gradient(contact, r);
  EXPECT_LT(contact.force_over_r(0.9), 0.0);
  EXPECT_EQ(contact.force_over_r(1.0), 0.0);
  EXPECT_EQ(contact.force_over_r(1.2), 0.0) << "no attraction between separated particles";
  EXPECT_EQ(contact.energy(1.2), 0.0);
  EXPECT_DOUBLE_EQ(contact.energy(0.9), 0.5 * 2e3 * 0.01);
}

TEST(ForceLaws, GlueSpringForceIsMinusEnergyGradient) {
  const GlueSpring glue{5e4};
  const double dx = 0.01, dy = -0.02, dz = 0.003, h = 1e-7;
  const double dE_dy = (glue.energy(dx, dy + h, dz) - glue.energy(dx, dy - h, dz)) / (2.0 * h);
  EXPECT_NEAR(glue.force(dy), -dE_dy, 1e-6 * std::abs(dE_dy));
  EXPECT_DOUBLE_EQ(glue.force(0.0), 0.0);
}

TEST(ForceLaws, BreakableBondActsUpToItsLimitOnly) {
  const BreakableBond bond{{1e3, 0.8}, 0.01};
  EXPECT_TRUE(bond.holds(0.8099));
  EXPECT_FALSE(bond.breaks(0.8099));
  EXPECT_EQ(bond.force_over_r(0.805), bond.law.force_over_r(0.805)) << "the Hooke law while it holds";
  EXPECT_FALSE(bond.holds(0.8101));
  EXPECT_TRUE(bond.breaks(0.8101));
  EXPECT_EQ(bond.force_over_r(0.8101), 0.0) << "no force in the pass that finds it past its limit";
  const double nan = std::nan("");
  EXPECT_FALSE(bond.holds(nan));
  EXPECT_FALSE(bond.breaks(nan)) << "a non-finite state is the stability check's to report";
  EXPECT_EQ(bond.force_over_r(nan), 0.0);
}

}  // namespace
}  // namespace rupture::dem
