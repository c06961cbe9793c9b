// `rupture run` and `rupture check` end to end: configs rejected with clear messages, an unstable
// run stopped with a diagnosis, identical bytes for any thread count, runs to separation.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/csv.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"
#include "support/json_convention.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;
using testing::run_rupture;
using testing::slurp;
using testing::TempDir;

const std::string examples = RUPTURE_EXAMPLES_DIR;

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

std::filesystem::path write_config(const TempDir& dir, const std::string& text) {
  const auto path = dir / "config.toml";
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(text.c_str(), f);
  std::fclose(f);
  return path;
}

TEST(RunCommand, HelpConfigShowsEveryKeyWithUnitAndDefault) {
  const auto r = run_rupture("run --help-config");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"[bonds]", "stiffness = 1000", "[N/mm]", "break_distance = 0.05", "[mm]",
                           "dt = \"auto\"", "[mm/s]", "snapshot_interval", "threads"})
    EXPECT_THAT(r.out, HasSubstr(text));
}

TEST(RunCommand, UnknownKeyIsRejectedListingValidKeys) {
  TempDir dir;
  const auto config = write_config(dir, "[sample]\nlattice = \"chain\"\n[bonds]\nstifness = 1e3\n");
  const auto r = run_rupture("check " + quoted(config));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bonds.stifness: unknown key"));
  EXPECT_THAT(r.err, HasSubstr("bonds.stiffness"));
}

TEST(RunCommand, MissingSampleIsRejected) {
  TempDir dir;
  const auto config = write_config(dir, "[bonds]\nstiffness = 1e3\n");
  const auto r = run_rupture("run " + quoted(config));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no sample given"));
}

TEST(RunCommand, NonPositiveStiffnessIsRejected) {
  const auto r = run_rupture("check '" + examples + "block.toml' --set bonds.stiffness=0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bonds.stiffness: 0 is outside the plausible range [1e-06, 1e+12] N/mm"));
}

TEST(RunCommand, DtAboveStabilityLimitIsRejectedWithTheLimit) {
  const auto r = run_rupture("check '" + examples + "block.toml' --set time.dt=1e-5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("exceeds the stability limit"));
  EXPECT_THAT(r.err, HasSubstr("dt = \"auto\""));
}

TEST(RunCommand, CheckPrintsDtSpeedRatioAndEstimates) {
  const auto r = run_rupture("check '" + examples + "block.toml'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"critical dt", "plate speed / wave speed", "estimate:", "bytes per particle",
                           "\"stiffness\": 1000.0"})
    EXPECT_THAT(r.out, HasSubstr(text));
}

TEST(RunCommand, UnstableRunStopsWithDiagnosisAndKeepsOutputs) {
  TempDir dir;
  const auto r = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "out") +
                             " --set time.dt=2e-6 --set time.allow_unstable_dt=true");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("unstable at step"));
  EXPECT_THAT(r.err, HasSubstr("try time.dt ="));
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "run.json"));
  EXPECT_EQ(report["status"], "failed");
  EXPECT_EQ(report["stop_reason"], "unstable");
  EXPECT_GE(io::read_csv(dir / "out" / "curves.csv").rows(), 1u);
}

// What `rupture check` warns of is said by `rupture run` too, on stderr as the run starts, and kept in
// run.json's plan.
TEST(RunCommand, RunSaysThePlansWarningsAsItStarts) {
  TempDir dir;
  const std::string ramp_warning = "a ramp shorter than 1000 steps sends a shock through the sample";
  const auto r = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "out") +
                             " --set loading.ramp_steps=500 --set stop.max_steps=50");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: " + ramp_warning));
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "run.json"));
  ASSERT_EQ(report["plan"]["warnings"].size(), 1u);
  EXPECT_THAT(report["plan"]["warnings"][0].get<std::string>(), HasSubstr(ramp_warning));
  const auto quiet = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "quiet") +
                                 " --set loading.ramp_steps=1000 --set stop.max_steps=50");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_THAT(quiet.err, ::testing::Not(HasSubstr("warning:")));
}

// The regular block runs to separation in well under a second (also under the sanitizers).
TEST(RunCommand, BlockRunsToSeparationWithBalancedEnergy) {
  TempDir dir;
  const auto r = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "run.json"));
  EXPECT_EQ(report["stop_reason"], "separated");
  EXPECT_LT(report["energy_balance"]["max_error_relative_to_work"].get<double>(), 1e-2);
  EXPECT_THAT(testing::json_convention_breaches(report), ::testing::IsEmpty());
  EXPECT_EQ(report["plan"]["dt"]["unit"], "s");
  EXPECT_EQ(report["sample"]["glued_layer_heights"]["top"]["unit"], "mm");
  const auto curves = io::read_csv(dir / "out" / "curves.csv");
  EXPECT_EQ(curves.header.size(), 18u);
  // Header first, no comment lines: what wrote the tables and what the strain means is in run.json.
  EXPECT_EQ(slurp(dir / "out" / "curves.csv").rfind("time[s],step[1],strain[%],", 0), 0u);
  EXPECT_EQ(slurp(dir / "out" / "breaks.csv").rfind("step[1],time[s],strain[%],", 0), 0u);
  EXPECT_THAT(report["columns"]["strain"].get<std::string>(), HasSubstr("initial plate separation"));
  EXPECT_TRUE(curves.find("force_top").has_value() && curves.find("elastic_energy").has_value());
  const auto breaks = io::read_csv(dir / "out" / "breaks.csv");
  EXPECT_GE(breaks.rows(), 8u) << "at least one bond per column";
  // run.log ends with the run's last line: steps, strain, breaks and why it stopped.
  const std::string log = slurp(dir / "out" / "run.log");
  EXPECT_NE(log.find(fmt::format("run: {}/", report["steps"].get<std::uint64_t>())), std::string::npos)
      << log;
  EXPECT_NE(log.find(fmt::format("{} broken, stopped: separated (end)", breaks.rows())), std::string::npos)
      << log;
}

// Each row's means (strain, top force, elastic energy) are those of the steps since the previous row:
// at 20 steps a row every step is sampled, so a run writing a row every step gives them back. The
// first row (step 0) holds the instant's values; every column is in its place in every row.
TEST(RunCommand, RowMeansAreTheMeansOfTheStepsSinceThePreviousRow) {
  TempDir dir;
  const std::string run = "run '" + examples + "block.toml' --set stop.max_steps=400 -o ";
  ASSERT_EQ(run_rupture(run + quoted(dir / "rows20") + " --set output.interval=20").exit_code, 0);
  ASSERT_EQ(run_rupture(run + quoted(dir / "rows1") + " --set output.interval=1").exit_code, 0);
  const auto rows20 = io::read_csv(dir / "rows20" / "curves.csv");
  const auto every = io::read_csv(dir / "rows1" / "curves.csv");
  ASSERT_EQ(rows20.rows(), 21u);
  ASSERT_EQ(every.rows(), 401u);
  const auto& step = every.column("step");
  for (std::size_t r = 0; r < every.rows(); ++r) ASSERT_EQ(step[r], double(r));
  const std::pair<const char*, const char*> pairs[] = {
      {"strain_mean", "strain"}, {"force_top_mean", "force_top"}, {"elastic_energy_mean", "elastic_energy"}};
  for (const auto& [mean, instant] : pairs) {
    const auto& means = rows20.column(mean);
    const auto& values = every.column(instant);
    EXPECT_EQ(means[0], values[0]) << mean;
    double largest = 0.0;
    for (std::size_t row = 1; row < rows20.rows(); ++row) {
      double sum = 0.0;
      for (std::size_t k = 20 * (row - 1) + 1; k <= 20 * row; ++k) sum += values[k];
      EXPECT_NEAR(means[row], sum / 20.0, 1e-12 * std::abs(sum)) << mean << " row " << row;
      largest = std::max(largest, std::abs(values[20 * row] - sum / 20.0));
    }
    // The mean is not the row's own sample: the block is loaded, so the values change within a row.
    EXPECT_GT(largest, 0.0) << mean;
  }
  // The row's single samples are unchanged by the means.
  EXPECT_EQ(rows20.column("force_top")[20], every.column("force_top")[400]);
}

// One switch keeps a run going past separation: it stops at max_strain, with the separation still
// recorded where it happened.
TEST(RunCommand, StopAtSeparationFalsePullsOnToMaxStrain) {
  TempDir dir;
  const auto r = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "out") +
                             " --set stop.at_separation=false --set stop.max_strain=3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "run.json"));
  EXPECT_EQ(report["stop_reason"], "max_strain");
  EXPECT_EQ(report["final_strain"]["unit"], "%");
  EXPECT_GE(report["final_strain"]["value"].get<double>(), 3.0);
  ASSERT_TRUE(report["separation_strain"]["value"].is_number());
  EXPECT_EQ(report["separation_strain"]["unit"], "%");
  EXPECT_LT(report["separation_strain"]["value"].get<double>(), 1.0);  // the block parts near 0.3 %
  EXPECT_EQ(report["config"]["stop"]["at_separation"], false);
}

// A sample that starts pre-stressed (rest lengths 0.05 % shorter than the initial distances, as
// LAMMPS's binned rest lengths would leave it) runs: its initial elastic energy, sum of k d^2 / 2 over
// the bonds, is counted in the energy balance instead of being taken for an instability.
TEST(RunCommand, PreStressedSampleRunsWithItsInitialEnergyInTheBalance) {
  TempDir dir;
  Sample block = make_cubic_block(4, 8, 2, 0.5);
  for (auto& bond : block.bonds) bond.rest_length *= 0.9995;  // 1 mm -> stretched by 5e-4 mm
  save_sample(block, dir / "pre.sample");
  const auto config =
      write_config(dir,
                   "[sample]\nfile = \"pre.sample\"\n[bonds]\nstiffness = 1e3\n"
                   "break_distance = 0.002\n[loading]\nspeed = 500.0\nramp_steps = 500\n"
                   "[stop]\nextra_strain = 0.5\nmax_strain = 20.0\n[output]\ninterval = 50\n");
  const auto r = run_rupture("run " + quoted(config) + " -o " + quoted(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "run.json"));
  EXPECT_EQ(report["stop_reason"], "separated");
  const double expected = double(block.bonds.size()) * 0.5 * 1e3 * 5e-4 * 5e-4;  // N/mm * mm^2 = mJ
  EXPECT_EQ(report["energy_balance"]["initial_energy"]["unit"], "mJ");
  EXPECT_NEAR(report["energy_balance"]["initial_energy"]["value"].get<double>(), expected, 1e-9 * expected);
  // The release of the pre-stress shakes the block: the balance holds to a few percent of the energy
  // in play (0.5 % without the pre-stress).
  EXPECT_LT(report["energy_balance"]["max_error_relative_to_work"].get<double>(), 3e-2);
}

TEST(RunCommand, SnapshotsAreWrittenForParaView) {
  TempDir dir;
  const auto r = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "out") +
                             " --set output.snapshot_interval=500");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string pvd = slurp(dir / "out" / "snapshots.pvd");
  EXPECT_THAT(pvd, HasSubstr("snapshots/step_0000000000.vtp"));
  EXPECT_THAT(pvd, HasSubstr("snapshots/step_0000000500.vtp"));
  const std::string vtp = slurp(dir / "out" / "snapshots" / "step_0000000500.vtp");
  EXPECT_THAT(vtp, HasSubstr("extension_mm"));
  EXPECT_THAT(vtp, HasSubstr("relative_extension"));
}

// A sample file is found relative to the config's folder and gives the same run as the lattice.
TEST(RunCommand, SampleFileIsReadRelativeToTheConfig) {
  TempDir dir;
  save_sample(make_cubic_block(4, 8, 2, 0.5), dir / "block.sample");
  std::string text = slurp(examples + "block.toml");
  const auto at = text.find("lattice = \"block\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("lattice = \"block\"").size(), "file = \"block.sample\"");
  const auto config = write_config(dir, text);
  const auto from_file =
      run_rupture("run " + quoted(config) + " -o " + quoted(dir / "file") + " --set stop.max_steps=300");
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  const auto from_lattice = run_rupture("run '" + examples + "block.toml' -o " + quoted(dir / "lattice") +
                                        " --set stop.max_steps=300");
  ASSERT_EQ(from_lattice.exit_code, 0) << from_lattice.err;
  EXPECT_EQ(io::read_csv(dir / "file" / "curves.csv").columns,
            io::read_csv(dir / "lattice" / "curves.csv").columns);
  const auto missing = run_rupture("check " + quoted(config) + " --set sample.file=nothing.sample");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("no such file"));
}

}  // namespace
}  // namespace rupture
