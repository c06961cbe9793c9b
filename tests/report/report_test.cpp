// Tests for src/report and `rupture report`: the page is well-formed HTML, references nothing but what
// it embeds (every picture a data: URI holding exactly the PNG drawn beside it), carries the analysis
// numbers and the config, and renders in headless Chromium with every figure decoded and no console
// message.
#include "report/report.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "figures/scan_fixture.hpp"
#include "io/atomic_file.hpp"
#include "io/markup.hpp"
#include "support/browser.hpp"
#include "support/tool.hpp"

namespace {

namespace fs = std::filesystem;
using namespace rupture;
using rupture::testing::chromium;
using rupture::testing::console_lines;
using rupture::testing::have_chromium;
using rupture::testing::run_rupture;
using rupture::testing::shell_quoted;
using rupture::testing::slurp;
using rupture::testing::TempDir;
using ::testing::HasSubstr;
using ::testing::Not;

const std::string examples = RUPTURE_EXAMPLES_DIR;

// What the checker found in a page: the values of every src/href attribute, the <img> sources and
// the text of the <table> cells, in order.
struct PageFacts {
  std::vector<std::string> references;
  std::vector<std::string> images;
  std::vector<std::string> cells;
  std::string body_text;
};

// A strict reading of the HTML the report writes: tags nest and close (void elements excepted),
// attribute values are double-quoted, '&' only starts an entity, <script>/<style> hold raw text.
// Any violation is a test failure naming the offset.
PageFacts check_well_formed(const std::string& html) {
  static const std::set<std::string> void_elements{"meta",  "img", "br",  "hr",    "link",
                                                   "input", "col", "wbr", "source"};
  PageFacts facts;
  std::vector<std::string> open;
  std::size_t i = 0;
  const auto fail = [&](const std::string& what) {
    ADD_FAILURE() << what << " at offset " << i << ": '" << html.substr(i, 60) << "'";
    i = html.size();
  };
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  i = html.find('\n');
  std::string* cell = nullptr;
  while (i < html.size()) {
    const char ch = html[i];
    if (ch == '&') {
      const auto end = html.find(';', i);
      const std::string entity = end == std::string::npos ? "" : html.substr(i + 1, end - i - 1);
      const auto letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; };
      const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
      const bool named = !entity.empty() && std::all_of(entity.begin(), entity.end(), letter);
      const bool numeric =
          entity.size() > 1 && entity[0] == '#' && std::all_of(entity.begin() + 1, entity.end(), digit);
      if (!named && !numeric) return fail("bare '&'"), facts;
      if (cell) *cell += html.substr(i, end - i + 1);
      i = end + 1;
      continue;
    }
    if (ch != '<') {
      if (ch == '>') return fail("bare '>'"), facts;
      if (cell) *cell += ch;
      if (!open.empty() && std::find(open.begin(), open.end(), "body") != open.end()) facts.body_text += ch;
      ++i;
      continue;
    }
    const bool closing = html[i + 1] == '/';
    std::size_t j = i + (closing ? 2 : 1);
    const std::size_t name_start = j;
    while (j < html.size() && std::isalnum(static_cast<unsigned char>(html[j]))) ++j;
    const std::string name = html.substr(name_start, j - name_start);
    if (name.empty()) return fail("'<' that starts no tag"), facts;
    if (closing) {
      if (html[j] != '>') return fail("malformed closing tag"), facts;
      if (open.empty() || open.back() != name)
        return fail("</" + name + "> closes <" + (open.empty() ? "" : open.back()) + ">"), facts;
      open.pop_back();
      if (name == "td" || name == "th") cell = nullptr;
      i = j + 1;
      continue;
    }
    std::map<std::string, std::string> attributes;
    for (;;) {
      while (html[j] == ' ' || html[j] == '\n') ++j;
      if (html[j] == '>') break;
      const std::size_t a = j;
      while (std::isalnum(static_cast<unsigned char>(html[j])) || html[j] == '-') ++j;
      const std::string attribute = html.substr(a, j - a);
      if (attribute.empty() || html[j] != '=' || html[j + 1] != '"')
        return fail("attribute without a quoted value"), facts;
      const auto close = html.find('"', j + 2);
      const std::string value = html.substr(j + 2, close - j - 2);
      if (value.find('<') != std::string::npos) return fail("'<' inside an attribute value"), facts;
      attributes[attribute] = value;
      j = close + 1;
    }
    for (const char* key : {"src", "href", "srcset", "poster", "data", "action"}) {
      if (attributes.count(key)) facts.references.push_back(attributes[key]);
    }
    if (name == "img") facts.images.push_back(attributes["src"]);
    i = j + 1;
    if (name == "script" || name == "style") {
      const auto end = html.find("</" + name + ">", i);
      if (end == std::string::npos) return fail("unclosed <" + name + ">"), facts;
      const std::string raw = html.substr(i, end - i);
      // Nothing fetched from outside the page: no imports, no url() in CSS, no fetch or XHR in scripts.
      for (const char* outside : {"url(", "@import", "fetch(", "XMLHttpRequest", "http:", "https:"}) {
        EXPECT_EQ(raw.find(outside), std::string::npos) << "<" << name << "> mentions " << outside;
      }
      i = end + name.size() + 3;
      continue;
    }
    if (!void_elements.count(name)) open.push_back(name);
    if (name == "td" || name == "th") {
      facts.cells.emplace_back();
      cell = &facts.cells.back();
    }
  }
  EXPECT_TRUE(open.empty()) << "unclosed <" << (open.empty() ? "" : open.back()) << ">";
  return facts;
}

std::string decode_base64(const std::string& text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned value = 0;
  int bits = 0;
  for (char ch : text) {
    if (ch == '=') break;
    const auto at = alphabet.find(ch);
    if (at == std::string::npos) {
      ADD_FAILURE() << "not base64: '" << ch << "'";
      return {};
    }
    value = (value << 6) | static_cast<unsigned>(at);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((value >> bits) & 0xffu);
    }
  }
  return out;
}

// Every reference is a data: URI; every image is a PNG equal, byte for byte, to a figure file in
// `figures`, and every figure file is embedded once.
void expect_self_contained(const PageFacts& facts, const fs::path& figures) {
  for (const auto& reference : facts.references) {
    EXPECT_EQ(reference.rfind("data:", 0), 0u) << "the page refers to " << reference.substr(0, 80);
  }
  std::set<std::string> embedded;
  for (const auto& src : facts.images) {
    const std::string prefix = "data:image/png;base64,";
    ASSERT_EQ(src.rfind(prefix, 0), 0u) << src.substr(0, 40);
    embedded.insert(decode_base64(src.substr(prefix.size())));
  }
  std::size_t pngs = 0;
  for (const auto& entry : fs::directory_iterator(figures)) {
    if (entry.path().extension() != ".png") continue;
    ++pngs;
    EXPECT_TRUE(embedded.count(slurp(entry.path()))) << entry.path() << " is not embedded";
  }
  EXPECT_EQ(facts.images.size(), pngs);
  EXPECT_EQ(embedded.size(), pngs);
}

bool has_cell(const PageFacts& facts, const std::string& text) {
  return std::find(facts.cells.begin(), facts.cells.end(), text) != facts.cells.end();
}

// A run of the reduced tissue example with bond snapshots, analysed; returns its folder. (The block
// example no longer serves: its ℰ rises until the collapse, so no precursor is found before it and
// the analysis stops before δ_x and α.)
fs::path analysed_tissue_run(const TempDir& dir) {
  const auto run = dir / "run";
  EXPECT_EQ(run_rupture("run " + shell_quoted(examples + "tissue-small.toml") + " -o " + shell_quoted(run) +
                        " --set output.snapshot_interval=2000")
                .exit_code,
            0);
  const auto analysed = run_rupture("analyze " + shell_quoted(run / "curves.csv"));
  EXPECT_TRUE(analysed.exit_code == 0 || analysed.exit_code == 4) << analysed.err;  // 4: analysed, rejected
  return run;
}

TEST(Report, Base64AndEscapingFollowTheStandards) {
  // RFC 4648 section 10 test vectors.
  EXPECT_EQ(report::base64(""), "");
  EXPECT_EQ(report::base64("f"), "Zg==");
  EXPECT_EQ(report::base64("fo"), "Zm8=");
  EXPECT_EQ(report::base64("foo"), "Zm9v");
  EXPECT_EQ(report::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(decode_base64(report::base64(std::string("\x00\xff\x10 png", 8))),
            std::string("\x00\xff\x10 png", 8));
  EXPECT_EQ(io::escape_markup(R"(<a href="x">&'</a>)"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;&lt;/a&gt;");
}

// The page checker itself: each kind of fault it exists for is reported.
TEST(Report, HtmlCheckerCatchesBrokenPages) {
  EXPECT_NONFATAL_FAILURE(check_well_formed("<!DOCTYPE html>\n<html><body><p></div></body></html>"),
                          "</div> closes <p>");
  EXPECT_NONFATAL_FAILURE(check_well_formed("<!DOCTYPE html>\n<html><body>a & b</body></html>"), "bare '&'");
  EXPECT_NONFATAL_FAILURE(check_well_formed("<!DOCTYPE html>\n<html><body><img src=x></body></html>"),
                          "quoted value");
  EXPECT_NONFATAL_FAILURE(check_well_formed("<!DOCTYPE html>\n<html><body><p>open</body></html>"),
                          "closes <p>");
  EXPECT_NONFATAL_FAILURE(
      check_well_formed("<!DOCTYPE html>\n<html><body><style>b{background:url(x.png)}</style></body></html>"),
      "mentions url(");
  const auto facts =
      check_well_formed("<!DOCTYPE html>\n<html><body><a href=\"figures/loading.png\">x</a></body></html>");
  EXPECT_EQ(facts.references, std::vector<std::string>{"figures/loading.png"});
}

// Where δ_x's intervals are not calibrated because the curve's white noise lies below the level from
// which the white factors were checked (analysis.json's delta_x.interval_scales.white_share), the report
// says so with the level, with a collapse or without; where the curve was split at a sharp collapse
// (collapse_onset) at a level checked or on a walk, it says that; other uncalibrated intervals get the
// plain mark.
TEST(Report, AnUncalibratedIntervalSaysWhenItsNoiseLiesBelowTheCheckedLevels) {
  TempDir dir;
  const auto run = analysed_tissue_run(dir);
  auto analysis = nlohmann::json::parse(slurp(run / "analysis.json"));
  auto& scales = analysis.at("delta_x").at("interval_scales");
  scales["calibrated"] = false;
  scales["white_share"] = 0.0009;
  analysis["collapse_onset"] = nullptr;  // the run comes apart; the low level is the reason without it
  io::write_json_atomically(run / "analysis.json", analysis);
  ASSERT_EQ(run_rupture("report " + shell_quoted(run)).exit_code, 0);
  EXPECT_THAT(check_well_formed(slurp(run / "report.html")).body_text,
              HasSubstr("its intervals are not calibrated: the curve's white noise, 0.09 % of its peak, lies "
                        "below the 0.17 % from which the white factors were checked"));
  // The low level is the reason with a collapse too: below it no factor is calibrated.
  analysis["collapse_onset"] = {{"unit", "%"}, {"value", 0.4194}};
  io::write_json_atomically(run / "analysis.json", analysis);
  ASSERT_EQ(run_rupture("report " + shell_quoted(run)).exit_code, 0);
  const auto low_and_cut = check_well_formed(slurp(run / "report.html")).body_text;
  EXPECT_THAT(low_and_cut, HasSubstr("lies below the 0.17 % from which the white factors were checked"));
  EXPECT_THAT(low_and_cut, Not(HasSubstr("collapse too sharp")));
  // On a walk (no white share) the collapse is the reason: only δ_x's far walk cell is calibrated.
  scales.erase("white_share");
  io::write_json_atomically(run / "analysis.json", analysis);
  ASSERT_EQ(run_rupture("report " + shell_quoted(run)).exit_code, 0);
  const auto cut = check_well_formed(slurp(run / "report.html")).body_text;
  EXPECT_THAT(cut,
              HasSubstr("its intervals are not calibrated: the curve ends in a collapse too sharp for the "
                        "filter (from 0.4194 %)"));
  EXPECT_THAT(cut,
              HasSubstr("where delta_x's intervals are calibrated only on a random walk with a far collapse "
                        "(far: 10 % of x_c or more past the force peak), and not where the noise model read "
                        "a ringing"));
  EXPECT_THAT(cut, Not(HasSubstr("white factors were checked")));
  analysis["collapse_onset"] = nullptr;
  io::write_json_atomically(run / "analysis.json", analysis);
  ASSERT_EQ(run_rupture("report " + shell_quoted(run)).exit_code, 0);
  const auto plain = check_well_formed(slurp(run / "report.html")).body_text;
  EXPECT_THAT(plain, HasSubstr("its intervals are not calibrated:"));
  EXPECT_THAT(plain, Not(HasSubstr("white factors were checked")));
  EXPECT_THAT(plain, Not(HasSubstr("collapse too sharp")));
}

TEST(Report, RunReportIsSelfContainedWithNumbersAndConfig) {
  TempDir dir;
  const auto run = analysed_tissue_run(dir);
  const auto r = run_rupture("report " + shell_quoted(run));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("report.html (3 figures embedded)"));
  const std::string html = slurp(run / "report.html");
  const auto facts = check_well_formed(html);
  expect_self_contained(facts, run / "figures");
  // The analysis numbers, as analysis.json holds them, in the table.
  const auto analysis = nlohmann::json::parse(slurp(run / "analysis.json"));
  for (const char* key : {"x_c", "F_c", "x_m"}) {
    ASSERT_TRUE(analysis.at(key).is_object()) << key;
    EXPECT_TRUE(has_cell(facts, fmt::format("{:.4g}", analysis[key]["value"].get<double>()))) << key;
  }
  if (!analysis.at("accepted").get<bool>()) {
    EXPECT_THAT(facts.body_text, HasSubstr("Analysis rejected"));
  }
  // The summary says when δ_x's interval carries no calibration, as analysis.json records.
  const bool calibrated = analysis.at("delta_x").at("interval_scales").at("calibrated").get<bool>();
  EXPECT_EQ(facts.body_text.find(", not calibrated)") == std::string::npos, calibrated) << facts.body_text;
  // α as analysis.json gives it (a plain number), never a dash when it is there.
  const auto& alpha = analysis.at("alpha").at("from_delta_over_x_p");
  ASSERT_TRUE(alpha.is_number()) << "the tissue run should imply an α";
  EXPECT_TRUE(has_cell(facts, fmt::format("{:.4g}", alpha.get<double>())));
  // The resolved config, key by key.
  EXPECT_TRUE(has_cell(facts, "bonds.stiffness"));
  EXPECT_TRUE(has_cell(facts, "1000"));
  EXPECT_TRUE(has_cell(facts, "output.snapshot_interval"));
  // Each config row carries the unit the schema states: key, value, unit.
  const auto stiffness = std::find(facts.cells.begin(), facts.cells.end(), "bonds.stiffness");
  ASSERT_GE(facts.cells.end() - stiffness, 3);
  EXPECT_EQ(stiffness[1], "1000");
  EXPECT_EQ(stiffness[2], "N/mm");
  // The sample's measured sizes with the units run.json gives them.
  const auto radius = std::find(facts.cells.begin(), facts.cells.end(), "radius.mean");
  ASSERT_GE(facts.cells.end() - radius, 3);
  EXPECT_EQ(radius[2], "mm");
  // The on-line monitor's outcome as run.json records it.
  const auto record = nlohmann::json::parse(slurp(run / "run.json"));
  ASSERT_TRUE(record.at("monitor").is_object());
  if (record["monitor"]["warning"].is_object()) {
    EXPECT_THAT(facts.body_text,
                HasSubstr(fmt::format("The monitor warned at strain {:.4g} %",
                                      record["monitor"]["warning"]["strain"]["value"].get<double>())));
  } else {
    EXPECT_THAT(facts.body_text, HasSubstr("The monitor never warned"));
  }
  EXPECT_THAT(html, HasSubstr("rupture report " + run.string()));
}

TEST(Report, ScanReportTablesEveryPoint) {
  using rupture::testing::ScanFixture;
  TempDir dir;
  const auto scan = dir / "scan";
  rupture::testing::write_scan_fixture(scan);
  const auto r = run_rupture("report " + shell_quoted(scan));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("(3 figures embedded)"));
  const auto facts = check_well_formed(slurp(scan / "report.html"));
  expect_self_contained(facts, scan / "figures");
  EXPECT_THAT(facts.body_text, HasSubstr(fmt::format(
                                   "{} points in results.csv, {} separated and accepted", ScanFixture::points,
                                   ScanFixture::points - ScanFixture::without_class -
                                       ScanFixture::rejected_ductile - ScanFixture::rejected_other)));
  EXPECT_EQ(std::count(facts.cells.begin(), facts.cells.end(), "semi-ductile"), ScanFixture::semi_ductile);
  EXPECT_EQ(std::count(facts.cells.begin(), facts.cells.end(), "ductile"), 0);
  EXPECT_TRUE(has_cell(facts, "still whole at max_strain"));
  EXPECT_TRUE(has_cell(facts, "k_n[N/mm]"));
  // The paper's claims against the fixture (scan/claims), and numbers shortened to 4 digits.
  EXPECT_TRUE(has_cell(facts, "4 of 6; A_r median 1.02 (10–90 %: 0.75–1.27; all 0.7–1.3)"));
  EXPECT_TRUE(has_cell(facts, "2 of 8 separated runs"));
  EXPECT_TRUE(has_cell(facts, "brittle at b_d = 0.001 mm"));
  EXPECT_TRUE(has_cell(facts, "0.0006"));  // δ_x_sd of the second point, 0.1 x 0.006
}

TEST(Report, WhatIsNotARunOrScanFolderIsBadInput) {
  TempDir dir;
  auto r = run_rupture("report " + shell_quoted(dir / "missing"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("not a folder"));
  r = run_rupture("report " + shell_quoted(dir.path()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("no curves.csv or results.csv"));
  EXPECT_FALSE(fs::exists(dir / "report.html"));
}

// ---- the browser test -------------------------------------------------------------------------

struct Image {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // 3 bytes per pixel
};

// Decodes an 8-bit RGB or RGBA PNG (what Chromium's screenshot writes): inflate the IDAT stream, undo
// the per-row filters (PNG spec section 9).
Image decode_png(const std::string& bytes) {
  Image image;
  if (bytes.size() < 33 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) {
    ADD_FAILURE() << "not a PNG";
    return image;
  }
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  image.width = be32(16);
  image.height = be32(20);
  const int depth = bytes[24], colour = bytes[25];
  if (depth != 8 || (colour != 2 && colour != 6) || bytes[28] != 0) {
    ADD_FAILURE() << "unexpected PNG format: depth " << depth << ", colour type " << colour;
    return image;
  }
  const std::size_t channels = colour == 6 ? 4 : 3;
  std::string idat;
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const std::uint32_t length = be32(at);
    if (bytes.compare(at + 4, 4, "IDAT") == 0) idat += bytes.substr(at + 8, length);
    at += 12 + length;
  }
  const std::size_t stride = image.width * channels;
  std::vector<std::uint8_t> raw((stride + 1) * image.height);
  uLongf raw_size = raw.size();
  if (uncompress(raw.data(), &raw_size, reinterpret_cast<const Bytef*>(idat.data()), idat.size()) != Z_OK ||
      raw_size != raw.size()) {
    ADD_FAILURE() << "IDAT does not inflate to " << raw.size() << " bytes";
    return image;
  }
  std::vector<std::uint8_t> previous(stride, 0), row(stride);
  image.rgb.reserve(std::size_t(image.width) * image.height * 3);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    const std::uint8_t* in = &raw[y * (stride + 1)];
    const int filter = in[0];
    for (std::size_t x = 0; x < stride; ++x) {
      const int a = x >= channels ? row[x - channels] : 0, b = previous[x],
                c = x >= channels ? previous[x - channels] : 0;
      int predictor = 0;
      switch (filter) {
        case 1:
          predictor = a;
          break;
        case 2:
          predictor = b;
          break;
        case 3:
          predictor = (a + b) / 2;
          break;
        case 4: {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default:
          break;
      }
      row[x] = static_cast<std::uint8_t>(in[1 + x] + predictor);
    }
    for (std::uint32_t x = 0; x < image.width; ++x)
      for (std::size_t k = 0; k < 3; ++k) image.rgb.push_back(row[x * channels + k]);
    previous = row;
  }
  return image;
}

// Share of pixels that differ from the page background (white) by more than a faint tint.
double inked_fraction(const Image& image) {
  std::size_t inked = 0;
  for (std::size_t p = 0; p + 2 < image.rgb.size(); p += 3)
    if (image.rgb[p] < 235 || image.rgb[p + 1] < 235 || image.rgb[p + 2] < 235) ++inked;
  return image.rgb.empty() ? 0.0 : static_cast<double>(inked) / static_cast<double>(image.rgb.size() / 3);
}

TEST(ReportBrowser, RunReportRendersWithEveryFigureAndNoConsoleMessage) {
  ASSERT_TRUE(have_chromium()) << "chromium is missing: scripts/bootstrap installs it (scripts/packages.txt)";
  TempDir dir;
  const auto run = analysed_tissue_run(dir);
  ASSERT_EQ(run_rupture("report " + shell_quoted(run)).exit_code, 0);
  const auto shot = dir / "screenshot.png";
  const auto drawn = chromium(run / "report.html", dir / "shot", "--screenshot=" + shell_quoted(shot));
  ASSERT_EQ(drawn.exit_code, 0) << drawn.log;
  const Image image = decode_png(slurp(shot));
  EXPECT_EQ(image.width, 1200u);
  EXPECT_EQ(image.height, 2000u);
  // Headings, tables and the figures cover a good part of the first screen; a blank page covers none.
  EXPECT_GT(inked_fraction(image), 0.03);
  EXPECT_THAT(console_lines(drawn.log), ::testing::IsEmpty());

  const auto dom = chromium(run / "report.html", dir / "dom", "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_THAT(dom.dom, HasSubstr("data-figures=\"3 of 3 loaded\""));
  EXPECT_THAT(console_lines(dom.log), ::testing::IsEmpty());
}

// The same checks catch a broken page: a picture that does not decode and a script error.
TEST(ReportBrowser, BrokenFigureAndScriptErrorAreCaught) {
  ASSERT_TRUE(have_chromium()) << "chromium is missing: scripts/bootstrap installs it (scripts/packages.txt)";
  TempDir dir;
  const auto scan = dir / "scan";
  rupture::testing::write_scan_fixture(scan);
  ASSERT_EQ(run_rupture("report " + shell_quoted(scan)).exit_code, 0);
  std::string html = slurp(scan / "report.html");
  const auto first = html.find("data:image/png;base64,") + 22;
  html.replace(first, 8, "AAAAAAAA");  // the PNG signature no longer decodes
  html.replace(html.find("</body>"), 0, "<script>no_such_function();</script>\n");
  io::write_file_atomically(scan / "broken.html", html);
  const auto dom = chromium(scan / "broken.html", dir / "dom", "--dump-dom");
  ASSERT_EQ(dom.exit_code, 0) << dom.log;
  EXPECT_THAT(dom.dom, HasSubstr("data-figures=\"2 of 3 loaded\""));
  const auto lines = console_lines(dom.log);
  ASSERT_FALSE(lines.empty());
  EXPECT_THAT(lines.front(), HasSubstr("no_such_function"));
}

}  // namespace
