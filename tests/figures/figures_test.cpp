// Tests for src/figures and `rupture plot`: pictures exist with the promised size, scripts rerun
// without a word from gnuplot, the FBM maxima sit at the closed-form strains, bad input is rejected.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "fbm/power_law.hpp"
#include "figures/gnuplot.hpp"
#include "figures/scan_fixture.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "support/tool.hpp"

namespace {

namespace fs = std::filesystem;
using namespace rupture;
using rupture::testing::run_rupture;
using rupture::testing::shell_quoted;
using rupture::testing::slurp;
using rupture::testing::TempDir;
using ::testing::HasSubstr;

const std::string examples = RUPTURE_EXAMPLES_DIR;

struct PngSize {
  std::uint32_t width = 0, height = 0;
};

// Width and height from the IHDR chunk, which the PNG format requires right after the signature.
PngSize png_size(const fs::path& file) {
  const std::string bytes = slurp(file);
  const std::string signature = "\x89PNG\r\n\x1a\n";
  EXPECT_EQ(bytes.substr(0, 8), signature) << file;
  EXPECT_EQ(bytes.substr(12, 4), "IHDR") << file;
  if (bytes.size() < 24) return {};
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  return {be32(16), be32(20)};
}

void expect_svg(const fs::path& file) {
  const std::string text = slurp(file);
  EXPECT_TRUE(text.rfind("<?xml", 0) == 0 || text.rfind("<svg", 0) == 0) << file;
  EXPECT_THAT(text, HasSubstr("</svg>")) << file;
}

void expect_pdf(const fs::path& file) {
  const std::string text = slurp(file);
  EXPECT_EQ(text.rfind("%PDF-", 0), 0u) << file;
  EXPECT_THAT(text, HasSubstr("%%EOF")) << file;
}

// Reruns the written script as a user would; gnuplot must not print anything.
void expect_silent_rerun(const fs::path& folder, const std::string& name) {
  fs::remove(folder / (name + ".png"));
  EXPECT_EQ(figures::run_gnuplot(folder, name + ".gp"), "");
  EXPECT_TRUE(fs::exists(folder / (name + ".png")));
}

std::vector<double> marker_strains(const fs::path& script) {
  // Lines "set arrow from X, graph 0 ...": the x of each marker. (A plain search: std::regex draws a
  // false -Wmaybe-uninitialized from GCC 12 in the sanitizer build.)
  const std::string text = slurp(script), prefix = "set arrow from ";
  std::vector<double> x;
  for (auto at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    const auto begin = at + prefix.size(), comma = text.find(", graph 0", begin);
    if (comma != std::string::npos && text.find('\n', begin) > comma)
      x.push_back(std::stod(text.substr(begin, comma - begin)));
  }
  return x;
}

// The columns of the first block of a NAME.dat file ('#' lines skipped, "?" as NaN).
std::vector<std::vector<double>> first_block(const fs::path& file) {
  std::vector<std::vector<double>> columns;
  std::istringstream in(slurp(file));
  std::string line;
  bool started = false;
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (started) break;
      continue;
    }
    if (line[0] == '#') continue;
    started = true;
    std::istringstream fields(line);
    std::string field;
    for (std::size_t c = 0; fields >> field; ++c) {
      if (columns.size() <= c) columns.emplace_back();
      columns[c].push_back(field == "?" ? std::numeric_limits<double>::quiet_NaN() : std::stod(field));
    }
  }
  return columns;
}

// Every block of a NAME.dat file: its '# index N: title' line and its rows of numbers.
struct Block {
  std::string title;
  std::vector<std::vector<double>> rows;
};
std::vector<Block> blocks(const fs::path& file) {
  std::vector<Block> out;
  std::istringstream in(slurp(file));
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# index ", 0) == 0) {
      out.push_back({line.substr(line.find(':') + 2), {}});
    } else if (!line.empty() && line[0] != '#' && !out.empty()) {
      std::istringstream fields(line);
      std::vector<double> row;
      for (std::string field; fields >> field;)
        row.push_back(field == "?" ? std::numeric_limits<double>::quiet_NaN() : std::stod(field));
      out.back().rows.push_back(std::move(row));
    }
  }
  return out;
}

const Block* find_block(const std::vector<Block>& all, const std::string& title) {
  for (const auto& b : all)
    if (b.title == title) return &b;
  ADD_FAILURE() << "no block titled '" << title << "'";
  return nullptr;
}

std::size_t rows_of(const std::vector<Block>& all, const std::string& title) {
  const Block* b = find_block(all, title);
  return b ? b->rows.size() : 0;
}

// The reduced tissue example run into `run` (about 2 s) and its curve analysed beside it (accepted or
// rejected, with δ_x either way). The block example has no force peak its rows resolve: it breaks
// within a row and its analysis finds no x_c.
void run_and_analyse_tissue(const fs::path& run) {
  ASSERT_EQ(run_rupture("run " + shell_quoted(examples + "tissue-small.toml") + " -o " + shell_quoted(run))
                .exit_code,
            0);
  const auto analysed = run_rupture("analyze " + shell_quoted(run / "curves.csv"));
  ASSERT_TRUE(analysed.exit_code == 0 || analysed.exit_code == 4) << analysed.err;  // 4: analysed, rejected
}

TEST(Figures, RunFolderWithAnalysisAndBreaks) {
  TempDir dir;
  const auto run = dir / "run";
  ASSERT_NO_FATAL_FAILURE(run_and_analyse_tissue(run));
  const auto out = dir / "figs";
  const auto r = run_rupture("plot " + shell_quoted(run) + " --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const std::string name : {"loading", "breaking_rate"}) {
    for (const std::string ext : {".gp", ".dat", ".png", ".svg", ".pdf"})
      EXPECT_TRUE(fs::exists(out / (name + ext))) << name << ext;
    expect_svg(out / (name + ".svg"));
    expect_pdf(out / (name + ".pdf"));
  }
  // Two stacked panels (curves, delta_x posterior) make the loading figure taller.
  const auto loading = png_size(out / "loading.png");
  EXPECT_EQ(loading.width, 1000u);
  EXPECT_EQ(loading.height, 1100u);
  const auto breaks = png_size(out / "breaking_rate.png");
  EXPECT_EQ(breaks.width, 1000u);
  EXPECT_EQ(breaks.height, 700u);
  // x_p, x_c, x_m from analysis.json, then the MAP of delta_x and the ends of its reported 95 % interval.
  const auto analysis = nlohmann::json::parse(slurp(run / "analysis.json"));
  const auto markers = marker_strains(out / "loading.gp");
  ASSERT_EQ(markers.size(), 6u);
  const auto& ci95 = analysis.at("delta_x").at("ci95");
  EXPECT_NEAR(markers[4], ci95.at(0).get<double>(), 1e-6 * std::abs(ci95.at(0).get<double>()));
  EXPECT_NEAR(markers[5], ci95.at(1).get<double>(), 1e-6 * std::abs(ci95.at(1).get<double>()));
  // The energy rate drawn is the one analysis.json carries (no second analysis), over its E_rate,max.
  const auto& stored = analysis.at("curves").at("energy_rate").at("value");
  const auto all = blocks(out / "loading.dat");
  ASSERT_GE(all.size(), 2u);
  ASSERT_EQ(all[1].rows.size(), stored.size());
  const double top = analysis.at("Erate_max").at("value").get<double>();
  for (std::size_t i = 0; i < stored.size(); i += 37)
    EXPECT_NEAR(all[1].rows[i][1], stored[i].get<double>() / top,
                1e-12 * std::abs(stored[i].get<double>() / top))
        << i;
  expect_silent_rerun(out, "loading");
  expect_silent_rerun(out, "breaking_rate");
}

// A curve whose every bootstrap replicate failed carries an empty sampling density of δ_x: the
// figure is drawn without that panel instead of handing gnuplot an empty block.
TEST(Figures, DelayPanelIsLeftOutWhenNoReplicateSucceeded) {
  TempDir dir;
  const auto run = dir / "run";
  ASSERT_NO_FATAL_FAILURE(run_and_analyse_tissue(run));
  auto analysis = nlohmann::json::parse(slurp(run / "analysis.json"));
  auto& density = analysis.at("delta_x").at("sampling_distribution");
  ASSERT_FALSE(density.at("density").at("value").empty());
  density["delta"]["value"] = nlohmann::json::array();
  density["density"]["value"] = nlohmann::json::array();
  io::write_json_atomically(run / "analysis.json", analysis);
  const auto r =
      run_rupture("plot " + shell_quoted(run) + " --format png --out " + shell_quoted(dir / "figs"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(png_size(dir / "figs" / "loading.png").height, 700u);  // one panel
  EXPECT_EQ(blocks(dir / "figs" / "loading.dat").size(), 2u);      // curves and ℰ, no density
}

TEST(Figures, RunCurvesAreNormalisedAndBreaksCounted) {
  TempDir dir;
  const auto run = dir / "run";
  ASSERT_EQ(
      run_rupture("run " + shell_quoted(examples + "block.toml") + " -o " + shell_quoted(run)).exit_code, 0);
  const auto r = run_rupture("plot " + shell_quoted(run) + " --format png");  // default folder: run/figures
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(run / "figures" / "loading.svg"));
  // Without analysis.json: one panel, no markers.
  EXPECT_EQ(png_size(run / "figures" / "loading.png").height, 700u);
  EXPECT_TRUE(marker_strains(run / "figures" / "loading.gp").empty());
  // Every curve is divided by its own maximum.
  const auto curves = first_block(run / "figures" / "loading.dat");
  ASSERT_EQ(curves.size(), 4u);
  for (std::size_t c = 1; c < 4; ++c)
    EXPECT_DOUBLE_EQ(*std::max_element(curves[c].begin(), curves[c].end()), 1.0) << c;
  // The histogram's rate times the bin width counts every broken bond once.
  const auto rate = first_block(run / "figures" / "breaking_rate.dat");
  ASSERT_EQ(rate.size(), 2u);
  const double width = rate[0][1] - rate[0][0];
  double counted = 0.0;
  for (double v : rate[1]) counted += v * width;
  EXPECT_NEAR(counted, static_cast<double>(io::read_csv(run / "breaks.csv").rows()), 1e-9);
}

TEST(Figures, FbmCurveMaximaAtClosedFormStrains) {
  TempDir dir;
  const auto csv = dir / "uniform.csv";
  ASSERT_EQ(run_rupture("fbm curves --dist uniform --out " + shell_quoted(csv)).exit_code, 0);
  const auto r = run_rupture("plot " + shell_quoted(csv) + " --out " + shell_quoted(dir / "figs"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto size = png_size(dir / "figs" / "uniform.png");
  EXPECT_EQ(size.width, 1000u);
  EXPECT_EQ(size.height, 700u);
  expect_svg(dir / "figs" / "uniform.svg");
  // Uniform thresholds on [0,1]: E_e = x^2 (1-x)/2, F = x (1-x), so x_p = 1/3, x_c = 1/2, x_m = 2/3;
  // the curve's grid step is 1e-3.
  const auto x = marker_strains(dir / "figs" / "uniform.gp");
  ASSERT_EQ(x.size(), 3u);
  EXPECT_NEAR(x[0], 1.0 / 3.0, 1e-3);
  EXPECT_NEAR(x[1], 0.5, 1e-3);
  EXPECT_NEAR(x[2], 2.0 / 3.0, 1e-3);
  expect_silent_rerun(dir / "figs", "uniform");
}

// The block example pulled to failure with a bond snapshot every 500 steps; empty if the run failed.
fs::path block_run_with_snapshots(const TempDir& dir) {
  const auto run = dir / "run";
  const auto r = run_rupture("run " + shell_quoted(examples + "block.toml") + " -o " + shell_quoted(run) +
                             " --set output.snapshot_interval=500");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? run : fs::path();
}

// Snapshots: one panel per chosen strain, each bond a segment between its two particles with its
// extension in percent, read back from the .vtp the run wrote.
TEST(Figures, SnapshotsDrawIntactBondsAtChosenStrains) {
  TempDir dir;
  const auto run = block_run_with_snapshots(dir);
  ASSERT_FALSE(run.empty());
  const auto out = dir / "figs";
  const auto r =
      run_rupture("plot " + shell_quoted(run) + " --out " + shell_quoted(out) + " --snapshots-at 0,0.15");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto size = png_size(out / "snapshots.png");
  EXPECT_EQ(size.width, 1000u);
  expect_svg(out / "snapshots.svg");
  const auto all = blocks(out / "snapshots.dat");
  ASSERT_EQ(all.size(), 2u);  // the snapshots nearest 0 % and 0.15 %: steps 0 and 500
  EXPECT_THAT(all[0].title, HasSubstr("step 0,"));
  EXPECT_THAT(all[1].title, HasSubstr("step 500,"));
  // 4 x 8 x 2 particles 1 mm apart, bonded to their axial neighbours: 3x8x2 + 4x7x2 + 4x8x1 = 136 bonds,
  // all intact and at rest before loading; projected on (x, y) each is 1 mm long or (along z) a point.
  ASSERT_EQ(all[0].rows.size(), 136u);
  for (const auto& bond : all[0].rows) {
    const double length = std::hypot(bond[2], bond[3]);
    EXPECT_TRUE(std::abs(length) < 1e-9 || std::abs(length - 1.0) < 1e-9) << length;
    EXPECT_NEAR(bond[4], 0.0, 1e-9);  // extension [%]
  }
  // Under load the bonds along y stretch; an intact bond is never beyond its breaking distance
  // 0.002 mm, 0.2 % of its 1 mm rest length.
  double largest = 0.0;
  for (const auto& bond : all[1].rows) {
    EXPECT_LE(bond[4], 0.2 + 1e-9);
    largest = std::max(largest, bond[4]);
  }
  EXPECT_GT(largest, 0.05);
  EXPECT_EQ(size.height, static_cast<std::uint32_t>(2 * 900));  // two tall panels of the 3 x 7 mm block
  expect_silent_rerun(out, "snapshots");
}

// The crack: each panel also marks the bonds broken up to its step, where breaks.csv says they broke;
// and only the snapshots that the run's snapshots.pvd lists are drawn, never a file left beside them.
TEST(Figures, SnapshotsMarkTheBondsBrokenSoFarAndOnlyTheRunsOwnFiles) {
  TempDir dir;
  const auto run = block_run_with_snapshots(dir);
  ASSERT_FALSE(run.empty());
  // A snapshot that is not this run's (a later step than any it wrote): copied in, not in the .pvd.
  fs::copy_file(run / "snapshots" / "step_0000000000.vtp", run / "snapshots" / "step_0009999999.vtp");
  const auto out = dir / "figs";
  const auto r = run_rupture("plot " + shell_quoted(run) + " --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable breaks = io::read_csv(run / "breaks.csv");
  ASSERT_GT(breaks.rows(), 0u) << "the block must break for this test";
  const auto all = blocks(out / "snapshots.dat");
  std::size_t panels = 0, marked = 0;
  for (std::size_t b = 0; b < all.size(); ++b) {
    if (all[b].title.rfind("intact bonds at step ", 0) != 0) continue;
    ++panels;
    EXPECT_THAT(all[b].title, ::testing::Not(HasSubstr("step 9999999,")));
    const double step = std::stod(all[b].title.substr(std::string("intact bonds at step ").size()));
    std::size_t expected = 0;
    for (std::size_t row = 0; row < breaks.rows(); ++row) expected += breaks.column("step")[row] <= step;
    if (expected == 0) continue;  // nothing broken yet: no dots
    ASSERT_LT(b + 1, all.size());
    const Block& broken = all[b + 1];
    EXPECT_THAT(broken.title, HasSubstr("bonds broken up to step"));
    ASSERT_EQ(broken.rows.size(), expected);
    for (std::size_t row = 0; row < expected; ++row) {
      EXPECT_DOUBLE_EQ(broken.rows[row][0], breaks.column("x")[row]);
      EXPECT_DOUBLE_EQ(broken.rows[row][1], breaks.column("y")[row]);
    }
    ++marked;
  }
  EXPECT_EQ(panels, 3u);  // near x_p, near x_c, the last: or the thirds when there is no analysis
  EXPECT_GE(marked, 1u) << "the last snapshot comes after the breaks";
}

TEST(Figures, SnapshotsAskedForInARunWithoutThemIsBadInput) {
  TempDir dir;
  const auto run = dir / "run";
  ASSERT_EQ(
      run_rupture("run " + shell_quoted(examples + "block.toml") + " -o " + shell_quoted(run)).exit_code, 0);
  const auto r = run_rupture("plot " + shell_quoted(run) + " --snapshots-at 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("output.snapshot_interval"));
}

// Figures 15-17 from a hand-written results.csv: every point lands in its class, Γ group and panel,
// and the FBM lines are the closed-form power-law values.
TEST(Figures, ScanFiguresFromResultsTable) {
  using rupture::testing::ScanFixture;
  TempDir dir;
  const auto scan = dir / "scan";
  rupture::testing::write_scan_fixture(scan);
  const auto r = run_rupture("plot " + shell_quoted(scan));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto out = scan / "figures";
  for (const std::string name : {"mechanism_map", "delay_vs_critical", "energy_ratio_vs_critical"}) {
    const auto size = png_size(out / (name + ".png"));
    EXPECT_EQ(size.width, 1000u) << name;
    EXPECT_EQ(size.height, 700u) << name;
    expect_svg(out / (name + ".svg"));
    expect_silent_rerun(out, name);
  }
  const auto map = blocks(out / "mechanism_map.dat");
  EXPECT_EQ(rows_of(map, "class brittle"), std::size_t(ScanFixture::brittle));
  EXPECT_EQ(rows_of(map, "class hyper-elastic"), std::size_t(ScanFixture::hyper_elastic));
  EXPECT_EQ(rows_of(map, "class semi-ductile"), std::size_t(ScanFixture::semi_ductile));
  // Ductile-like points are rejected, never classed: no such group.
  EXPECT_TRUE(
      std::none_of(map.begin(), map.end(), [](const Block& b) { return b.title == "class ductile"; }));
  EXPECT_EQ(rows_of(map, "rejected as ductile-like (x_c not identifiable)"),
            std::size_t(ScanFixture::rejected_ductile));
  EXPECT_EQ(rows_of(map, "rejected for another reason (see results.csv why)"),
            std::size_t(ScanFixture::rejected_other));
  EXPECT_EQ(rows_of(map, "points not analysed (not separated, unstable, failed or unfinished)"),
            std::size_t(ScanFixture::without_class));
  EXPECT_EQ(rows_of(map, "points with Gamma > 5"), std::size_t(ScanFixture::gamma_above_5));
  EXPECT_THAT(slurp(out / "mechanism_map.gp"), HasSubstr("set logscale x 10"));

  const auto delay = blocks(out / "delay_vs_critical.dat");
  const Block* points = find_block(delay, "analysed points: x_c, delta_x, x_c -/+ sd, delta_x 68 % interval");
  ASSERT_NE(points, nullptr);
  EXPECT_EQ(points->rows.size(), std::size_t(ScanFixture::positive_delay));
  EXPECT_THAT(slurp(out / "delay_vs_critical.gp"), HasSubstr("1 with δ_x ≤ 0 not on log axes"));
  // Uniform thresholds (α = 0): x_c = 1/2, x_p = 1/3, so δ_x = x_c / 3 on the FBM line.
  const Block* line = find_block(delay, "FBM power law, alpha = 0");
  ASSERT_NE(line, nullptr);
  for (const auto& row : line->rows) EXPECT_NEAR(row[1] / row[0], 1.0 / 3.0, 1e-12);

  const auto ratio = blocks(out / "energy_ratio_vs_critical.dat");
  EXPECT_EQ(rows_of(ratio, "points with Γ < 1"), std::size_t(ScanFixture::gamma_below_1));
  EXPECT_EQ(rows_of(ratio, "points with 1 ≤ Γ ≤ 5"), std::size_t(ScanFixture::gamma_1_to_5));
  EXPECT_EQ(rows_of(ratio, "points with Γ > 5"), std::size_t(ScanFixture::gamma_above_5));
  const Block* uniform = find_block(ratio, "FBM power law, alpha = 0");
  ASSERT_NE(uniform, nullptr);
  for (const auto& row : uniform->rows) EXPECT_NEAR(row[1], 4.0 / 3.0, 1e-12);  // A_r of the uniform bundle
  const Block* alpha5 = find_block(ratio, "FBM power law, alpha = 5");
  ASSERT_NE(alpha5, nullptr);
  for (const auto& row : alpha5->rows) EXPECT_NEAR(row[1], fbm::power_law::energy_ratio(5.0), 1e-12);
}

TEST(Figures, ScanFolderWithoutResultsIsBadInput) {
  TempDir dir;
  io::write_file_atomically(dir / "scan.json", "{}");
  const auto r = run_rupture("plot " + shell_quoted(dir.path()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no results.csv"));
}

TEST(Figures, FolderWithoutCurvesIsBadInput) {
  TempDir dir;
  const auto r = run_rupture("plot " + shell_quoted(dir.path()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no curves.csv"));
  EXPECT_THAT(r.err, HasSubstr(dir.path().string()));
}

TEST(Figures, CsvWithoutCurveColumnsIsBadInput) {
  TempDir dir;
  io::write_file_atomically(dir / "odd.csv", "time[s],pressure[Pa]\n0,1\n1,2\n2,3\n");
  const auto r = run_rupture("plot " + shell_quoted(dir / "odd.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("strain"));
}

TEST(Figures, MissingGnuplotSaysHowToInstall) {
  TempDir dir;
  const auto csv = dir / "uniform.csv";
  ASSERT_EQ(run_rupture("fbm curves --dist uniform --points 11 --out " + shell_quoted(csv)).exit_code, 0);
  ::setenv("RUPTURE_GNUPLOT", (dir / "no-such-gnuplot").c_str(), 1);
  const auto r = run_rupture("plot " + shell_quoted(csv));
  ::unsetenv("RUPTURE_GNUPLOT");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("apt-get install gnuplot-nox"));
}

// A plot gnuplot only warns about (it still exits 0) must fail too: the picture is not what was asked.
TEST(Figures, GnuplotWarningFailsTheDrawing) {
  TempDir dir;
  figures::Figure figure;
  figure.name = "flat";
  figure.blocks.push_back({"two points", {"x[1]", "y[1]"}, {{0.0, 1.0}, {0.5, 0.5}}});
  figures::Panel panel;
  panel.xlabel = "x [1]";
  panel.ylabel = "y [1]";
  panel.yrange = "[*:*]";  // a flat curve autoscales to an empty range: gnuplot warns and widens it
  panel.series = {{0, 0, 1, "y"}};
  figure.panels.push_back(panel);
  try {
    figures::draw(figure, dir.path(), figures::Formats{.png = true, .svg = false, .pdf = false});
    ADD_FAILURE() << "a gnuplot warning must fail the drawing";
  } catch (const RunError& e) {
    EXPECT_THAT(e.what(), HasSubstr("flat.gp"));
    EXPECT_THAT(e.what(), HasSubstr("empty y range"));
  }
  figure.panels.front().yrange = "[0:1]";
  EXPECT_NO_THROW(
      figures::draw(figure, dir.path(), figures::Formats{.png = true, .svg = false, .pdf = false}));
}

TEST(Figures, DataFileSeparatesBlocksAndMarksMissingValues) {
  figures::Figure figure;
  figure.name = "t";
  figure.provenance = {"rupture test"};
  figure.blocks.push_back(
      {"first", {"x[1]", "y[1]"}, {{0.0, 1.0}, {2.0, std::numeric_limits<double>::quiet_NaN()}}});
  figure.blocks.push_back({"second", {"x[1]", "y[1]"}, {{5.0}, {0.25}}});
  EXPECT_EQ(figures::data_text(figure),
            "# rupture test\n# index 0: first\n# x[1] y[1]\n0 2\n1 ?\n\n\n# index 1: second\n# x[1] y[1]\n5 "
            "0.25\n");
  EXPECT_THROW(figures::parse_formats("jpeg"), InputError);
  EXPECT_THROW(figures::parse_formats("png,"), InputError);
  EXPECT_EQ(figures::parse_formats("svg,pdf"), (figures::Formats{.png = false, .svg = true, .pdf = true}));
  EXPECT_EQ(figures::parse_formats("all"), figures::Formats{});
  const std::string all = figures::script_text(figure, figures::Formats{});
  EXPECT_THAT(all, HasSubstr("formats = \"png svg pdf\""));
  EXPECT_THAT(all, HasSubstr("set terminal pdfcairo"));
  EXPECT_THAT(figures::script_text(figure, figures::parse_formats("both")),
              HasSubstr("formats = \"png svg\""));
}

}  // namespace
