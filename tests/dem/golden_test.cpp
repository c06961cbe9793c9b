// The engine pinned bit for bit: short runs of the reduced tissue whose final state hash, plate
// work and released energy are written down here. A change that moves any of them changes the
// physics' floating-point path (summation order, a formula rewritten, a law changed); such a change
// must say so and re-pin these values with the reason in its commit. Each case also runs on one and
// two threads: the pinned value holds for both.
// Re-pinned once: contact forces summed over touching pairs in sorted order (skin-independent lists).
#include <gtest/gtest.h>
#include <omp.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "dem/system.hpp"
#include "loading/ramp.hpp"
#include "sample/presets.hpp"

namespace rupture::dem {
namespace {

struct Pinned {
  std::uint64_t state_hash;
  std::uint64_t plate_work_bits;
  std::uint64_t released_bits;
  std::size_t intact_bonds;
};

const Sample& small_tissue() {
  static const Sample sample = make_preset("tissue-small", 1);
  return sample;
}

// Pulls the reduced tissue `steps` steps at `speed` (mm/s, ramped over the first 200 steps).
Pinned pull(const Params& params, double speed, int steps, int threads) {
  omp_set_num_threads(threads);
  System system(small_tissue(), params);
  const double dt = 0.4 * system.critical_dt();
  const loading::SpeedRamp ramp{speed, 200 * dt};
  for (int s = 1; s <= steps; ++s) system.step(dt, ramp.at(double(s) * dt));
  return {system.state_hash(), std::bit_cast<std::uint64_t>(system.plate_work()),
          std::bit_cast<std::uint64_t>(system.released_energy()), system.intact_bonds()};
}

void expect_pinned(const Params& params, double speed, int steps, const Pinned& expected) {
  for (const int threads : {1, 2}) {
    const Pinned got = pull(params, speed, steps, threads);
    std::printf("pinned {0x%016llxull, 0x%016llxull, 0x%016llxull, %zu} on %d threads\n",
                static_cast<unsigned long long>(got.state_hash),
                static_cast<unsigned long long>(got.plate_work_bits),
                static_cast<unsigned long long>(got.released_bits), got.intact_bonds, threads);
    EXPECT_EQ(got.state_hash, expected.state_hash) << threads << " threads";
    EXPECT_EQ(got.plate_work_bits, expected.plate_work_bits) << threads << " threads";
    EXPECT_EQ(got.released_bits, expected.released_bits) << threads << " threads";
    EXPECT_EQ(got.intact_bonds, expected.intact_bonds) << threads << " threads";
  }
}

// Rigid glue, fast pull through the first breaks and into fragmentation (contacts, rebuilds, breaks).
TEST(Golden, RigidFastPullThroughFailure) {
  Params p;
  p.break_distance = 0.005;
  p.glue_mode = GlueMode::rigid;
  expect_pinned(p, 5000.0, 3000,
                {0x15d47815311ff9f2ull, 0x403b567081ad6ec2ull, 0x4030aeea7b52e97dull, 11392});
}

// Spring glue with viscous damping and ESyS's relative rule with scaled stiffness.
TEST(Golden, SpringGlueDampedRelativeRule) {
  Params p;
  p.bond_stiffness = 4e3;
  p.scale_stiffness = true;
  p.break_rule = BreakRule::relative;
  p.break_distance = 0.01;
  p.damping = 2e4;
  expect_pinned(p, 5000.0, 2500,
                {0x63c340065b1990ffull, 0x40521cac861658e5ull, 0x4041b2198c7a4ca3ull, 11236});
}

// The skin is a speed setting only: a narrow, the default and a wide one give the same state bit for
// bit, though the lists hold different candidates and are rebuilt at different steps.
TEST(Golden, StateDoesNotDependOnTheSkin) {
  Params p;
  p.break_distance = 0.005;
  p.glue_mode = GlueMode::rigid;
  const Pinned reference = pull(p, 5000.0, 3000, 2);
  for (const double skin : {0.01, 0.3}) {
    p.skin = skin;
    const Pinned got = pull(p, 5000.0, 3000, 2);
    EXPECT_EQ(got.state_hash, reference.state_hash) << "skin " << skin;
    EXPECT_EQ(got.released_bits, reference.released_bits) << "skin " << skin;
  }
}

// Energies measured by a step's force pass (and, after breaks, their particles' shares measured again)
// are the ones summed afresh, bit for bit, on steps with and without breaks, and asking for them does
// not change the state (rigid glue undamped, spring glue
// damped: the pass's two kinds of kick).
TEST(Golden, EnergiesMeasuredByTheStepAreTheSummedOnes) {
  Params rigid;
  rigid.break_distance = 0.005;
  rigid.glue_mode = GlueMode::rigid;
  Params damped = rigid;
  damped.glue_mode = GlueMode::spring;
  damped.damping = 2e4;
  omp_set_num_threads(2);
  for (const Params& p : {rigid, damped}) {
    System measuring(small_tissue(), p), summing(small_tissue(), p);
    const double dt = 0.4 * measuring.critical_dt();
    const loading::SpeedRamp ramp{5000.0, 200 * dt};
    int breaking_steps = 0;
    for (int s = 1; s <= 2000; ++s) {
      measuring.step(dt, ramp.at(double(s) * dt), true);
      summing.step(dt, ramp.at(double(s) * dt));
      const Energies a = measuring.energies(), b = summing.energies();
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.elastic), std::bit_cast<std::uint64_t>(b.elastic))
          << "step " << s;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.kinetic), std::bit_cast<std::uint64_t>(b.kinetic))
          << "step " << s;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.contact), std::bit_cast<std::uint64_t>(b.contact))
          << "step " << s;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(a.glue), std::bit_cast<std::uint64_t>(b.glue)) << "step " << s;
      ASSERT_EQ(a.contacts, b.contacts) << "step " << s;
      EXPECT_FALSE(summing.energies_measured());
      ASSERT_TRUE(measuring.energies_measured()) << "step " << s;
      breaking_steps += measuring.break_events().empty() ? 0 : 1;
      measuring.break_events().clear();
    }
    EXPECT_EQ(measuring.state_hash(), summing.state_hash());
    EXPECT_GT(measuring.bond_count() - measuring.intact_bonds(), 100u) << "the pull must reach failure";
    // A change of state between steps drops the measurement: energies() then sums the new state.
    const auto same_elastic = [&] {
      return std::bit_cast<std::uint64_t>(measuring.energies().elastic) ==
             std::bit_cast<std::uint64_t>(summing.energies().elastic);
    };
    std::size_t intact = 0;
    while (!measuring.bond_intact(intact)) ++intact;
    const EngineState before_break = measuring.save_state();
    for (System* system : {&measuring, &summing}) system->break_bond(intact);
    EXPECT_FALSE(measuring.energies_measured()) << "break_bond";
    EXPECT_TRUE(same_elastic()) << "break_bond";
    measuring.step(dt, ramp.at(2001.0 * dt), true);
    summing.step(dt, ramp.at(2001.0 * dt));
    for (System* system : {&measuring, &summing}) system->set_velocity(0, {1.0, 2.0, 3.0});
    EXPECT_FALSE(measuring.energies_measured()) << "set_velocity";
    EXPECT_EQ(std::bit_cast<std::uint64_t>(measuring.energies().kinetic),
              std::bit_cast<std::uint64_t>(summing.energies().kinetic));
    measuring.step(dt, ramp.at(2002.0 * dt), true);
    for (System* system : {&measuring, &summing}) system->restore_state(before_break, "test");
    EXPECT_FALSE(measuring.energies_measured()) << "restore_state";
    EXPECT_TRUE(same_elastic()) << "restore_state";
    EXPECT_GT(breaking_steps, 100) << "steps with breaks re-measure the broken bonds' particles";
  }
}

// Same state, bit for bit, for 1, 2 and 3 threads (another seed and break distance than above).
TEST(Determinism, StateHashIsIndependentOfThreadCount) {
  const Sample tissue = make_preset("tissue-small", 7);
  Params p;
  p.break_distance = 4e-3;
  std::vector<std::uint64_t> hashes;
  std::vector<std::size_t> broken;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    System system(tissue, p);
    const double dt = 0.4 * system.critical_dt();
    const loading::SpeedRamp ramp{20000.0, 50 * dt};
    for (int s = 1; s <= 400; ++s) system.step(dt, ramp.at(s * dt));
    hashes.push_back(system.state_hash());
    broken.push_back(system.bond_count() - system.intact_bonds());
  }
  omp_set_num_threads(2);
  EXPECT_GT(broken[0], 0u) << "some bonds must break so that the break path is covered";
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
  EXPECT_EQ(broken[0], broken[1]);
}

}  // namespace
}  // namespace rupture::dem
