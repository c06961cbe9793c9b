// Slow physics validations (label `validation`, opt-in: ctest -L validation): the whole fast pull of
// bench/runs/fast-pull.toml against the quantities the engine gave when it matched Yade's loading
// curve on the reduced tissue (docs/performance.md). An engine change that moves any of them by more
// than 0.2 % changed the physics, not just the speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/csv.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using testing::run_rupture;
using testing::slurp;
using testing::TempDir;

// y(x) by linear interpolation on a curve sampled in increasing x.
double at(const std::vector<double>& x, const std::vector<double>& y, double where) {
  const auto upper = std::lower_bound(x.begin(), x.end(), where);
  if (upper == x.begin() || upper == x.end()) return NAN;
  const std::size_t i = std::size_t(upper - x.begin());
  const double t = (where - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + t * (y[i] - y[i - 1]);
}

TEST(Validation, FastPullKeepsItsLoadingCurve) {
  TempDir dir;
  const std::string config = std::string(RUPTURE_EXAMPLES_DIR) + "../bench/runs/fast-pull.toml";
  const auto r = run_rupture("run '" + config + "' -o '" + (dir / "run").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto curves = io::read_csv(dir / "run" / "curves.csv");
  const auto& strain = curves.column("strain");
  const auto& force = curves.column("force_top");
  const auto& broken = curves.column("broken_bonds");
  const std::size_t peak = std::size_t(std::max_element(force.begin(), force.end()) - force.begin());
  // Recorded with the engine before the dem/ split (and unchanged by it): N, %, bonds.
  const double tolerance = 0.002;
  EXPECT_NEAR(force[peak], 636.014, tolerance * 636.014) << "peak plate force (N)";
  EXPECT_NEAR(strain[peak], 0.42203, tolerance * 0.42203) << "strain at the peak (%)";
  EXPECT_NEAR(at(strain, force, 1.0), 35.1672, tolerance * 35.1672) << "force at 1 % strain";
  EXPECT_NEAR(at(strain, force, 2.0), 38.404, tolerance * 38.404) << "force at 2 % strain";
  EXPECT_NEAR(at(strain, force, 3.0), -122.39, tolerance * 122.39) << "force at 3 % strain";
  EXPECT_NEAR(at(strain, broken, 5.0), 1260.04, tolerance * 1260.04) << "broken bonds at 5 % strain";
  const auto report = nlohmann::json::parse(slurp(dir / "run" / "run.json"));
  EXPECT_LT(report["energy_balance"]["max_error_relative_to_work"].get<double>(), 0.005);
}

}  // namespace
}  // namespace rupture
