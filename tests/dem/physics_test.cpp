// dem/physics: the derived quantities every folder asks of dem/, against hand-computed values.
#include "dem/physics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/units.hpp"
#include "sample/lattice.hpp"

namespace rupture::dem {
namespace {

// Two glued particles and one bond between them at `angle` (radians) from the pull axis y.
Sample tilted_pair(double rest_length, double angle) {
  Sample s = make_chain(2, 0.5 * rest_length, 2.5e-4);
  s.position[0] = {0.0, 0.0, 0.0};
  s.position[1] = {rest_length * std::sin(angle), rest_length * std::cos(angle), 0.0};
  s.bonds[0].rest_length = rest_length;
  return s;
}

TEST(Physics, MassStiffnessAndLimitFollowTheModel) {
  Params p;
  EXPECT_DOUBLE_EQ(particle_mass(0.5, 2.5e-4), 2.5e-10 * 4.0 / 3.0 * units::pi * 0.125);
  p.bond_stiffness = 2e3;
  EXPECT_EQ(bond_stiffness(p, 0.8), 2e3);
  p.scale_stiffness = true;
  EXPECT_DOUBLE_EQ(bond_stiffness(p, 0.8), 2e3 * 0.8 / 4.0) << "ESyS: k = normalK r0 / 4";
  p.break_distance = 0.01;
  EXPECT_EQ(break_limit(p, 0.8), 0.01);
  p.break_rule = BreakRule::relative;
  EXPECT_DOUBLE_EQ(break_limit(p, 0.8), 0.008);
  EXPECT_EQ(nominal_break_strain(p, 0.8), 0.01);
  p.break_rule = BreakRule::absolute;
  EXPECT_DOUBLE_EQ(nominal_break_strain(p, 0.8), 0.0125);
}

TEST(Physics, FirstBreakOfABondAlongThePullIsItsLimitOverItsLength) {
  Params p;
  p.break_distance = 0.01;
  EXPECT_NEAR(first_break_strain(tilted_pair(1.0, 0.0), p), 0.01, 1e-12);
  p.break_rule = BreakRule::relative;
  p.break_distance = 0.02;
  EXPECT_NEAR(first_break_strain(tilted_pair(1.0, 0.0), p), 0.02, 1e-12);
}

TEST(Physics, FirstBreakOfATiltedBondSolvesTheAffineStretch) {
  // At 60 degrees from y: (r0 sin)^2 + ((1 + e) r0 cos)^2 = (r0 + b)^2.
  Params p;
  p.break_distance = 0.01;
  const double angle = units::pi / 3.0, r0 = 1.0;
  const double expected = std::sqrt(((r0 + 0.01) * (r0 + 0.01) - std::pow(r0 * std::sin(angle), 2)) /
                                    std::pow(r0 * std::cos(angle), 2)) -
                          1.0;
  EXPECT_NEAR(first_break_strain(tilted_pair(r0, angle), p), expected, 1e-12);
  EXPECT_NEAR(expected, 0.01 / std::pow(std::cos(angle), 2), 0.02 * expected) << "about b / (r0 cos^2)";
  Sample across = tilted_pair(r0, 0.0);
  across.position[1] = {r0, 0.0, 0.0};
  EXPECT_TRUE(std::isinf(first_break_strain(across, p))) << "a bond across the pull axis never breaks by it";
}

TEST(Physics, WaveSpeedOfAChainIsRestLengthTimesRootOfStiffnessOverMass) {
  const Sample chain = make_chain(5, 0.5, 2.5e-4);
  Params p;
  p.bond_stiffness = 1e3;
  EXPECT_NEAR(wave_speed(chain, p), 1.0 * std::sqrt(1e3 / particle_mass(0.5, 2.5e-4)), 1e-6);
}

}  // namespace
}  // namespace rupture::dem
