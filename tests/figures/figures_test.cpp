// Tests for src/figures and `rupture plot`: pictures exist with the promised size, scripts rerun
// without a word from gnuplot, the FBM maxima sit at the closed-form strains, bad input is rejected.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "figures/gnuplot.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "support/tool.hpp"

namespace {

namespace fs = std::filesystem;
using namespace rupture;
using rupture::testing::run_rupture;
using rupture::testing::slurp;
using rupture::testing::TempDir;
using ::testing::HasSubstr;

const std::string examples = RUPTURE_EXAMPLES_DIR;

std::string shell_quoted(const fs::path& p) { return "'" + p.string() + "'"; }

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

// Reruns the written script as a user would; gnuplot must not print anything.
void expect_silent_rerun(const fs::path& folder, const std::string& name) {
  fs::remove(folder / (name + ".png"));
  EXPECT_EQ(figures::run_gnuplot(folder, name + ".gp"), "");
  EXPECT_TRUE(fs::exists(folder / (name + ".png")));
}

std::vector<double> marker_strains(const fs::path& script) {
  const std::string text = slurp(script);
  const std::regex arrow(R"(set arrow from ([-+0-9.eE]+), graph 0)");
  std::vector<double> x;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), arrow); it != std::sregex_iterator(); ++it)
    x.push_back(std::stod((*it)[1].str()));
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

TEST(Figures, RunFolderWithAnalysisAndBreaks) {
  TempDir dir;
  const auto run = dir / "run";
  ASSERT_EQ(run_rupture("run " + shell_quoted(examples + "block.toml") + " -o " + shell_quoted(run)).exit_code, 0);
  const auto analysed = run_rupture("analyze " + shell_quoted(run / "curves.csv"));
  ASSERT_TRUE(analysed.exit_code == 0 || analysed.exit_code == 4) << analysed.err;  // 4: analysed, rejected
  const auto out = dir / "figs";
  const auto r = run_rupture("plot " + shell_quoted(run) + " --out " + shell_quoted(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  for (const std::string name : {"loading", "breaking_rate"}) {
    for (const std::string ext : {".gp", ".dat", ".png", ".svg"}) EXPECT_TRUE(fs::exists(out / (name + ext))) << name << ext;
    expect_svg(out / (name + ".svg"));
  }
  // Two stacked panels (curves, delta_x posterior) make the loading figure taller.
  const auto loading = png_size(out / "loading.png");
  EXPECT_EQ(loading.width, 1000u);
  EXPECT_EQ(loading.height, 1100u);
  const auto breaks = png_size(out / "breaking_rate.png");
  EXPECT_EQ(breaks.width, 1000u);
  EXPECT_EQ(breaks.height, 700u);
  // x_p, x_c, x_m from analysis.json, then the MAP of delta_x.
  EXPECT_EQ(marker_strains(out / "loading.gp").size(), 4u);
  expect_silent_rerun(out, "loading");
  expect_silent_rerun(out, "breaking_rate");
}

TEST(Figures, RunCurvesAreNormalisedAndBreaksCounted) {
  TempDir dir;
  const auto run = dir / "run";
  ASSERT_EQ(run_rupture("run " + shell_quoted(examples + "block.toml") + " -o " + shell_quoted(run)).exit_code, 0);
  const auto r = run_rupture("plot " + shell_quoted(run) + " --format png");  // default folder: run/figures
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(run / "figures" / "loading.svg"));
  // Without analysis.json: one panel, no markers.
  EXPECT_EQ(png_size(run / "figures" / "loading.png").height, 700u);
  EXPECT_TRUE(marker_strains(run / "figures" / "loading.gp").empty());
  // Every curve is divided by its own maximum.
  const auto curves = first_block(run / "figures" / "loading.dat");
  ASSERT_EQ(curves.size(), 4u);
  for (std::size_t c = 1; c < 4; ++c) EXPECT_DOUBLE_EQ(*std::max_element(curves[c].begin(), curves[c].end()), 1.0) << c;
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
    figures::draw(figure, dir.path(), figures::Format::png);
    ADD_FAILURE() << "a gnuplot warning must fail the drawing";
  } catch (const RunError& e) {
    EXPECT_THAT(e.what(), HasSubstr("flat.gp"));
    EXPECT_THAT(e.what(), HasSubstr("empty y range"));
  }
  figure.panels.front().yrange = "[0:1]";
  EXPECT_NO_THROW(figures::draw(figure, dir.path(), figures::Format::png));
}

TEST(Figures, DataFileSeparatesBlocksAndMarksMissingValues) {
  figures::Figure figure;
  figure.name = "t";
  figure.provenance = {"rupture test"};
  figure.blocks.push_back({"first", {"x[1]", "y[1]"}, {{0.0, 1.0}, {2.0, std::numeric_limits<double>::quiet_NaN()}}});
  figure.blocks.push_back({"second", {"x[1]", "y[1]"}, {{5.0}, {0.25}}});
  EXPECT_EQ(figures::data_text(figure),
            "# rupture test\n# index 0: first\n# x[1] y[1]\n0 2\n1 ?\n\n\n# index 1: second\n# x[1] y[1]\n5 0.25\n");
  EXPECT_THROW(figures::parse_format("jpeg"), InputError);
  const std::string both = figures::script_text(figure, figures::Format::both);
  EXPECT_THAT(both, HasSubstr("formats = \"png svg\""));
  EXPECT_THAT(figures::script_text(figure, figures::Format::svg), HasSubstr("formats = \"svg\""));
}

}  // namespace
