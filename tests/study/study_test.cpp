#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "figures/scan_fixture.hpp"
#include "scan/results.hpp"
#include "support/browser.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;
using testing::run_rupture;
using testing::slurp;
using testing::TempDir;

// The default study must find the paper's result on its own sample: an energy-rate maximum before
// the force maximum, with a 95 % interval of delta_x that excludes zero; and its scan of the same
// tissue must give figures 15-17 from real runs in one report that a browser shows whole.
TEST(Study, DefaultStudyFindsThePrecursorBeforeFailureAndScansTheTissue) {
  TempDir tmp;
  const auto out = tmp / "study";
  const auto r = run_rupture("study --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // The last line says where the report is and what the precursor was.
  const auto html = std::filesystem::absolute(out / "report.html").lexically_normal();
  EXPECT_THAT(r.out, HasSubstr("report: " + html.string() + "; precursor: x_p = "));
  for (const char* file :
       {"study.toml", "scan.toml", "sample.rsample", "run/curves.csv", "run/breaks.csv", "run/run.json",
        "run/analysis.json", "run/figures/loading.png", "run/figures/loading.gp", "run/figures/snapshots.png",
        "scan/results.csv", "scan/scan.json", "scan/figures/mechanism_map.png",
        "scan/figures/delay_vs_critical.png", "scan/figures/energy_ratio_vs_critical.png", "report.html"}) {
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  }
  const auto analysis = nlohmann::json::parse(slurp(out / "run/analysis.json"));
  ASSERT_TRUE(analysis.at("accepted").get<bool>());
  const double x_p = analysis.at("x_p").at("value").get<double>();
  const double x_c = analysis.at("x_c").at("value").get<double>();
  EXPECT_GT(x_p, 0.0);
  EXPECT_LT(x_p, x_c);
  const auto ci95 = analysis.at("delta_x").at("ci95");
  EXPECT_GT(ci95.at(0).get<double>(), 0.0) << "the 95 % interval of delta_x must exclude zero";
  const auto run = nlohmann::json::parse(slurp(out / "run/run.json"));
  EXPECT_EQ(run.at("status"), "finished");

  // The scan: nine points of k_n x b_d, every one separated; most accepted, each with delta_x > 0.
  const auto scan = nlohmann::json::parse(slurp(out / "scan/scan.json"));
  const auto results = scan::read_results(out / "scan/results.csv");
  ASSERT_EQ(results.rows.size(), 9u);
  std::size_t accepted = 0;
  for (std::size_t row = 0; row < results.rows.size(); ++row) {
    EXPECT_EQ(results.text(row, "status"), "ok") << results.text(row, "why");
    if (results.number(row, "accepted").value_or(0.0) != 1.0) continue;
    ++accepted;
    EXPECT_GT(*results.number(row, "delta_x"), 0.0) << "point " << row;
  }
  EXPECT_GE(accepted, 6u);

  // One page: the run's loading curves and the scan's figure 16 side by side, six figures in all,
  // the claims table, the monitor's outcome; and a headless browser decodes every picture.
  const std::string page = slurp(out / "report.html");
  EXPECT_THAT(page, HasSubstr("<div class=\"row\">\n<figure><img alt=\"loading\""));
  EXPECT_THAT(page, HasSubstr("<figure><img alt=\"delay_vs_critical\""));
  EXPECT_THAT(page, HasSubstr("claims against this scan"));
  EXPECT_THAT(page, HasSubstr("The monitor warned at strain"));
  ASSERT_TRUE(testing::have_chromium()) << "chromium is missing: scripts/bootstrap installs it";
  const auto dom = testing::chromium(out / "report.html", tmp / "browser", "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_THAT(dom.dom, HasSubstr("data-figures=\"6 of 6 loaded\""));
  EXPECT_THAT(testing::console_lines(dom.log), ::testing::IsEmpty());
}

// --no-scan runs the single run only, and a scan an earlier study left in the folder is removed
// rather than shown as this study's.
TEST(Study, NoScanLeavesNoScanBehind) {
  TempDir tmp;
  const auto out = tmp / "study";
  testing::write_scan_fixture(out / "scan");
  const auto r = run_rupture("study --out '" + out.string() + "' --no-scan");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("[4/4] figures and report"));
  EXPECT_FALSE(std::filesystem::exists(out / "scan"));
  const std::string page = slurp(out / "report.html");
  EXPECT_THAT(page, HasSubstr("No scan in this study"));
  EXPECT_THAT(page, ::testing::Not(HasSubstr("delay_vs_critical")));
}

TEST(Study, BadOverrideIsRejectedBeforeAnythingRuns) {
  TempDir tmp;
  const auto out = tmp / "study";
  const auto r = run_rupture("study --out '" + out.string() + "' --set bonds.stiffness=-1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bonds.stiffness"));
  EXPECT_FALSE(std::filesystem::exists(out / "run"));
}

}  // namespace
}  // namespace rupture
