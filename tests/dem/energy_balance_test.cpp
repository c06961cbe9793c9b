// The simulation's own correctness check: the plate work W equals E_e + E_k + E_contact + E_glue +
// E_released (+ damping) to a small drift that shrinks as dt shrinks (velocity Verlet is second
// order).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dem/system.hpp"
#include "loading/ramp.hpp"
#include "sample/lattice.hpp"

namespace rupture::dem {
namespace {

struct Balance {
  double max_error = 0.0;  // mJ: max |W - sum of energies| over the run
  double max_work = 0.0;   // mJ
  std::size_t broken = 0;
  double relative() const { return max_error / max_work; }
};

// Pulls `sample` for `duration` seconds at `speed`, checking the ledger every `every` steps.
Balance pull(const Sample& sample, const Params& params, double dt_fraction, double speed, double duration,
             int every = 20) {
  System system(sample, params);
  const double dt = dt_fraction * system.critical_dt();
  const loading::SpeedRamp ramp{speed, 0.2 * duration};
  Balance balance;
  const auto steps = std::int64_t(duration / dt);
  for (std::int64_t s = 1; s <= steps; ++s) {
    system.step(dt, ramp.at(double(s) * dt));
    if (s % every == 0 || s == steps) {
      const Energies e = system.energies();
      const double total =
          e.elastic + e.kinetic + e.contact + e.glue + system.released_energy() + system.damping_energy();
      balance.max_work = std::max(balance.max_work, system.plate_work());
      balance.max_error = std::max(balance.max_error, std::abs(system.plate_work() - total));
    }
  }
  balance.broken = system.bond_count() - system.intact_bonds();
  return balance;
}

Params block_params(double break_distance) {
  Params p;
  p.bond_stiffness = 1e3;
  p.break_distance = break_distance;
  p.contact_stiffness = 1e3;
  p.glue_stiffness = 1e4;
  return p;
}

TEST(EnergyBalance, ElasticPullIsSecondOrderInDt) {
  const Sample block = make_cubic_block(3, 6, 2, 0.5);
  const Params p = block_params(1e3);
  // A fast pull (2 m/s) so that waves carry real kinetic energy.
  const Balance coarse = pull(block, p, 0.4, 2000.0, 2e-5);
  const Balance fine = pull(block, p, 0.2, 2000.0, 2e-5);
  EXPECT_EQ(coarse.broken, 0u);
  EXPECT_LT(coarse.relative(), 1e-2);
  EXPECT_GT(coarse.max_error / fine.max_error, 3.0) << "halving dt must cut the drift about 4x";
}

TEST(EnergyBalance, BlockPulledThroughFailureBalancesWithinOnePercent) {
  const Sample block = make_cubic_block(4, 8, 2, 0.5);
  const Params p = block_params(2e-3);
  const Balance coarse = pull(block, p, 0.4, 2000.0, 6e-5);
  const Balance fine = pull(block, p, 0.2, 2000.0, 6e-5);
  EXPECT_GT(coarse.broken, 8u) << "the block must have failed";
  EXPECT_LT(coarse.relative(), 1e-2);
  EXPECT_LT(fine.relative(), coarse.relative()) << "the drift shrinks with dt";
}

TEST(EnergyBalance, ViscousDampingIsAccountedFor) {
  const Sample block = make_cubic_block(3, 6, 2, 0.5);
  Params p = block_params(1e3);
  p.damping = 2e4;  // 1/s
  const Balance b = pull(block, p, 0.4, 2000.0, 2e-5);
  EXPECT_LT(b.relative(), 1e-2);
}

}  // namespace
}  // namespace rupture::dem
