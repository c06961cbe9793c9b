// `rupture fbm` end to end: JSON and table output, CSV curves readable as loading curves, the
// simulate outputs, and bad input rejected with exit code 2 and one line naming the fix.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/csv.hpp"
#include "support/json_convention.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;
using testing::run_rupture;
using testing::TempDir;

void write(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(FbmCli, TheoryJsonHasEveryKeyAndNullWhereUndefined) {
  const auto r = run_rupture("fbm theory --dist uniform --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_THAT(testing::json_convention_breaches(j), ::testing::IsEmpty());
  for (const char* key :
       {"x_c", "F_c", "x_m", "E_max", "x_p", "Erate_max", "delta_x", "Gamma", "A_r", "E_d_at_x_c"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["x_c"].get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(j["A_r"].get<double>(), 4.0 / 3.0, 1e-12);
  EXPECT_EQ(j["dist"], "uniform:a=0,b=1");
  EXPECT_TRUE(j.contains("version"));
  const auto brittle = nlohmann::json::parse(run_rupture("fbm theory --dist uniform:a=0.6,b=1 --json").out);
  EXPECT_TRUE(brittle["Gamma"].is_null());
  EXPECT_TRUE(brittle["Erate_max_at_cutoff"].get<bool>());
}

TEST(FbmCli, TheoryTableSaysWhenTheMaximumSitsOnTheCutoff) {
  const auto r = run_rupture("fbm theory --dist uniform:a=0.25,b=1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("per N kappa = 1"));
  EXPECT_THAT(r.out, HasSubstr("supremum"));
}

TEST(FbmCli, BadDistributionSpecsExitWithTwoAndOneLine) {
  TempDir dir;
  write(dir / "empty.txt", "# nothing measured\n");
  write(dir / "words.txt", "0.1\nzero point two\n");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"foo", "unknown distribution 'foo'"},
      {"powerlaw:alpha=-1", "alpha > -1"},
      {"weibull:k=0", "k > 0"},
      {"file:" + (dir / "empty.txt").string(), "no thresholds"},
      {"file:" + (dir / "words.txt").string(), "words.txt:2: 'zero point two' is not a number"},
  };
  for (const auto& [spec, message] : cases) {
    for (const char* sub : {"theory", "simulate --fibers 10"}) {
      const auto r = run_rupture(std::string("fbm ") + sub + " --dist '" + spec + "'");
      EXPECT_EQ(r.exit_code, 2) << spec;
      EXPECT_THAT(r.err, HasSubstr(message)) << spec;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
  }
  const auto lls_strain = run_rupture("fbm simulate --fibers 10 --sharing lls --control strain");
  EXPECT_EQ(lls_strain.exit_code, 2);
  EXPECT_THAT(lls_strain.err, HasSubstr("--control load"));
}

TEST(FbmCli, CurvesAreLoadingCurvesWithUnitsAndBalancedWork) {
  TempDir dir;
  const auto r =
      run_rupture("fbm curves --dist weibull:k=2 --points 4001 --out '" + (dir / "c.csv").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto table = io::read_csv(dir / "c.csv");
  ASSERT_EQ(table.rows(), 4001u);
  EXPECT_EQ(table.header[0], "strain[1]");
  EXPECT_THAT(table.comments[0], HasSubstr("rupture"));
  const auto& x = table.column("strain");
  const auto& F = table.column("force");
  const auto& E = table.column("elastic_energy");
  const auto& D = table.column("damage_energy");
  double work = 0;
  for (std::size_t i = 1; i < x.size(); ++i) work += 0.5 * (F[i] + F[i - 1]) * (x[i] - x[i - 1]);
  EXPECT_NEAR(work, E.back() + D.back(), 1e-6);
}

// "-" is standard output: the same CSV a file would get, and nothing written beside it.
TEST(FbmCli, CurvesToStdoutEqualTheFile) {
  TempDir dir;
  const auto file =
      run_rupture("fbm curves --dist uniform --points 11 -o '" + (dir / "c.csv").string() + "'");
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const auto piped = run_rupture("fbm curves --dist uniform --points 11 -o -");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.out, testing::slurp(dir / "c.csv"));
}

TEST(FbmCli, SimulateWritesCurveBurstsAndSummary) {
  TempDir dir;
  const auto out = dir / "run.csv";
  const auto r = run_rupture("fbm simulate --fibers 100000 --seed 5 --control load --points 501 --out '" +
                             out.string() + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto curve = io::read_csv(out);
  EXPECT_EQ(curve.rows(), 501u);
  for (const char* column :
       {"strain", "force", "elastic_energy", "damage_energy", "energy_rate", "broken_fraction"})
    EXPECT_TRUE(curve.find(column).has_value()) << column;
  const auto bursts = io::read_csv(dir / "run_bursts.csv");
  EXPECT_EQ(bursts.column("size").front(), 1.0);
  const auto summary = nlohmann::json::parse(r.out);  // --json: the summary on stdout, nothing else
  EXPECT_THAT(testing::json_convention_breaches(summary), ::testing::IsEmpty());
  EXPECT_EQ(summary["inputs"]["fibers"], 100000);
  EXPECT_EQ(summary["inputs"]["seed"], 5);
  EXPECT_TRUE(summary["x_m"].is_null());
  EXPECT_NEAR(summary["F_c"].get<double>(), 0.25, 0.01);
  // Same seed, same bundle, same bytes.
  const auto again = run_rupture("fbm simulate --fibers 100000 --seed 5 --control load --points 501 --out '" +
                                 (dir / "again.csv").string() + "'");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(testing::slurp(out), testing::slurp(dir / "again.csv"));
}

TEST(FbmCli, EmpiricalThresholdsFromAFile) {
  TempDir dir;
  write(dir / "t.txt", "# four fibers\n0.4\n0.1\n0.5\n0.3\n");
  const auto r = run_rupture("fbm theory --json --dist 'file:" + (dir / "t.txt").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(j["x_c"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(j["F_c"].get<double>(), 0.225);
}

}  // namespace
}  // namespace rupture
