// Scans: the point list and its rules, the results table round trip, and `rupture scan` end to end on
// the block lattice — every column present, the same physics bytes for 1 and 2 jobs, for a scan killed
// (SIGKILL, then SIGINT) midway and restarted, and for job-array tasks collected afterwards; failed
// points recorded; a point held by another process left to it.
#include "scan/scan.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "core/error.hpp"
#include "dem/system.hpp"
#include "figures/scan_fixture.hpp"
#include "rupture/version.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"
#include "scan/claims.hpp"
#include "scan/farm.hpp"
#include "scan/results.hpp"
#include "scan_support.hpp"
#include "support/json_convention.hpp"
#include "support/tool.hpp"

namespace rupture::scan {
namespace {

using rupture::testing::run_rupture;
using rupture::testing::shell_quoted;
using rupture::testing::slurp;
using rupture::testing::TempDir;
using test_support::physics;

const std::string examples = RUPTURE_EXAMPLES_DIR;

void write(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

// A block whose bonds are all 1 mm long (radius 0.5 mm): the sample the plan tests scan.
const Sample& unit_block() {
  static const Sample block = make_cubic_block(2, 3, 1, 0.5);
  return block;
}

// A scan of the block lattice grown to 6 x 16 x 3 particles and pulled slower, so that each point takes
// long enough to be killed in the middle of one.
std::string slow_scan(const std::string& output) {
  return "[scan]\nbase = '" + examples + "block.toml'\noutput = '" + output +
         "'\nset = [\"sample.lattice_cells=[6, 16, 3]\", \"loading.speed=250\"]\n"
         "[grid]\nk_n = { from = 1e2, to = 1e3, count = 3 }\nb_d = { from = 0.002, to = 0.004, count = 2 }\n"
         "[rules]\nramp_steps = 500\nramp_b_d = 0.004\nramp_min_steps = 500\nramp_max_steps = 2000\n"
         "max_strain = \"scaled\"\nmax_strain_factor = 10\n";
}

TEST(ScanPlan, GridIsLogSpacedWithExactNames) {
  EXPECT_EQ(log_spaced({100.0, 1e4, 3}), (std::vector<double>{100.0, 1000.0, 10000.0}));
  EXPECT_EQ(log_spaced({0.002, 0.002, 1}), std::vector<double>{0.002});
  // 10^(1/3) rounded to 6 significant digits, so the folder name is the value used.
  const auto v = log_spaced({1.0, 10.0, 4});
  EXPECT_DOUBLE_EQ(v[1], 2.15443);
  EXPECT_EQ(point_name(v[1], 0.005), "kn_2.15443_bd_0.005");
}

TEST(ScanPlan, RulesScaleTheRampAndTheStopWithBreakingDistance) {
  TempDir dir;
  const auto config = load_scan_config(examples + "scan-block.toml");
  // block.toml: simple cubic, radius 0.5 mm, so every bond's rest length is 1 mm.
  const Plan plan = make_plan(config, unit_block());
  ASSERT_EQ(plan.points.size(), 6u);
  EXPECT_EQ(plan.points[0].name, "kn_100_bd_0.002");
  EXPECT_EQ(plan.points[1].name, "kn_100_bd_0.004");  // k_n varies slowest
  // ramp_steps x (ramp_b_d / b_d) = 500 x 0.004 / 0.002; stop at 10 x the first-break strain 100 b_d / r0.
  EXPECT_EQ(plan.points[0].ramp_steps, 1000);
  EXPECT_EQ(plan.points[1].ramp_steps, 500);
  EXPECT_DOUBLE_EQ(plan.points[0].max_strain, 2.0);
  EXPECT_DOUBLE_EQ(plan.points[1].max_strain, 4.0);
  const auto run = point_config(plan, plan.points[5], 3);
  EXPECT_EQ(run.bond_stiffness, 1e4);
  EXPECT_EQ(run.break_distance, 0.004);
  EXPECT_EQ(run.threads, 3);
  EXPECT_FALSE(run.dt.has_value());  // dt = "auto": from k_n and the lightest particle
}

TEST(ScanPlan, StrainRulesEndTheRampAndSpaceTheRowsByTheFirstBreakStrain) {
  TempDir dir;
  write(dir / "s.toml",
        "[scan]\nbase = '" + examples +
            "block.toml'\n[grid]\nk_n = { from = 1e2, to = 1e4, count = 2 }\n"
            "b_d = { from = 0.002, to = 0.02, count = 2 }\n[rules]\nramp = \"strain\"\n"
            "ramp_fraction = 0.1\nramp_min_steps = 1\ninterval = \"scaled\"\nrows_to_first_break = 10\n");
  const ScanConfig config = load_scan_config(dir / "s.toml");
  const Plan plan = make_plan(config, unit_block());
  ASSERT_EQ(plan.points.size(), 4u);
  // Steps to the first-break strain 100 b_d / r0 (r0 = 1 mm) at full speed, from the engine's dt.
  const loading::RunConfig base = base_config(config);
  const auto steps_to_first_break = [&](const Point& p) {
    const auto run = point_config(plan, p, 1);
    const dem::System system(unit_block(), run.dem_params(unit_block().density));
    const double dt = run.dt_safety * system.critical_dt();
    return p.b_d * system.initial_plate_separation() / (base.speed * dt);
  };
  for (const auto& p : plan.points) {
    const double steps = steps_to_first_break(p);
    // The ramp v/2 (1 - cos) over T covers half of v T: 10 % of the first-break strain takes 0.2 x steps.
    EXPECT_NEAR(double(p.ramp_steps), 0.2 * steps, 1.0) << p.name;
    EXPECT_NEAR(double(p.output_interval), steps / 10.0, 1.0) << p.name;
    EXPECT_EQ(point_settings(plan, p, 1)["output"]["interval"], p.output_interval);
    EXPECT_EQ(point_config(plan, p, 1).output_interval, p.output_interval);
  }
  // dt ~ 1/sqrt(k_n): 100 times the stiffness, ten times the steps to the same strain; b_d ten
  // times larger, ten times the steps.
  EXPECT_NEAR(steps_to_first_break(plan.points[2]) / steps_to_first_break(plan.points[0]), 10.0, 1e-9);
  EXPECT_NEAR(double(plan.points[3].output_interval) / double(plan.points[2].output_interval), 10.0, 0.2);
  // Bad values are refused with the key.
  write(dir / "bad.toml", "[scan]\nbase = '" + examples +
                              "block.toml'\n[[points]]\nk_n = 1\nb_d = 1\n[rules]\n"
                              "interval = \"fine\"\n");
  EXPECT_THROW((void)load_scan_config(dir / "bad.toml"), InputError);
  write(dir / "bad.toml", "[scan]\nbase = '" + examples +
                              "block.toml'\n[[points]]\nk_n = 1\nb_d = 1\n[rules]\n"
                              "ramp = \"strain\"\nramp_fraction = 2\n");
  try {
    (void)load_scan_config(dir / "bad.toml");
    ADD_FAILURE() << "ramp_fraction = 2 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rules.ramp_fraction"), std::string::npos) << e.what();
  }
}

// The [rules] reference (rupture scan --help-config) is itself a valid [rules] section: read back,
// it gives exactly the defaults, and it names every key the scan's JSON writes.
TEST(ScanPlan, RulesReferenceReadsBackAsTheDefaults) {
  TempDir dir;
  const std::string reference = rules_reference();
  write(dir / "reference.toml",
        "[scan]\nbase = '" + examples + "block.toml'\n[[points]]\nk_n = 1\nb_d = 1\n" + reference);
  const auto read = to_json(load_scan_config(dir / "reference.toml"))["rules"];
  ScanConfig defaults;
  EXPECT_EQ(read, to_json(defaults)["rules"]);
  for (const auto& [key, value] : read.items())
    EXPECT_NE(reference.find("\n" + key + " = "), std::string::npos) << key;
  EXPECT_EQ(read.size(), 13u);
  write(dir / "reference.toml",
        "[scan]\nbase = '" + examples +
            "block.toml'\n[[points]]\nk_n = 1\nb_d = 1\n[rules]\nramp_min_steps = 10\n"
            "ramp_max_steps = 5\n");
  EXPECT_THROW((void)load_scan_config(dir / "reference.toml"), InputError);
}

// A plan.json written before the rules went through the schema names the time step "dt_s": the
// scan folder still reads, with its dt.
TEST(ScanPlan, PlansThatNameTheTimeStepDtSStillRead) {
  TempDir dir;
  write(dir / "s.toml", "[scan]\nbase = '" + examples + "block.toml'\noutput = '" + (dir / "scan").string() +
                            "'\n[[points]]\nk_n = 1e2\nb_d = 0.01\n[rules]\ndt = 1e-7\n");
  const Plan plan = make_plan(load_scan_config(dir / "s.toml"), unit_block());
  write_plan(plan);
  EXPECT_EQ(read_plan(plan.folder).dt, std::optional<double>(1e-7));
  auto document = nlohmann::json::parse(slurp(plan.folder / "plan.json"));
  auto& rules = document["scan_config"]["rules"];
  rules["dt_s"] = rules["dt"];
  rules.erase("dt");
  write(plan.folder / "plan.json", document.dump());
  EXPECT_EQ(read_plan(plan.folder).dt, std::optional<double>(1e-7));
}

TEST(ScanPlan, PaperScanSpansTheRangesOfSectionFive) {
  // The paper's scan: k_n from 10 to 10^7 N/mm, b_d from 10^-3 to 5 mm; the ramp 10^4 steps where
  // bonds break at large strains and up to 10^6 steps where they break at small ones.
  const Plan plan = make_plan(load_scan_config(examples + "scan-tissue.toml"), unit_block());
  ASSERT_EQ(plan.points.size(), 195u);
  EXPECT_EQ(plan.points.front().name, "kn_10_bd_0.001");
  EXPECT_EQ(plan.points.back().name, "kn_10000000_bd_5");
  EXPECT_EQ(plan.points.front().ramp_steps, 1000000);
  EXPECT_EQ(plan.points.back().ramp_steps, 10000);
  // Stop strain 5 x the first-break strain 100 b_d / r0 (r0 = 1 mm here), within [2 %, 600 %].
  EXPECT_DOUBLE_EQ(plan.points.front().max_strain, 2.0);
  EXPECT_DOUBLE_EQ(plan.points.back().max_strain, 600.0);
  EXPECT_NEAR(plan.points[7].max_strain, 5 * 100 * plan.points[7].b_d,
              1e-5 * plan.points[7].max_strain);  // 6 digits
}

TEST(ScanPlan, TheStudyScansPlanTheirPoints) {
  // examples/study: the scans docs/study.md reports, planned here on the unit block (the rules need
  // only the sample's dt and rest length).
  const struct {
    const char* file;
    std::size_t points;
    const char* break_rule;
  } scans[] = {{"study/scan-small-absolute.toml", 48, "absolute"},
               {"study/scan-small-relative.toml", 49, "relative"},
               {"study/scan-tissue-absolute.toml", 6, "absolute"}};
  for (const auto& scan : scans) {
    const ScanConfig config = load_scan_config(examples + scan.file);
    const Plan plan = make_plan(config, unit_block());
    EXPECT_EQ(plan.points.size(), scan.points) << scan.file;
    EXPECT_EQ(base_config(config).break_rule, scan.break_rule) << scan.file;
    EXPECT_DOUBLE_EQ(base_config(config).speed, 50.0) << scan.file;  // the paper's plate speed
    for (const auto& p : plan.points) {
      EXPECT_GE(p.ramp_steps, 500) << p.name;
      EXPECT_GE(p.output_interval, 1) << p.name;
    }
  }
}

TEST(ScanPlan, ListedPointsFollowTheGridWithoutDuplicates) {
  TempDir dir;
  write(dir / "s.toml",
        "[scan]\nbase = '" + examples +
            "block.toml'\n[grid]\nk_n = { from = 1e2, to = 1e3, count = 2 }\n"
            "b_d = { from = 0.002, to = 0.002, count = 1 }\n[[points]]\nk_n = 1e5\nb_d = 0.05\n"
            "[[points]]\nk_n = 100\nb_d = 0.002\n");
  const Plan plan = make_plan(load_scan_config(dir / "s.toml"), unit_block());
  ASSERT_EQ(plan.points.size(), 3u);
  EXPECT_EQ(plan.points[2].name, "kn_100000_bd_0.05");
  EXPECT_EQ(plan.points[2].index, 2u);
}

TEST(ScanPlan, BadConfigsNameTheKeyAndTheFix) {
  TempDir dir;
  const auto message = [&](const std::string& text) {
    write(dir / "bad.toml", text);
    try {
      (void)make_plan(load_scan_config(dir / "bad.toml"), unit_block());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string base = "[scan]\nbase = '" + examples + "block.toml'\n";
  EXPECT_NE(
      message(base + "[grid]\nk_n = { from = 1, to = 2, count = 2 }\nb_d = { from = 1, to = 2, count = 2 }\n"
                     "[rules]\nramp_step = 5\n")
          .find("rules.ramp_step"),
      std::string::npos);
  EXPECT_NE(message(base).find("no points"), std::string::npos);
  EXPECT_NE(
      message(base + "[grid]\nk_n = { from = 0, to = 2, count = 2 }\nb_d = { from = 1, to = 2, count = 2 }\n")
          .find("grid.k_n"),
      std::string::npos);
  EXPECT_NE(
      message(base +
              "[grid]\nk_n = { from = 1, to = 2, count = 2.5 }\nb_d = { from = 1, to = 2, count = 2 }\n")
          .find("grid.k_n.count"),
      std::string::npos);
  // The grid's ranges, the points and [scan] are read by the config schema, as [rules] and a run
  // config are: unknown and missing keys are named with the ones that belong there.
  EXPECT_NE(
      message(base + "[grid]\nk_n = { from = 1, to = 2, count = 2 }\nb_d = { from = 1, to = 2, step = 2 }\n")
          .find("grid.b_d.step: unknown key; valid keys: grid.b_d.from, grid.b_d.to, grid.b_d.count"),
      std::string::npos);
  EXPECT_NE(message(base + "[grid]\nk_n = { from = 1, to = 2, count = 2 }\nb_d = { from = 1, to = 2 }\n")
                .find("grid.b_d.count: missing; add count = ..."),
            std::string::npos);
  EXPECT_NE(message(base + "[grid]\nk_n = { from = 1, to = 2, count = 2 }\n").find("grid.b_d: missing"),
            std::string::npos);
  EXPECT_NE(message(base + "[[points]]\nk_n = 10\n[[points]]\nb_d = 1\n").find("points[0].b_d: missing"),
            std::string::npos);
  EXPECT_NE(message(base + "set = \"stop.max_steps=10\"\n[[points]]\nk_n = 10\nb_d = 1\n")
                .find("scan.set: expects an array of strings"),
            std::string::npos);
  EXPECT_NE(message(base + "set = [\"stop.max_steps=10\", 3]\n[[points]]\nk_n = 10\nb_d = 1\n")
                .find("scan.set[1]: expects a string"),
            std::string::npos);
  // Non-finite or subnormal values, grids too large to hold, and a given dt above some point's
  // stability limit are refused with the key, before anything runs.
  EXPECT_NE(
      message(base +
              "[grid]\nk_n = { from = 1, to = inf, count = 2 }\nb_d = { from = 1, to = 2, count = 2 }\n")
          .find("grid.k_n.to: inf is not a finite number in the plausible range"),
      std::string::npos);
  EXPECT_NE(message(base + "[[points]]\nk_n = 1e-308\nb_d = 1\n")
                .find("points[0].k_n: 1e-308 is outside the plausible range"),
            std::string::npos);
  EXPECT_NE(
      message(
          base +
          "[grid]\nk_n = { from = 1, to = 2, count = 10000 }\nb_d = { from = 1, to = 2, count = 10000 }\n")
          .find("1e+08 points, more than the 100000 a scan folder holds"),
      std::string::npos);
  const std::string dt_limit =
      message(base +
              "[grid]\nk_n = { from = 1e2, to = 1e6, count = 3 }\nb_d = { from = 1, to = 1, count = 1 }\n"
              "[rules]\ndt = 1e-7\n");
  // The limits scale as 1/sqrt(k_n) from the first point's; the engine gives the same at k_n = 1e4
  // on the plan's sample.
  const loading::RunConfig at_1e4 = loading::load_config(examples + "block.toml", {"bonds.stiffness=1e4"});
  const double limit = dem::System(unit_block(), at_1e4.dem_params(unit_block().density)).critical_dt();
  EXPECT_NE(
      dt_limit.find(fmt::format("bad.toml: rules.dt: dt = 1e-07 s exceeds the stability limit at 2 of 3 "
                                "points: kn_10000_bd_1 (limit {:.3g} s), kn_1000000_bd_1",
                                limit)),
      std::string::npos)
      << dt_limit << " (engine: " << limit << " s)";
  write(dir / "file", "");
  EXPECT_NE(message(base + "output = '" + (dir / "file").string() + "'\n[[points]]\nk_n = 1\nb_d = 1\n")
                .find("is a file, not a scan folder"),
            std::string::npos);
  // A bad override reaches the run config's own check before anything runs.
  EXPECT_NE(
      message(base + "set = [\"bonds.nothing=1\"]\n[[points]]\nk_n = 1\nb_d = 1\n").find("bonds.nothing"),
      std::string::npos);
}

TEST(ScanParallelism, JobsFillTheCoresAndLeftoversGoToThreads) {
  EXPECT_EQ(choose_parallelism(16, 200, 0, 0).jobs, 16);
  EXPECT_EQ(choose_parallelism(16, 200, 0, 0).threads, 1);
  EXPECT_EQ(choose_parallelism(16, 3, 0, 0).jobs, 3);
  EXPECT_EQ(choose_parallelism(16, 3, 0, 0).threads, 5);
  EXPECT_EQ(choose_parallelism(16, 200, 0, 4).jobs, 4);
  EXPECT_EQ(choose_parallelism(16, 200, 2, 0).threads, 8);
  EXPECT_EQ(choose_parallelism(2, 200, 1, 1).jobs, 1);
  EXPECT_EQ(choose_parallelism(1, 0, 0, 0).jobs, 1);
}

TEST(ScanResults, TextAndMissingValuesRoundTrip) {
  const std::vector<nlohmann::json> rows = {
      {{"point", 0}, {"k_n", 1e3}, {"status", "ok"}, {"why", "a, \"quoted\"\nreason"}, {"x_c", 0.1 + 0.2}},
      {{"point", 1}, {"k_n", 2.5}, {"status", "pending"}}};
  const std::string text = format_results(rows, {"test"});
  const ResultsTable table = parse_results(text, "mem");
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.header.size(), result_columns().size());
  EXPECT_EQ(table.text(0, "why"), "a, \"quoted\"\nreason");
  EXPECT_EQ(*table.number(0, "x_c"), 0.1 + 0.2);  // shortest form that reads back exactly
  EXPECT_FALSE(table.number(1, "x_c").has_value());
  EXPECT_EQ(table.text(1, "status"), "pending");
  EXPECT_THROW((void)table.number(0, "status"), InputError);
  EXPECT_THROW((void)table.require("nothing"), InputError);
  EXPECT_THROW(parse_results("a,b\n1\n", "mem"), InputError);
}

// The paper's claims against the hand-written fixture, whose every number is known: 10 points, 8
// separated, 6 accepted (5 with δ_x > 0), 4 of them with A_r inside the FBM band 0.837-1.333.
TEST(ScanClaims, CountAndSummariseTheAcceptedPointsOfAKnownTable) {
  rupture::testing::TempDir dir;
  rupture::testing::write_scan_fixture(dir.path());
  const auto claims = scan::check_claims(scan::read_results(dir / "results.csv"));
  using F = rupture::testing::ScanFixture;
  EXPECT_EQ(claims.points, std::size_t(F::points));
  EXPECT_EQ(claims.separated, 8u);
  EXPECT_EQ(claims.accepted, std::size_t(F::brittle + F::hyper_elastic + F::semi_ductile));
  EXPECT_EQ(claims.counts(),
            "10 points: 10 ran, 8 separated, 6 accepted, 2 rejected, 2 not separated or failed.");
  ASSERT_EQ(claims.rows.size(), 9u);
  const auto here = [&](std::size_t row) { return claims.rows[row].here; };
  EXPECT_EQ(here(0), "5 of 6 have δ_x > 0; 0 of 6 with the 95 % lower bound > 0");
  // log δ_x on log x_c over the five positive points: slope 0.927 (computed by hand).
  EXPECT_EQ(here(1),
            "δ_x ∝ x_c^0.927 over x_c = 0.02–5 % (log–log fit, δ_x > 0); x_c^0.927 over the 5 whose 68 % "
            "interval excludes 0");
  // δ_x/x_c sorted: -0.05, 0.18, 0.24, 0.25, 0.267, 0.3; quantiles interpolated linearly: the median
  // (0.24 + 0.25)/2, the 10 % one half way from -0.05 to 0.18, the 90 % one half way from 0.267 to 0.3.
  EXPECT_EQ(here(2), "median 0.245 (10–90 %: 0.065–0.283; all -0.05–0.3)");
  EXPECT_EQ(here(3), "median –");  // the fixture has no α column values
  EXPECT_EQ(claims.rows[4].paper, "A_r in the FBM band 0.84–1.33 for x_c < 10 %");
  // A_r sorted: 0.7, 0.8, 0.95, 1.1, 1.25, 1.3 (1.025 and 1.275 print below their decimal ties).
  EXPECT_EQ(here(4), "4 of 6; A_r median 1.02 (10–90 %: 0.75–1.27; all 0.7–1.3)");
  EXPECT_EQ(here(5), fmt::format("Γ > 5: {}; A_r > 2: 0", F::gamma_above_5));
  EXPECT_EQ(here(6), "brittle at b_d = 0.001 mm");
  EXPECT_EQ(here(7), "brittle: 2, hyper-elastic: 1, semi-ductile: 3; rejected as ductile-like: 1");
  EXPECT_EQ(here(8), "2 of 8 separated runs");
  // The same table in markdown from the command line.
  const auto r = rupture::testing::run_rupture("scan --claims " + rupture::testing::shell_quoted(dir.path()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, scan::claims_markdown(claims, dir.path().string()));
  EXPECT_NE(r.out.find("| δ_x > 0 in every accepted run | 5 of 6 have δ_x > 0;"), std::string::npos);
}

// A positive δ_x whose 68 % interval reaches 0 counts in the plain fit, not in the resolved one:
// without the point (x_c, δ_x) = (5, 0.9) the slope over the other four is 0.970 (computed by hand).
TEST(ScanClaims, TheResolvedFitLeavesOutDelaysWhoseIntervalReachesZero) {
  rupture::testing::TempDir dir;
  rupture::testing::write_scan_fixture(dir.path());
  auto table = scan::read_results(dir / "results.csv");
  const std::size_t x_c = table.require("x_c"), lo68 = table.require("delta_x_lo68");
  std::size_t changed = 0;
  for (auto& row : table.rows)
    if (row[x_c] == "5") row[lo68] = "-0.1", ++changed;
  ASSERT_EQ(changed, 1u);
  EXPECT_EQ(scan::check_claims(table).rows[1].here,
            "δ_x ∝ x_c^0.927 over x_c = 0.02–5 % (log–log fit, δ_x > 0); x_c^0.970 over the 4 whose 68 % "
            "interval excludes 0");
}

TEST(ScanCommand, SmallScanWritesEveryColumnAndTheSamePhysicsForAnyJobsAndThreads) {
  TempDir dir;
  const auto one = run_rupture("scan " + shell_quoted(examples + "scan-tissue-small.toml") + " -o " +
                               shell_quoted(dir / "one") + " --jobs 1 --threads 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = run_rupture("scan " + shell_quoted(examples + "scan-tissue-small.toml") + " -o " +
                               shell_quoted(dir / "two") + " --jobs 2 --threads 1");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const ResultsTable table = read_results(dir / "one" / "results.csv");
  ASSERT_EQ(table.rows.size(), 4u);
  for (std::size_t c = 0; c < result_columns().size(); ++c)
    EXPECT_EQ(table.header[c], result_columns()[c].header());
  std::size_t accepted = 0;
  for (std::size_t r = 0; r < 4; ++r) {
    EXPECT_EQ(table.text(r, "status"), "ok") << table.text(r, "why");
    EXPECT_EQ(table.text(r, "stop_reason"), "separated");
    EXPECT_GT(*table.number(r, "dt"), 0.0);
    EXPECT_GT(*table.number(r, "broken_bonds"), 0.0);
    EXPECT_TRUE(std::filesystem::exists(dir / "one" / "points" /
                                        point_name(*table.number(r, "k_n"), *table.number(r, "b_d")) /
                                        "result.json"));
    if (*table.number(r, "accepted") == 1.0) {
      ++accepted;
      // An accepted point has every analysed quantity, the critical strain inside the run.
      for (const char* name :
           {"x_c", "F_c", "x_p", "Erate_max", "x_m", "E_max", "delta_x", "delta_x_lo95", "Gamma", "A_r"})
        EXPECT_TRUE(table.number(r, name).has_value()) << name;
      EXPECT_LT(*table.number(r, "x_c"), *table.number(r, "final_strain"));
      EXPECT_LE(*table.number(r, "delta_x_lo95"), *table.number(r, "delta_x"));
      EXPECT_FALSE(table.text(r, "class").empty());
    }
  }
  EXPECT_GE(accepted, 1u);
  EXPECT_EQ(physics(dir / "one" / "results.csv"), physics(dir / "two" / "results.csv"));
  const auto scan = nlohmann::json::parse(slurp(dir / "two" / "scan.json"));
  EXPECT_TRUE(rupture::testing::json_convention_breaches(scan).empty()) << scan.dump();
  EXPECT_EQ(scan["wall_time"]["unit"], "s");
  const auto plan = nlohmann::json::parse(slurp(dir / "two" / "plan.json"));
  EXPECT_TRUE(rupture::testing::json_convention_breaches(plan).empty()) << plan.dump();
  EXPECT_EQ(plan["points"][0]["max_strain"]["unit"], "%");
  EXPECT_EQ(scan["jobs"], 2);
  EXPECT_EQ(scan["threads"], 1);
  EXPECT_EQ(scan["counts"]["ok"], 4);
  EXPECT_FALSE(scan["version"].get<std::string>().empty());
  // Run again: nothing left to do, nothing redone.
  const auto again = run_rupture("scan " + shell_quoted(examples + "scan-tissue-small.toml") + " -o " +
                                 shell_quoted(dir / "one"));
  EXPECT_NE(again.out.find("0 to run"), std::string::npos) << again.out;
  EXPECT_FALSE(std::filesystem::exists(dir / "one" / "points" / "kn_1000_bd_0.005" / "attempt-2"));
  const auto status = run_rupture("scan --status " + shell_quoted(dir / "one"));
  EXPECT_EQ(status.exit_code, 0);
  EXPECT_NE(status.out.find("4 points: 4 done, 0 failed, 0 running, 0 pending"), std::string::npos)
      << status.out;
}

// Starts `rupture scan CONFIG --jobs 1` and sends it `signal` as soon as `started` exists (a point's
// run.json, written before its first step: the point is then mid-run). Returns the wait status, or
// nullopt when the scan ended first.
std::optional<int> interrupt_scan(const std::filesystem::path& config, const std::filesystem::path& started,
                                  int signal) {
  const pid_t child = fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::setenv("CI", "1", 1);
    ::execl(RUPTURE_BINARY, RUPTURE_BINARY, "scan", config.c_str(), "--jobs", "1",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  while (!std::filesystem::exists(started)) {
    if (::waitpid(child, &status, WNOHANG) == child) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ::kill(child, signal);
  ::waitpid(child, &status, 0);
  return status;
}

TEST(ScanCommand, ReanalyzeRewritesTheAnalysisAndKeepsTheRuns) {
  TempDir dir;
  const auto scan = dir / "scan";
  const auto first =
      run_rupture("scan " + shell_quoted(examples + "scan-block.toml") + " -o " + shell_quoted(scan));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  std::filesystem::copy_file(scan / "results.csv", dir / "before.csv");
  const auto point = scan / "points" / "kn_100_bd_0.002";
  const auto result_before = nlohmann::json::parse(slurp(point / "result.json"));
  EXPECT_TRUE(rupture::testing::json_convention_breaches(result_before).empty()) << result_before.dump();
  EXPECT_EQ(result_before.at("point").at("b_d").at("unit"), "mm");
  const auto attempt = point / result_before.at("attempt").get<std::string>();
  const std::string curves = slurp(attempt / "curves.csv");
  // A stale analysis (as an older version would have left it) is replaced by this version's.
  std::filesystem::remove(attempt / "analysis.json");
  // A point never started (as in a scan stopped early) is left pending.
  std::filesystem::remove_all(scan / "points" / "kn_10000_bd_0.004");
  // The run's record, marked as an older version's run so that keeping it is visible.
  auto run_record = nlohmann::json::parse(slurp(scan / "scan.json"));
  run_record["version"] = "0.0.1 (an older build)";
  run_record["command"] = "rupture scan the-original-command";
  {
    std::ofstream out(scan / "scan.json");
    out << run_record.dump(2);
  }
  const auto again = run_rupture("scan --reanalyze " + shell_quoted(scan));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  // The run's record survives; the re-analysis adds its own.
  const auto record = nlohmann::json::parse(slurp(scan / "scan.json"));
  for (const char* key : {"command", "version", "cores", "jobs", "wall_time"})
    EXPECT_EQ(record.at(key), run_record.at(key)) << key;
  EXPECT_NE(record.at("reanalysed").at("command").get<std::string>().find("--reanalyze"), std::string::npos);
  EXPECT_EQ(record.at("reanalysed").at("version"), rupture::version_string);
  EXPECT_NE(again.out.find("re-analysed 5 of 6 points"), std::string::npos) << again.out;
  EXPECT_TRUE(std::filesystem::exists(attempt / "analysis.json"));
  EXPECT_EQ(slurp(attempt / "curves.csv"), curves);  // the run is untouched
  const auto after = physics(scan / "results.csv"), expected = physics(dir / "before.csv");
  ASSERT_EQ(after.size(), 6u);
  for (std::size_t r = 0; r < 5; ++r) EXPECT_EQ(after[r], expected[r]) << r;  // same analysis, same numbers
  EXPECT_NE(after[5].find("pending"), std::string::npos) << after[5];
  const auto result_after = nlohmann::json::parse(slurp(point / "result.json"));
  EXPECT_EQ(result_after.at("row").at("steps"), result_before.at("row").at("steps"));
  EXPECT_EQ(run_rupture("scan --reanalyze " + shell_quoted(dir / "nothing")).exit_code, 2);
}

TEST(ScanCommand, KilledMidwayAndRestartedGivesTheSameResults) {
  TempDir dir;
  write(dir / "whole.toml", slow_scan((dir / "whole").string()));
  write(dir / "killed.toml", slow_scan((dir / "killed").string()));
  const auto whole = run_rupture("scan " + shell_quoted(dir / "whole.toml") + " --jobs 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;

  // SIGKILL (no chance to clean up) in the middle of the second point.
  const auto points = dir / "killed" / "points";
  const auto first = points / "kn_100_bd_0.002";
  const auto second = points / "kn_100_bd_0.004";
  const auto third = points / "kn_316.228_bd_0.002";
  const auto killed = interrupt_scan(dir / "killed.toml", second / "attempt-1" / "run.json", SIGKILL);
  ASSERT_TRUE(killed.has_value()) << "the scan ended before its second point began";
  ASSERT_TRUE(WIFSIGNALED(*killed) && WTERMSIG(*killed) == SIGKILL);
  const std::string first_result = slurp(first / "result.json");
  ASSERT_FALSE(std::filesystem::exists(second / "result.json"))
      << "the second point finished before the kill";

  const auto status_text = run_rupture("scan --status " + shell_quoted(dir / "killed"));
  EXPECT_NE(status_text.out.find("6 points: 1 done, 0 failed, 0 running, 5 pending (1 of them partial"),
            std::string::npos)
      << status_text.out;  // the lock died with the process

  // Restarted, then interrupted again (SIGINT, as Ctrl-C) in the middle of the third point.
  const auto interrupted = interrupt_scan(dir / "killed.toml", third / "attempt-1" / "run.json", SIGINT);
  ASSERT_TRUE(interrupted.has_value()) << "the restarted scan ended before its third point began";
  ASSERT_TRUE(WIFSIGNALED(*interrupted) && WTERMSIG(*interrupted) == SIGINT);
  ASSERT_FALSE(std::filesystem::exists(third / "result.json")) << "the third point finished before SIGINT";
  EXPECT_EQ(nlohmann::json::parse(slurp(second / "result.json"))["attempt"], "attempt-2");

  const auto restarted = run_rupture("scan " + shell_quoted(dir / "killed.toml") + " --jobs 1");
  ASSERT_EQ(restarted.exit_code, 0) << restarted.err;
  EXPECT_NE(restarted.out.find("4 to run"), std::string::npos) << restarted.out;
  EXPECT_EQ(slurp(first / "result.json"), first_result);  // a finished point is never redone
  EXPECT_FALSE(std::filesystem::exists(first / "attempt-2"));
  EXPECT_EQ(physics(dir / "whole" / "results.csv"), physics(dir / "killed" / "results.csv"));
  // Each interrupted point was redone in a fresh attempt folder; the partial one is left apart, unread.
  for (const auto& point : {second, third}) {
    EXPECT_EQ(nlohmann::json::parse(slurp(point / "result.json"))["attempt"], "attempt-2") << point;
    EXPECT_TRUE(std::filesystem::exists(point / "attempt-1"));
    EXPECT_FALSE(std::filesystem::exists(point / "attempt-1" / "analysis.json"));
  }
}

TEST(ScanCommand, ArrayTasksThenCollectGiveTheSameResults) {
  TempDir dir;
  const std::string config = examples + "scan-block.toml";
  const auto whole = run_rupture("scan " + shell_quoted(config) + " -o " + shell_quoted(dir / "whole"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  // Tasks 5, 4, 3 by the option, in any order; the scan folder is [scan] output under the working dir.
  const auto array = dir / "scan-block";
  for (int i = 5; i >= 3; --i) {
    const auto task = run_rupture("scan " + shell_quoted(config) + " -o " + shell_quoted(array) +
                                  " --task-index " + std::to_string(i));
    ASSERT_EQ(task.exit_code, 0) << task.err;
  }
  EXPECT_FALSE(std::filesystem::exists(array / "results.csv"));  // tasks leave the aggregate to --collect
  const auto part = run_rupture("scan --status " + shell_quoted(array));
  EXPECT_NE(part.out.find("6 points: 3 done, 0 failed, 0 running, 3 pending"), std::string::npos) << part.out;
  // Tasks 2, 1, 0 as the example batch script runs them, the index from SLURM_ARRAY_TASK_ID.
  for (int i = 2; i >= 0; --i) {
    const auto task =
        test_support::run_script("scan-array.sbatch", dir.path(),
                                 "SLURM_ARRAY_TASK_ID=" + std::to_string(i) +
                                     " SLURM_CPUS_PER_TASK=1 SCAN_CONFIG=" + shell_quoted(config));
    ASSERT_EQ(task.exit_code, 0) << task.out;
  }
  const auto past =
      run_rupture("scan " + shell_quoted(config) + " -o " + shell_quoted(array) + " --task-index 6");
  EXPECT_EQ(past.exit_code, 2);
  EXPECT_NE(past.err.find("--array=0-5"), std::string::npos) << past.err;
  const auto collect = test_support::run_script("scan-collect.sbatch", dir.path(), "SCAN_FOLDER=scan-block");
  ASSERT_EQ(collect.exit_code, 0) << collect.out;
  EXPECT_NE(collect.out.find("6 points: 6 done"), std::string::npos) << collect.out;
  EXPECT_EQ(physics(dir / "whole" / "results.csv"), physics(array / "results.csv"));
  const auto collected = nlohmann::json::parse(slurp(array / "scan.json"));
  EXPECT_NE(collected.at("collected").at("command").get<std::string>().find("--collect"), std::string::npos);
  EXPECT_EQ(collected.at("points").size(), 6u);
  // Collecting a scan that ran whole keeps that run's record and adds the collection's beside it.
  const auto run_record = nlohmann::json::parse(slurp(dir / "whole" / "scan.json"));
  const auto again = run_rupture("scan --collect " + shell_quoted(dir / "whole"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const auto kept = nlohmann::json::parse(slurp(dir / "whole" / "scan.json"));
  for (const char* key : {"command", "version", "cores", "jobs", "wall_time"})
    EXPECT_EQ(kept.at(key), run_record.at(key)) << key;
  EXPECT_EQ(kept.at("collected").at("version"), rupture::version_string);
}

TEST(ScanCommand, APointHeldByAnotherProcessIsLeftToIt) {
  TempDir dir;
  write(dir / "s.toml", "[scan]\nbase = '" + examples + "block.toml'\noutput = '" + (dir / "out").string() +
                            "'\n[[points]]\nk_n = 100\nb_d = 0.002\n[[points]]\nk_n = 1000\nb_d = 0.002\n");
  // This test process holds the first point's lock as a running scan would.
  const auto held = dir / "out" / "points" / "kn_100_bd_0.002";
  std::filesystem::create_directories(held);
  const int fd = ::open((held / "lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;
  ASSERT_EQ(::fcntl(fd, F_OFD_SETLK, &lock), 0);

  const auto first = run_rupture("scan " + shell_quoted(dir / "s.toml") + " --jobs 2");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_FALSE(std::filesystem::exists(held / "attempt-1"));  // never touched
  ResultsTable table = read_results(dir / "out" / "results.csv");
  EXPECT_EQ(table.text(0, "status"), "running");
  EXPECT_EQ(table.text(1, "status"), "ok");
  const auto busy = run_rupture("scan --status " + shell_quoted(dir / "out"));
  EXPECT_NE(busy.out.find("2 points: 1 done, 0 failed, 1 running, 0 pending"), std::string::npos) << busy.out;

  ::close(fd);  // the holder is gone: the next scan runs the point
  const auto second = run_rupture("scan " + shell_quoted(dir / "s.toml"));
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.out.find("1 to run"), std::string::npos) << second.out;
  table = read_results(dir / "out" / "results.csv");
  EXPECT_EQ(table.text(0, "status"), "ok");
}

TEST(ScanCommand, FailedPointsAreRecordedAndTheScanGoesOn) {
  TempDir dir;
  // A fixed dt that is stable for k_n = 100 N/mm but 5x over the limit for 10^4 N/mm (allowed, so the
  // run goes unstable), and a stop strain below the first break for the third point.
  write(dir / "s.toml", "[scan]\nbase = '" + examples + "block.toml'\noutput = '" + (dir / "out").string() +
                            "'\nset = [\"time.allow_unstable_dt=true\", \"output.interval=10\"]\n"
                            "[[points]]\nk_n = 100\nb_d = 0.002\n[[points]]\nk_n = 1e4\nb_d = 0.002\n"
                            "[[points]]\nk_n = 100\nb_d = 0.5\n[rules]\ndt = 2.5e-7\nramp = \"base\"\n");
  const auto r = run_rupture("scan " + shell_quoted(dir / "s.toml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ResultsTable table = read_results(dir / "out" / "results.csv");
  ASSERT_EQ(table.rows.size(), 3u);
  EXPECT_EQ(table.text(0, "status"), "ok");
  EXPECT_EQ(table.text(1, "status"), "unstable");
  EXPECT_NE(table.text(1, "why").find("unstable"), std::string::npos);
  EXPECT_EQ(*table.number(1, "dt"), 2.5e-7);
  EXPECT_EQ(table.text(1, "stop_reason"), "unstable");  // the failed run's own summary
  EXPECT_GT(*table.number(1, "steps"), 0.0);
  EXPECT_EQ(table.text(2, "status"), "no_separation");
  EXPECT_EQ(table.text(2, "stop_reason"), "max_strain");
  EXPECT_EQ(*table.number(2, "accepted"), 0.0);
  const auto status = run_rupture("scan --status " + shell_quoted(dir / "out"));
  EXPECT_NE(status.out.find("3 points: 1 done, 2 failed"), std::string::npos) << status.out;
}

TEST(ScanCommand, ChangedConfigOnAnOldFolderIsRefused) {
  TempDir dir;
  write(dir / "s.toml", "[scan]\nbase = '" + examples + "block.toml'\noutput = '" + (dir / "out").string() +
                            "'\n[[points]]\nk_n = 100\nb_d = 0.002\n");
  ASSERT_EQ(run_rupture("scan " + shell_quoted(dir / "s.toml")).exit_code, 0);
  write(dir / "s.toml", "[scan]\nbase = '" + examples + "block.toml'\noutput = '" + (dir / "out").string() +
                            "'\nset = [\"loading.speed=100\"]\n[[points]]\nk_n = 100\nb_d = 0.002\n");
  const auto r = run_rupture("scan " + shell_quoted(dir / "s.toml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("different run config"), std::string::npos) << r.err;
}

TEST(ScanCommand, AChangedSampleFileOnAnOldFolderIsRefused) {
  TempDir dir;
  Sample sample = make_cubic_block(4, 8, 2, 0.5);
  save_sample(sample, dir / "block.sample");
  write(dir / "base.toml",
        "[sample]\nfile = 'block.sample'\n[bonds]\nbreak_distance = 0.002\n[loading]\nspeed = 500.0\n"
        "ramp_steps = 500\n[stop]\nmax_strain = 20.0\nseparation_check_interval = 100\n[output]\ninterval = "
        "50\n"
        "[run]\nthreads = 1\n");
  write(dir / "s.toml", "[scan]\nbase = 'base.toml'\noutput = '" + (dir / "out").string() +
                            "'\n[[points]]\nk_n = 100\nb_d = 0.002\n");
  const auto first = run_rupture("scan " + shell_quoted(dir / "s.toml"));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  sample.position[5].x += 1e-9;  // mm: one coordinate, moved by a nanometre
  save_sample(sample, dir / "block.sample");
  const auto r = run_rupture("scan " + shell_quoted(dir / "s.toml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("this point was computed on another sample (fingerprint "), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace rupture::scan
