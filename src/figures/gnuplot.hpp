// figures/gnuplot: the one place that writes gnuplot scripts and runs gnuplot. A Figure (panels of
// series read from one data file, vertical markers) becomes NAME.dat + NAME.gp, then NAME.png/.svg.
// Owns: script text, data-file layout, the gnuplot child process. Not: what a figure shows.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rupture::figures {

// The pictures drawn from each figure's script: PNG for screens, SVG and PDF for papers (vector).
struct Formats {
  bool png = true, svg = true, pdf = true;
  bool operator==(const Formats&) const = default;
};
// A comma-separated list of png, svg and pdf, or "all"; "both" (png,svg) is kept for older
// scripts. InputError otherwise, naming the choices.
Formats parse_formats(const std::string& text);

// One table of the data file; gnuplot addresses it as `index N` (blocks are separated by two blank lines).
// Missing values (e.g. an undefined derivative) are written as "?".
struct DataBlock {
  std::string title;                         // written as a '#' line above the block
  std::vector<std::string> header;           // column names with units, e.g. "strain[%]"
  std::vector<std::vector<double>> columns;  // columns[c][row]; NaN = missing
};

// How a series is drawn, and which columns beyond x and y it reads (`extra_columns`, in order):
//   lines, boxes, points: none;  xyerrorbars: x_low, x_high, y_low, y_high (the ends of the bars);
//   segments: dx, dy and the colour value (mapped through the panel's palette; bonds in snapshots).
enum class Style { lines, boxes, points, xyerrorbars, segments };

struct Series {
  std::size_t block = 0;     // DataBlock index
  std::size_t x_column = 0;  // 0-based column in that block
  std::size_t y_column = 1;
  std::string title{};  // legend text (gnuplot enhanced text: E_e, F_{max}); empty: not in the legend
  Style style = Style::lines;
  std::vector<std::size_t> extra_columns{};
  std::string color{};  // "#rrggbb"; empty: gnuplot's colour number (series index + 1)
  int point_type = 7;   // gnuplot pt: 7 filled circle, 5 filled square, 9 filled triangle, 3 star
  double point_size = 1.2;
};

struct Marker {
  double x = 0.0;     // in the panel's x unit
  std::string label;  // drawn at the top of the line
};

struct Panel {
  std::string title, xlabel, ylabel;  // labels carry their units, e.g. "strain x [%]"
  std::string xrange = "[*:*]";       // gnuplot range text
  std::string yrange = "[*:*]";
  bool log_x = false, log_y = false;  // logarithmic axes (base 10)
  bool equal_axes = false;            // one unit is as long on x as on y (pictures of the sample)
  std::string cblabel;                // colour-bar label with unit; non-empty turns the palette on
  std::string cbrange = "[*:*]";
  std::vector<Series> series;
  std::vector<Marker> markers;
};

struct Figure {
  std::string name;                     // file stem: NAME.gp, NAME.dat, NAME.png, NAME.svg
  std::string caption;                  // one sentence saying what the figure shows (report captions)
  int width = 1000, height = 700;       // pixels (png) and points (svg)
  std::vector<std::string> provenance;  // '#' lines at the top of both files: version, inputs
  std::vector<DataBlock> blocks;
  std::vector<Panel> panels;  // stacked top to bottom
};

std::string data_text(const Figure& figure);
std::string script_text(const Figure& figure, Formats formats);

// Writes NAME.dat and NAME.gp atomically into `folder`, runs `gnuplot NAME.gp` there and returns the
// files written. Any gnuplot output on stdout/stderr (warnings included) or a non-zero exit is a
// RunError quoting it; a missing gnuplot is a RunError saying how to install it. The program is
// $RUPTURE_GNUPLOT if set, else `gnuplot` from PATH.
std::vector<std::filesystem::path> draw(const Figure& figure, const std::filesystem::path& folder,
                                        Formats formats);

// Runs gnuplot on `script` with `folder` as working directory; returns its combined stdout+stderr.
// Throws RunError when gnuplot cannot be started or exits non-zero.
std::string run_gnuplot(const std::filesystem::path& folder, const std::string& script);

}  // namespace rupture::figures
