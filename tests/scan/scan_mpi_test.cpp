// Scans under MPI: `mpirun -n 2 --oversubscribe rupture scan` farms the small block scan out across
// two ranks and gives the same physics columns, byte for byte, as the scan run locally; restarted through
// examples/slurm/scan-mpi.sbatch, it finds every point finished and runs nothing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "scan_support.hpp"
#include "support/tool.hpp"

namespace rupture::scan {
namespace {

using rupture::testing::run_rupture;
using rupture::testing::shell_quoted;
using rupture::testing::slurp;
using rupture::testing::TempDir;
using test_support::physics;

const std::string examples = RUPTURE_EXAMPLES_DIR;

struct Launch {
  int exit_code = -1;
  std::string out;
};

// `mpirun -n RANKS rupture ARGS`, stdout and stderr together in `out`. Root is allowed (containers);
// leak checking is off for the ranks because the MPI library's own allocations outlive MPI_Finalize.
Launch mpirun(int ranks, const std::string& args, const TempDir& dir) {
  const auto log = dir / "mpirun.log";
  const std::string command =
      "CI=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
      "ASAN_OPTIONS=detect_leaks=0 '" RUPTURE_MPIEXEC "' -n " +
      std::to_string(ranks) + " --oversubscribe '" + RUPTURE_BINARY + "' " + args + " </dev/null >" +
      shell_quoted(log) + " 2>&1";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(log)};
}

TEST(ScanMpi, TwoRanksGiveTheSamePhysicsAsOneProcess) {
  TempDir dir;
  const std::string config = shell_quoted(examples + "scan-block.toml");
  const auto local = run_rupture("scan " + config + " -o " + shell_quoted(dir / "local") + " --jobs 1");
  ASSERT_EQ(local.exit_code, 0) << local.err;

  const auto farmed = mpirun(2, "scan " + config + " -o " + shell_quoted(dir / "scan-block"), dir);
  ASSERT_EQ(farmed.exit_code, 0) << farmed.out;
  EXPECT_NE(farmed.out.find("6 to run on 2 MPI ranks"), std::string::npos) << farmed.out;
  EXPECT_EQ(physics(dir / "local" / "results.csv"), physics(dir / "scan-block" / "results.csv"));
  const auto scan = nlohmann::json::parse(slurp(dir / "scan-block" / "scan.json"));
  EXPECT_EQ(scan["mpi_ranks"], 2);
  EXPECT_EQ(scan["counts"]["ok"], 6);

  // Restarted under MPI as the example batch script does it: every point is finished, none runs again.
  const auto again = test_support::run_script("scan-mpi.sbatch", dir.path(),
                                              "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                                              "ASAN_OPTIONS=detect_leaks=0 MPIRUN='" RUPTURE_MPIEXEC
                                              " -n 2 --oversubscribe' SCAN_CONFIG=" +
                                                  config + " SLURM_CPUS_PER_TASK=1");
  ASSERT_EQ(again.exit_code, 0) << again.out;
  EXPECT_NE(again.out.find("0 to run"), std::string::npos) << again.out;
  EXPECT_FALSE(std::filesystem::exists(dir / "scan-block" / "points" / "kn_100_bd_0.002" / "attempt-2"));
  EXPECT_EQ(physics(dir / "local" / "results.csv"), physics(dir / "scan-block" / "results.csv"));
}

}  // namespace
}  // namespace rupture::scan
