// Analytic checks of the engine on regular lattices: oscillation frequencies of a bond and a chain,
// the stability limit, the exact breaking point, the linear stiffness and stored energy of a block.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/units.hpp"
#include "dem/system.hpp"
#include "sample/lattice.hpp"

namespace rupture::dem {
namespace {

constexpr double k_n = 1e3;         // N/mm
constexpr double radius = 0.5;      // mm
constexpr double density = 2.5e-4;  // g/mm^3

double particle_mass() { return units::density_from_g_per_mm3(density) * units::sphere_volume(radius); }

Params rigid_params() {
  Params p;
  p.bond_stiffness = k_n;
  p.break_distance = 1e3;  // nothing breaks
  p.contact_stiffness = 0.0;
  p.glue_mode = GlueMode::rigid;
  p.density = density;
  return p;
}

// Period (s) of y(t) of one particle from its upward zero crossings (linear interpolation).
double measured_period(System& system, std::size_t particle, double dt, std::size_t steps) {
  const double y0 = system.position(particle).y;
  std::vector<double> crossings;
  double previous = 0.0;
  for (std::size_t s = 0; s < steps; ++s) {
    system.step(dt, {});
    const double y = system.position(particle).y - y0;
    if (previous < 0.0 && y >= 0.0) crossings.push_back(system.time() - dt * y / (y - previous));
    previous = y;
  }
  EXPECT_GE(crossings.size(), 3u);
  return (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

// Velocity Verlet oscillates at omega_h with sin(omega_h dt / 2) = omega dt / 2.
double verlet_period(double omega, double dt) {
  return 2.0 * units::pi / (2.0 / dt * std::asin(omega * dt / 2.0));
}

TEST(Analytic, SingleBondOscillatesAtSqrtKOverM) {
  Sample sample = make_chain(3, radius, density);
  sample.bonds.pop_back();  // particle 1 hangs on one bond from the fixed bottom particle
  System system(sample, rigid_params());
  const double omega = std::sqrt(k_n / particle_mass());
  const double dt = 0.02 * system.critical_dt();
  system.set_velocity(1, {0.0, 1.0, 0.0});
  const double period = measured_period(system, 1, dt, std::size_t(10.5 * 2.0 * units::pi / omega / dt));
  EXPECT_NEAR(period, verlet_period(omega, dt), 1e-4 * period);
  EXPECT_NEAR(period, 2.0 * units::pi / omega, 2e-3 * period);
}

TEST(Analytic, ChainLowestModeHasTheLatticeFrequency) {
  const std::uint32_t free_particles = 8;
  Sample sample = make_chain(free_particles + 2, radius, density);
  System system(sample, rigid_params());
  for (std::uint32_t i = 1; i <= free_particles; ++i)
    system.set_velocity(i, {0.0, std::sin(i * units::pi / (free_particles + 1)), 0.0});
  const double omega =
      2.0 * std::sqrt(k_n / particle_mass()) * std::sin(units::pi / (2.0 * (free_particles + 1)));
  const double dt = 0.02 * system.critical_dt();
  const double period =
      measured_period(system, free_particles / 2, dt, std::size_t(6.5 * 2.0 * units::pi / omega / dt));
  EXPECT_NEAR(period, verlet_period(omega, dt), 1e-3 * period);
}

// The automatic limit must be safe and not wildly pessimistic: a long chain (highest mode close to
// 2 sqrt(k/m)) stays bounded just below the limit and blows up 20 % above it.
TEST(Analytic, StabilityLimitSeparatesBoundedFromExplodingChain) {
  const auto max_speed_after = [](double dt_factor) {
    Sample sample = make_chain(60, radius, density);
    System system(sample, rigid_params());
    for (std::uint32_t i = 1; i + 1 < 60; ++i) system.set_velocity(i, {0.0, (i % 2 ? 1.0 : -1.0), 0.0});
    const double dt = dt_factor * system.critical_dt();
    for (int s = 0; s < 4000; ++s) system.step(dt, {});
    const Vec3 v = system.velocity(system.sample_index_of_largest_speed());
    return std::isfinite(v.y) ? std::abs(v.y) : 1e300;
  };
  EXPECT_LT(max_speed_after(0.98), 10.0) << "mm/s: bounded (started at 1 mm/s)";
  EXPECT_GT(max_speed_after(1.2), 1e6) << "mm/s: exploded";
}

// A chain pulled slowly breaks each bond the first step its stretch exceeds b_d, so the recorded
// stretch is above b_d by less than one step's increment; its energy is k s^2 / 2.
TEST(Analytic, BondBreaksAtRestLengthPlusBreakDistance) {
  Params p = rigid_params();
  p.break_distance = 1e-4;  // mm
  Sample sample = make_chain(2, radius, density);
  System system(sample, p);
  const double speed = 20.0, dt = 0.1 * system.critical_dt();  // mm/s, s
  std::vector<BreakEvent> events;
  for (int s = 1; s < 100000 && events.empty(); ++s) {
    system.step(dt, {speed * s * dt, speed, 0.0});
    events = system.break_events();
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_GT(events[0].stretch, p.break_distance);
  EXPECT_LE(events[0].stretch, p.break_distance + speed * dt * (1.0 + 1e-9));
  // Released: the bond energy half a step earlier (both ends rigid: stretch - speed dt / 2).
  const double s_mid = events[0].stretch - 0.5 * speed * dt;
  EXPECT_NEAR(events[0].energy, 0.5 * k_n * s_mid * s_mid, 1e-9 * events[0].energy);
  EXPECT_DOUBLE_EQ(events[0].rest_length, 2.0 * radius);
  EXPECT_EQ(system.intact_bonds(), 0u);
  EXPECT_DOUBLE_EQ(system.released_energy(), events[0].energy);
  EXPECT_EQ(system.force_top(), 0.0) << "nothing holds the top particle any more";
}

// Relative (ESyS) rule: the limit scales with the rest length, the stiffness with r0 / 4.
TEST(Analytic, RelativeRuleBreaksAtStrainTimesRestLength) {
  Params p = rigid_params();
  p.break_rule = BreakRule::relative;
  p.scale_stiffness = true;
  p.break_distance = 1e-4;  // strain
  Sample sample = make_chain(2, radius, density);
  System system(sample, p);
  const double r0 = 2.0 * radius, speed = 20.0, dt = 0.1 * system.critical_dt();
  std::vector<BreakEvent> events;
  for (int s = 1; s < 100000 && events.empty(); ++s) {
    system.step(dt, {speed * s * dt, speed, 0.0});
    events = system.break_events();
  }
  ASSERT_EQ(events.size(), 1u);
  EXPECT_GT(events[0].stretch, p.break_distance * r0);
  EXPECT_LE(events[0].stretch, p.break_distance * r0 + speed * dt * (1.0 + 1e-9));
  const double s_mid = events[0].stretch - 0.5 * speed * dt;
  EXPECT_NEAR(events[0].energy, 0.5 * (k_n * r0 / 4.0) * s_mid * s_mid, 1e-9 * events[0].energy);
}

struct BlockCase {
  GlueMode glue;
  double expected_stiffness_per_column_over_k;  // 1/(ny-1) rigid; 1/((ny-1) + 2 k/k_glue) springs
};

// A simple-cubic block with axial bonds pulled slowly: nx*nz parallel columns of ny-1 bonds (plus
// two glue springs each in spring mode). Before anything breaks F = K u and E = K u^2 / 2.
class BlockStiffness : public ::testing::TestWithParam<BlockCase> {};

TEST_P(BlockStiffness, MatchesParallelChains) {
  const std::uint32_t nx = 3, ny = 6, nz = 2;
  Params p = rigid_params();
  p.glue_mode = GetParam().glue;
  p.glue_stiffness = 10.0 * k_n;
  Sample sample = make_cubic_block(nx, ny, nz, radius, density);
  System system(sample, p);
  const double stiffness = nx * nz * k_n * GetParam().expected_stiffness_per_column_over_k;  // N/mm
  const double dt = 0.4 * system.critical_dt(), speed = 20.0;                                // s, mm/s
  const double ramp = 2000 * dt;
  for (int s = 1; s <= 20000; ++s) {
    const double t = s * dt;
    // Smooth start (same law as loading::SpeedRamp) so that no wave is launched.
    const double w = units::pi / ramp;
    const PlateMotion top =
        t < ramp ? PlateMotion{0.5 * speed * (t - std::sin(w * t) / w), 0.5 * speed * (1 - std::cos(w * t)),
                               0.5 * speed * w * std::sin(w * t)}
                 : PlateMotion{speed * (t - 0.5 * ramp), speed, 0.0};
    system.step(dt, top);
  }
  const double u = system.top_plate().displacement;
  EXPECT_NEAR(system.force_top(), stiffness * u, 5e-3 * stiffness * u);
  EXPECT_NEAR(system.force_bottom(), stiffness * u, 5e-3 * stiffness * u);
  const Energies e = system.energies();
  EXPECT_NEAR(e.elastic + e.glue, 0.5 * stiffness * u * u, 1e-2 * 0.5 * stiffness * u * u);
  EXPECT_EQ(system.intact_bonds(), system.bond_count());
  EXPECT_NEAR(system.plate_work(), e.elastic + e.glue + e.kinetic, 1e-3 * system.plate_work());
}

INSTANTIATE_TEST_SUITE_P(GlueModes, BlockStiffness,
                         ::testing::Values(BlockCase{GlueMode::rigid, 1.0 / 5.0},
                                           BlockCase{GlueMode::spring, 1.0 / (5.0 + 2.0 / 10.0)}));

}  // namespace
}  // namespace rupture::dem
