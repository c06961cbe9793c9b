// `rupture analyze` and `rupture monitor` end to end: exit codes (0 accepted, 4 rejected, 2 bad
// input), analysis.json with units, and messages that name the file, line and column.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "analysis/analysis.hpp"
#include "calibration_set.hpp"
#include "fbm/power_law.hpp"
#include "support/json_convention.hpp"
#include "support/tool.hpp"
#include "synthetic_curves.hpp"

namespace rupture::analysis {
namespace {

using rupture::testing::run_rupture;
using rupture::testing::slurp;
using rupture::testing::TempDir;

// Writes a curve as CSV with the given header names (units included).
void write_curve(const std::filesystem::path& file, const Curve& c, const std::string& header) {
  std::ofstream out(file);
  out << "# synthetic curve\n" << header << "\n";
  out.precision(17);
  for (std::size_t i = 0; i < c.strain.size(); ++i)
    out << c.strain[i] << "," << c.force[i] << "," << c.energy[i] << "\n";
}

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// White noise at 10^-6 (0.0004 % of F's peak, 0.25) reads as white over the whole record and is
// quiet: the terminal says whose factors its intervals take and why, as analysis.json does.
TEST(AnalyzeCli, AQuietCurvesIntervalsSayTheyAreSizedForARandomWalk) {
  TempDir dir;
  auto c = testing::power_law_curve(0.0, 2001);
  testing::add_noise(c, 1e-6, 1e-7, 5);
  write_curve(dir / "curve.csv", c, "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("analyze " + quoted(dir / "curve.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(
      r.out.find("noise       F white, E_e white (over the whole record); intervals sized for a random walk "
                 "(quiet: white noise below 0.05 % of the peaks)\n"),
      std::string::npos)
      << r.out;
  const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
  EXPECT_TRUE(j["x_c"]["interval_scales"]["quiet"].get<bool>());
  EXPECT_EQ(j["x_c"]["interval_scales"]["noise"], "random walk");
}

// --rows says what a file's rows hold where its columns cannot: the same file read as instants by
// default and as interval means when told, the walk then read larger (its own term, (2L − 1) σ_r²);
// a word that names no kind of row is refused.
TEST(AnalyzeCli, RowsThatAreIntervalMeansAreReadSoWhenTold) {
  TempDir dir;
  const Curve c = calibration::run_like_curve(calibration::weibull(3), 10000, {200, true, 0.0, false}, 3);
  write_curve(dir / "means.csv", c, "strain[1],force[1],elastic_energy[1]");
  const auto as_instants =
      run_rupture("analyze " + quoted(dir / "means.csv") + " -o " + quoted(dir / "i.json"));
  const auto as_means = run_rupture("analyze " + quoted(dir / "means.csv") + " --rows interval-means -o " +
                                    quoted(dir / "m.json"));
  ASSERT_EQ(as_instants.exit_code, 0) << as_instants.out << as_instants.err;
  ASSERT_EQ(as_means.exit_code, 0) << as_means.out << as_means.err;
  const auto i = nlohmann::json::parse(slurp(dir / "i.json")),
             m = nlohmann::json::parse(slurp(dir / "m.json"));
  EXPECT_EQ(i["resample"]["rows"], "instants");
  EXPECT_EQ(m["resample"]["rows"], "interval-means");
  const auto walk = [](const nlohmann::json& j) {
    return j["uncertainty"]["noise"]["elastic_energy"]["walk_step_sd"]["value"].get<double>();
  };
  EXPECT_GT(walk(m), 1.05 * walk(i));
  const auto wrong = run_rupture("analyze " + quoted(dir / "means.csv") + " --rows means");
  EXPECT_EQ(wrong.exit_code, 2);
  EXPECT_NE(wrong.err.find("--rows"), std::string::npos) << wrong.err;
}

// A uniform bundle's curve that falls by e every 3 rows from 1.05 x_c on, with E_e's white noise at
// 0.05 % of its top, below the levels x_p's white factors follow: the curve is cut by a collapse, on
// which no factors follow a level, so the terminal names the collapse (a warning) and no level.
TEST(AnalyzeCli, ACurveCutByACollapseGetsNoNoiseLevelNote) {
  TempDir dir;
  auto c = testing::power_law_curve(0.0, 1001);
  const double step = c.strain[1] - c.strain[0], cut = 1.05 * 0.5;
  std::size_t held = 0;
  while (c.strain[held + 1] <= cut) ++held;
  for (std::size_t i = held + 1; i < c.strain.size(); ++i) {
    const double fall = std::exp(-(c.strain[i] - c.strain[held]) / (3.0 * step));
    c.force[i] = c.force[held] * fall;
    c.energy[i] = c.energy[held] * fall;
  }
  testing::add_noise(c, 0.005, 3e-5, 5);
  write_curve(dir / "curve.csv", c, "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("analyze " + quoted(dir / "curve.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
  ASSERT_TRUE(j["collapse_onset"].is_object()) << r.out;
  EXPECT_LT(j["x_p"]["interval_scales"]["energy_white_share"].get<double>(),
            precursor_white_levels.calibrated_from);
  EXPECT_NE(r.err.find("collapse too sharp for the filter"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("factors are calibrated for"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("not calibrated"), std::string::npos) << r.out;
}

// --force-peak-form corner: recorded with the inputs, the force's fit named as a corner, x_c moved onto it
// (a dem-like curve: Weibull k = 3, x_c 0.6118, the cubic's 0.603); an unknown form is refused.
TEST(AnalyzeCli, ForcePeakFormCornerIsRecordedAndMovesX_cOntoTheCorner) {
  using namespace calibration;
  TempDir dir;
  const NoiseGroup group = dem_like_group(200, true);
  const auto set = calibration_set("tuning");  // CalibrationCase refers to its shape
  const auto curve_case = CalibrationCase::at(set, 1);
  write_curve(dir / "curve.csv", curve_case.draw(group), "strain[1],force[1],elastic_energy[1]");
  const double x_c = run_like_truth(curve_case.shape, curve_case.seed, group.run).x_c;
  const auto smooth =
      run_rupture("analyze " + quoted(dir / "curve.csv") + " -o " + quoted(dir / "smooth.json"));
  const auto corner = run_rupture("analyze " + quoted(dir / "curve.csv") + " -o " +
                                  quoted(dir / "corner.json") + " --force-peak-form corner");
  ASSERT_EQ(smooth.exit_code, 0) << smooth.out << smooth.err;
  ASSERT_EQ(corner.exit_code, 0) << corner.out << corner.err;
  const auto s = nlohmann::json::parse(slurp(dir / "smooth.json"));
  const auto c = nlohmann::json::parse(slurp(dir / "corner.json"));
  EXPECT_EQ(s["inputs"]["force_peak_form"], "smooth");
  EXPECT_EQ(c["inputs"]["force_peak_form"], "corner");
  EXPECT_EQ(s["peak_fits"]["force"]["form"], "cubic");
  // Its F rings and E_e does not: F's walk step was taken from E_e's, and the file says so.
  const auto& noise = s["uncertainty"]["noise"];
  EXPECT_GE(noise["force"]["ringing_block"]["value"].get<double>(), 2.0);
  EXPECT_TRUE(noise["force"]["walk_from_energy"].get<bool>());
  EXPECT_FALSE(noise["elastic_energy"]["walk_from_energy"].get<bool>());
  EXPECT_EQ(c["peak_fits"]["force"]["form"], "corner");
  EXPECT_LT(s["x_c"]["value"].get<double>(), x_c - 0.01 * x_c);
  EXPECT_NEAR(c["x_c"]["value"].get<double>(), x_c, 0.005 * x_c);
  const auto bad = run_rupture("analyze " + quoted(dir / "curve.csv") + " --force-peak-form sharp");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--force-peak-form"), std::string::npos) << bad.err;
}

// --smoothing-floor 0.25 strengthens the filter of a run-like curve at rows every 100 steps; the default
// (0) leaves it to the noise alone; both runs say what they did (docs/analysis.md, "The smoothing
// floor").
TEST(AnalyzeCli, SmoothingFloorIsRecordedAndStrengthensTheFilterWhereAskedFor) {
  using namespace calibration;
  TempDir dir;
  const NoiseGroup group = dem_like_group(100, false);
  const auto set = calibration_set("tuning");
  write_curve(dir / "curve.csv", CalibrationCase::at(set, 3).draw(group),
              "strain[1],force[1],elastic_energy[1]");
  const auto floored = run_rupture("analyze " + quoted(dir / "curve.csv") + " -o " +
                                   quoted(dir / "floored.json") + " --smoothing-floor 0.25");
  const auto alone =
      run_rupture("analyze " + quoted(dir / "curve.csv") + " -o " + quoted(dir / "alone.json"));
  ASSERT_EQ(floored.exit_code, 0) << floored.out << floored.err;
  ASSERT_EQ(alone.exit_code, 0) << alone.out << alone.err;
  const auto f = nlohmann::json::parse(slurp(dir / "floored.json"));
  const auto a = nlohmann::json::parse(slurp(dir / "alone.json"));
  EXPECT_EQ(f["inputs"]["smoothing_floor_share"], 0.25);
  EXPECT_EQ(a["inputs"]["smoothing_floor_share"], 0.0);
  EXPECT_TRUE(f["filter"]["smoothing_floor_applied"].get<bool>());
  EXPECT_FALSE(a["filter"]["smoothing_floor_applied"].get<bool>());
  EXPECT_LT(f["filter"]["cutoff_nyquist"].get<double>(), 0.25 * a["filter"]["cutoff_nyquist"].get<double>());
  const auto bad = run_rupture("analyze " + quoted(dir / "curve.csv") + " --smoothing-floor 1.5");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--smoothing-floor"), std::string::npos) << bad.err;
}

TEST(AnalyzeCli, FbmCurveIsAcceptedAndWritesAnalysisJsonWithUnits) {
  TempDir dir;
  auto c = testing::power_law_curve(0.0, 2001);
  testing::add_noise(c, 0.002, 1e-5, 5);
  write_curve(dir / "curve.csv", c, "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("analyze " + quoted(dir / "curve.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("accepted"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
  EXPECT_TRUE(rupture::testing::json_convention_breaches(j).empty())
      << nlohmann::json(rupture::testing::json_convention_breaches(j)).dump();
  EXPECT_TRUE(j["accepted"].get<bool>());
  EXPECT_EQ(j["x_c"]["unit"], "1");
  EXPECT_NEAR(j["x_c"]["value"].get<double>(), 0.5, 0.01);
  EXPECT_NEAR(j["delta_x"]["value"].get<double>(), 1.0 / 6.0, 0.005);
  EXPECT_GT(j["delta_x"]["error"].get<double>(), 0.0);
  EXPECT_EQ(j["delta_x"]["method"], "fitted-maxima");
  // White noise: the intervals carry the white-noise factors, and the 95 % one holds the 68 % one.
  EXPECT_NE(
      r.out.find("noise       F white, E_e white (over the whole record); intervals sized for white noise\n"),
      std::string::npos)
      << r.out;
  EXPECT_EQ(j["delta_x"]["interval_scales"]["noise"], "white");
  // E_e's white noise here is ~0.01 % of E_max, below the range x_p's white factors were checked on:
  // x_p's interval is ± sd, not calibrated, and analysis.json and the terminal say at which level and
  // which range is calibrated.
  const double share = j["x_p"]["interval_scales"]["energy_white_share"].get<double>();
  EXPECT_GT(share, 0.5e-4);
  EXPECT_LT(share, precursor_white_levels.calibrated_from);
  EXPECT_FALSE(j["x_p"]["interval_scales"]["calibrated"].get<bool>());
  EXPECT_EQ(j["x_p"]["interval_scales"]["ci68"].get<double>(), 1.0);
  EXPECT_NE(r.out.find("x_p's factors are calibrated for 0.17-3.2 %"), std::string::npos) << r.out;
  // δ_x's level is the larger of F's and E_e's white noise, ~0.8 % here (F's), as is x_c's (F's):
  // both within the range their white factors were checked on: both calibrated.
  EXPECT_GT(j["delta_x"]["interval_scales"]["white_share"].get<double>(), 0.002);
  EXPECT_EQ(j["x_c"]["interval_scales"]["force_white_share"].get<double>(),
            j["delta_x"]["interval_scales"]["white_share"].get<double>());
  EXPECT_TRUE(j["delta_x"]["interval_scales"]["calibrated"].get<bool>());
  EXPECT_TRUE(j["x_c"]["interval_scales"]["calibrated"].get<bool>());
  EXPECT_EQ(j["delta_x"]["interval_scales"]["ci68"].get<double>(), delta_interval_scales.white_noise.level68);
  EXPECT_EQ(j["delta_x"]["interval_scales"]["ci95"].get<double>(), delta_interval_scales.white_noise.level95);
  EXPECT_LE(j["delta_x"]["ci95"][0].get<double>(), j["delta_x"]["ci68"][0].get<double>());
  EXPECT_GE(j["delta_x"]["ci95"][1].get<double>(), j["delta_x"]["ci68"][1].get<double>());
  EXPECT_LT(j["delta_x"]["ci68"][0].get<double>(), j["delta_x"]["value"].get<double>());
  EXPECT_GT(j["delta_x"]["ci68"][1].get<double>(), j["delta_x"]["value"].get<double>());
  const auto& sampled = j["delta_x"]["sampling_distribution"];
  EXPECT_GT(sampled["delta"]["value"].size(), 10u);
  EXPECT_EQ(sampled["delta"]["value"].size(), sampled["density"]["value"].size());
  EXPECT_EQ(sampled["delta"]["unit"], "1");
  EXPECT_EQ(sampled["density"]["unit"], "1");
  EXPECT_EQ(j["uncertainty"]["replicates"], 200);
  EXPECT_EQ(j["filter"]["kind"], "butterworth");
  EXPECT_TRUE(j.contains("version"));
  EXPECT_EQ(j["inputs"]["curves"], (dir / "curve.csv").string());
}

TEST(AnalyzeCli, DemStyleColumnsAndUnitsAreRecognised) {
  TempDir dir;
  auto c = testing::power_law_curve(2.0, 1001, 1.2);
  for (auto& x : c.strain) x *= 10.0;  // a curve in %
  write_curve(dir / "curves.csv", c, "strain[%],force_top[N],elastic_energy[mJ]");
  const auto r = run_rupture("analyze " + quoted(dir / "curves.csv") + " -o " + quoted(dir / "out.json"));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(slurp(dir / "out.json"));
  EXPECT_EQ(j["x_c"]["unit"], "%");
  EXPECT_EQ(j["F_c"]["unit"], "N");
  EXPECT_EQ(j["E_max"]["unit"], "mJ");
  EXPECT_EQ(j["Erate_max"]["unit"], "mJ/%");
  EXPECT_NEAR(j["x_c"]["value"].get<double>(), 10.0 * std::pow(0.25, 1.0 / 3.0), 1e-3);
}

TEST(AnalyzeCli, OtherTablesByNamingColumnsWithScales) {
  TempDir dir;
  const auto c = testing::power_law_curve(0.0, 1001);
  write_curve(dir / "lab.csv", c, "elongation[mm],load[kN],work[J]");
  const auto missing = run_rupture("analyze " + quoted(dir / "lab.csv"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no column 'strain'"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("--strain"), std::string::npos) << missing.err;
  const auto r =
      run_rupture("analyze " + quoted(dir / "lab.csv") +
                  " --strain elongation --force load --energy work --strain-scale 4 --strain-unit %");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
  EXPECT_EQ(j["x_c"]["unit"], "%");
  EXPECT_NEAR(j["x_c"]["value"].get<double>(), 2.0, 1e-3);
  EXPECT_EQ(j["F_c"]["unit"], "kN");
}

TEST(AnalyzeCli, TextInANumberFieldNamesLineAndColumn) {
  TempDir dir;
  std::ofstream(dir / "bad.csv") << "strain[1],force[1],elastic_energy[1]\n0,0,0\n0.1,abc,0.01\n";
  const auto r = run_rupture("analyze " + quoted(dir / "bad.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.csv:3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("column 2 ('force[1]')"), std::string::npos) << r.err;
}

TEST(AnalyzeCli, TooFewPointsForTheFilterIsBadInput) {
  TempDir dir;
  write_curve(dir / "short.csv", testing::power_law_curve(0.0, 12), "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("analyze " + quoted(dir / "short.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("12 data rows, the analysis needs at least"), std::string::npos) << r.err;
}

TEST(AnalyzeCli, MultiPeakedCurveIsRejectedWithExitCode4) {
  TempDir dir;
  auto c = testing::power_law_curve(0.0, 2001);
  for (std::size_t i = 0; i < c.strain.size(); ++i) {
    const double x = c.strain[i];
    c.force[i] = std::exp(-std::pow((x - 0.3) / 0.05, 2)) + std::exp(-std::pow((x - 0.6) / 0.05, 2));
  }
  write_curve(dir / "two.csv", c, "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("analyze " + quoted(dir / "two.csv"));
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_NE(r.err.find("rejected: several force maxima"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
  EXPECT_FALSE(j["accepted"].get<bool>());
  EXPECT_NE(j["rejection"].get<std::string>().find("several force maxima"), std::string::npos);
}

// -o -: analysis.json on standard output (the whole of it), the text summary on stderr.
TEST(AnalyzeCli, DashWritesTheDocumentToStdout) {
  TempDir dir;
  write_curve(dir / "curve.csv", testing::power_law_curve(2.0, 2001), "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("analyze " + quoted(dir / "curve.csv") + " -o -");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["tool"], "rupture analyze");
  EXPECT_TRUE(j["accepted"].get<bool>());
  EXPECT_NE(r.err.find("wrote the document to standard output"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "analysis.json"));
}

TEST(MonitorCli, WarnsFromStdinBeforeCriticalStrain) {
  TempDir dir;
  write_curve(dir / "curve.csv", testing::power_law_curve(2.0, 2001), "strain[1],force[1],elastic_energy[1]");
  const auto r = run_rupture("monitor", (dir / "curve.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("WARNING at strain"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("x_c prediction held"), std::string::npos) << r.out;
  // --json: the same outcome as one JSON document on stdout, the live warning on stderr.
  const auto as_json = run_rupture("monitor --json", (dir / "curve.csv").string());
  ASSERT_EQ(as_json.exit_code, 0) << as_json.err;
  EXPECT_NE(as_json.err.find("WARNING at strain"), std::string::npos) << as_json.err;
  const auto j = nlohmann::json::parse(as_json.out);
  EXPECT_TRUE(rupture::testing::json_convention_breaches(j).empty())
      << nlohmann::json(rupture::testing::json_convention_breaches(j)).dump();
  EXPECT_LT(j["warning"]["strain"]["value"].get<double>(), std::pow(0.25, 1.0 / 3.0));
  EXPECT_EQ(j["warning"]["strain"]["unit"], "1");
  EXPECT_EQ(j["warning"]["x_c_predicted"]["value"].size(), 2u);
  EXPECT_TRUE(j["x_c_held"].get<bool>());
  EXPECT_GT(j["lead"]["value"].get<double>(), 0.0);
}

TEST(MonitorCli, FollowsAGrowingFile) {
  TempDir dir;
  const auto c = testing::power_law_curve(2.0, 1201);
  const auto file = dir / "curves.csv";
  std::ofstream(file) << "strain[1],force[1],elastic_energy[1]\n";
  // A writer appends rows in bursts while the monitor follows the file.
  std::thread writer([&] {
    for (std::size_t i = 0; i < c.strain.size(); ++i) {
      std::ofstream out(file, std::ios::app);
      out.precision(17);
      out << c.strain[i] << "," << c.force[i] << "," << c.energy[i] << "\n";
      if (i % 200 == 199) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  const auto r = run_rupture("monitor " + quoted(file) + " --follow --idle-timeout 1 --poll 10");
  writer.join();
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1201 samples read"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("WARNING at strain"), std::string::npos) << r.out;
}

// A followed file that is cut back and rewritten, or replaced by another file of its name (an
// editor's save, a rerun into the same folder), restarts the curve instead of mixing two.
TEST(MonitorCli, FollowStartsOverWhenTheFileIsTruncatedOrReplaced) {
  const auto c = testing::power_law_curve(2.0, 1201);
  const auto rows = [&](std::ostream& out, std::size_t from, std::size_t to) {
    out.precision(17);
    for (std::size_t i = from; i < to; ++i)
      out << c.strain[i] << "," << c.force[i] << "," << c.energy[i] << "\n";
  };
  for (const bool replace : {false, true}) {
    SCOPED_TRACE(replace ? "replaced" : "truncated");
    TempDir dir;
    const auto file = dir / "curves.csv";
    {
      std::ofstream out(file);
      out << "strain[1],force[1],elastic_energy[1]\n";
      rows(out, 0, 500);  // the first attempt's rows
    }
    // The pauses leave the monitor time to start and read the first rows: 300 ms was too short
    // for a sanitizer build on a loaded machine, which then never saw the file shrink.
    std::thread writer([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(1500));
      if (replace) {
        std::ofstream out(dir / "new.csv");
        out << "strain[1],force[1],elastic_energy[1]\n";
        out.close();
        std::filesystem::rename(dir / "new.csv", file);
      } else {
        std::ofstream(file, std::ios::trunc) << "strain[1],force[1],elastic_energy[1]\n";
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      std::ofstream out(file, std::ios::app);
      rows(out, 0, c.strain.size());
    });
    const auto r = run_rupture("monitor " + quoted(file) + " --follow --idle-timeout 3 --poll 10");
    writer.join();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(replace ? "the file was replaced; reading it again from the start"
                                 : "the file was truncated; reading it again from the start"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1201 samples read"), std::string::npos) << r.out;
  }
}

// The monitor reads with the same reader as analyze: a LAMMPS `fix print` file, space separated,
// its header the last '#' line.
TEST(MonitorCli, ReadsWhitespaceSeparatedFilesWithTheHeaderInAComment) {
  TempDir dir;
  const auto c = testing::power_law_curve(2.0, 1201);
  {
    std::ofstream out(dir / "print.txt");
    out.precision(17);
    out << "# Fix print output for fix 2\n# strain force elastic_energy\n";
    for (std::size_t i = 0; i < c.strain.size(); ++i)
      out << c.strain[i] << " " << c.force[i] << " " << c.energy[i] << "\n";
  }
  const auto r = run_rupture("monitor " + quoted(dir / "print.txt"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1201 samples read"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("x_c prediction held"), std::string::npos) << r.out;
}

TEST(MonitorCli, TextInANumberFieldNamesLineAndColumn) {
  TempDir dir;
  std::ofstream(dir / "bad.csv") << "# comment\nstrain[1],force[1],elastic_energy[1]\n0,0,0\n0.1,0.1,x\n";
  const auto r = run_rupture("monitor " + quoted(dir / "bad.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.csv:4"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("column 3 ('elastic_energy[1]')"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rupture::analysis

namespace rupture::analysis {
namespace {

// Finite bundles from `rupture fbm simulate` analysed end to end: accepted, maxima near the ELS
// values (finite-N fluctuations of 10^5 fibers are ~1e-3), δ_x within the model's few-% bias.
TEST(AnalyzeCli, FbmSimulateOutputEndToEnd) {
  TempDir dir;
  for (double alpha : {0.0, 2.0}) {
    const auto expected = fbm::power_law::maxima(alpha);
    const auto curve = dir / ("bundle_" + std::to_string(static_cast<int>(alpha)) + ".csv");
    const auto sim =
        run_rupture("fbm simulate --dist " + std::string(alpha == 0.0 ? "uniform" : "powerlaw:alpha=2") +
                    " --fibers 100000 --seed 7 --out " + quoted(curve));
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
    // A finite bundle's noise is a random walk (fibers break one by one): nearly invisible in E_e
    // but white in ℰ, which the automatic cutoff (set from F and E_e) does not see; name the cutoff
    // (docs/analysis.md, "Known limits").
    const auto r =
        run_rupture("analyze " + quoted(curve) + " --cutoff 0.03 -o " + quoted(dir / "analysis.json"));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
    EXPECT_NEAR(j["x_c"]["value"].get<double>(), expected.x_c, 0.005) << alpha;
    EXPECT_NEAR(j["x_p"]["value"].get<double>(), expected.x_p, 0.02) << alpha;
    EXPECT_NEAR(j["x_m"]["value"].get<double>(), expected.x_m, 0.005) << alpha;
    EXPECT_NEAR(j["delta_x"]["value"].get<double>(), expected.delta_x, 0.05 * expected.delta_x) << alpha;
    EXPECT_NEAR(j["A_r"]["value"].get<double>(), expected.A_r, 0.05 * expected.A_r) << alpha;
    // The monitor replayed on the same file warns before x_c.
    const auto m = run_rupture("monitor " + quoted(curve) + " --json");
    ASSERT_EQ(m.exit_code, 0) << m.err;
    const auto w = nlohmann::json::parse(m.out);
    ASSERT_FALSE(w["warning"].is_null()) << m.out;
    EXPECT_LT(w["warning"]["strain"]["value"].get<double>(), w["x_c_observed"]["value"].get<double>())
        << alpha;
  }
}

// A finite bundle's noise is a random walk: by default the bootstrap's steps follow the curve's
// breaks and the intervals carry that profile's factors; --no-walk-profile takes one stationary step
// and the bootstrap's own intervals. Both choices are written to analysis.json.
TEST(AnalyzeCli, WalkProfileIsTheDefaultOnRandomWalkNoiseAndCanBeTurnedOff) {
  TempDir dir;
  const auto curve = dir / "bundle.csv";
  ASSERT_EQ(
      run_rupture("fbm simulate --dist uniform --fibers 100000 --seed 7 --out " + quoted(curve)).exit_code,
      0);
  std::map<std::string, std::string> printed;
  const auto analysed = [&](const std::string& switches, const std::string& name) {
    const auto r = run_rupture("analyze " + quoted(curve) + switches + " -o " + quoted(dir / name));
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    printed[name] = r.out;
    return nlohmann::json::parse(slurp(dir / name));
  };
  const auto profiled = analysed("", "profiled.json");
  const auto stationary = analysed(" --no-walk-profile", "stationary.json");
  EXPECT_TRUE(profiled["inputs"]["walk_profile"].get<bool>());
  EXPECT_FALSE(stationary["inputs"]["walk_profile"].get<bool>());
  for (const auto* j : {&profiled, &stationary})
    EXPECT_EQ((*j)["delta_x"]["interval_scales"]["noise"], "random walk");
  EXPECT_EQ(profiled["delta_x"]["interval_scales"]["ci68"].get<double>(),
            delta_interval_scales.random_walk_profile.level68);
  EXPECT_EQ(profiled["delta_x"]["interval_scales"]["ci95"].get<double>(),
            delta_interval_scales.random_walk_profile.level95);
  EXPECT_EQ(stationary["delta_x"]["interval_scales"]["ci95"].get<double>(), 1.0);
  // Which intervals carry a calibration is written down and printed: with the profile, those whose
  // factors passed their last held-out check (all three since held-out 35); none with the stationary step.
  const auto line_of = [&](const std::string& name, const std::string& quantity) {
    const auto& out = printed[name];
    const auto begin = out.find("  " + quantity + " ");
    return begin == std::string::npos ? std::string() : out.substr(begin, out.find('\n', begin) - begin);
  };
  for (const auto& [key, scales] :
       {std::pair{"delta_x", delta_interval_scales}, std::pair{"x_c", critical_strain_scales},
        std::pair{"x_p", precursor_strain_scales}}) {
    const bool calibrated = scales.random_walk_profile.calibrated;
    EXPECT_EQ(profiled[key]["interval_scales"]["calibrated"].get<bool>(), calibrated) << key;
    EXPECT_FALSE(stationary[key]["interval_scales"]["calibrated"].get<bool>()) << key;
    EXPECT_FALSE(line_of("profiled.json", key).empty()) << key;
    EXPECT_EQ(line_of("profiled.json", key).find("not calibrated") == std::string::npos, calibrated)
        << printed["profiled.json"];
    EXPECT_NE(line_of("stationary.json", key).find("not calibrated"), std::string::npos)
        << printed["stationary.json"];
  }
  EXPECT_TRUE(critical_strain_scales.random_walk_profile.calibrated);
  EXPECT_TRUE(delta_interval_scales.random_walk_profile.calibrated);  // learned again, passed held-out 35
  EXPECT_TRUE(precursor_strain_scales.random_walk_profile.calibrated);
  // The fitted maxima are the same; the estimate moves only by the bootstrap's bias correction.
  EXPECT_NEAR(profiled["delta_x"]["value"].get<double>(), stationary["delta_x"]["value"].get<double>(),
              0.5 * stationary["delta_x"]["error"].get<double>());
  EXPECT_NE(profiled["delta_x"]["error"], stationary["delta_x"]["error"]);
}

}  // namespace
// A LAMMPS fix ave/time file (whitespace columns, header in the last '#' line, no units): analysed
// with the columns named, and a warning for each column that names no unit.
TEST(AnalyzeCli, LammpsAveTimeFileIsReadAndUnitlessColumnsAreWarnedAbout) {
  TempDir dir;
  const auto c = testing::power_law_curve(1.0, 1001);
  {
    std::ofstream out(dir / "strain_force.ave");
    out << "# Time-averaged data for fix pull\n# TimeStep v_strain v_force v_eel\n";
    out.precision(17);
    for (std::size_t i = 0; i < c.strain.size(); ++i) {
      out << 100 * i << " " << c.strain[i] << " " << c.force[i] << " " << c.energy[i] << "\n";
    }
  }
  const auto r = run_rupture("analyze " + quoted(dir / "strain_force.ave") +
                             " --strain v_strain --force v_force --energy v_eel --strain-unit 1");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err.find("'v_strain' names no unit"), std::string::npos) << r.err;
  EXPECT_NE(
      r.err.find("warning: " + (dir / "strain_force.ave").string() + ": column 'v_force' names no unit"),
      std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("give --force-unit"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(slurp(dir / "analysis.json"));
  EXPECT_EQ(j["warnings"].size(), 2u);
  EXPECT_NEAR(j["x_c"]["value"].get<double>(), std::pow(3.0, -0.5), 2e-3);
}

}  // namespace rupture::analysis
