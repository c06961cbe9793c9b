#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/tool.hpp"

namespace rupture {
namespace {

using ::testing::HasSubstr;
using testing::run_rupture;
using testing::slurp;
using testing::TempDir;

// The default study must find the paper's result on its own sample: an energy-rate maximum before
// the force maximum, with a 95 % interval of delta_x that excludes zero.
TEST(Study, DefaultStudyFindsThePrecursorBeforeFailure) {
  TempDir tmp;
  const auto out = tmp / "study";
  const auto r = run_rupture("study --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // The last line says where the report is and what the precursor was.
  const auto html = std::filesystem::absolute(out / "run" / "report.html").lexically_normal();
  EXPECT_THAT(r.out, HasSubstr("report: " + html.string() + "; precursor: x_p = "));
  for (const char* file : {"study.toml", "sample.rsample", "run/curves.csv", "run/breaks.csv", "run/run.json",
                           "run/analysis.json", "run/figures/loading.png", "run/figures/loading.gp",
                           "run/figures/snapshots.png", "run/report.html"}) {
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
