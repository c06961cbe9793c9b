#include "figures/gnuplot.hpp"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace rupture::figures {

namespace {

constexpr int exec_failed = 127;  // child exit status when gnuplot could not be started (as the shell uses)

// Quotes text for a gnuplot double-quoted string.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + '"';
}

std::string number(double value) {
  return std::isfinite(value) ? fmt::format("{}", value) : std::string("?");
}

std::string series_plot(const Series& s, std::size_t index, const std::string& data_file) {
  std::string columns = fmt::format("{}:{}", s.x_column + 1, s.y_column + 1);
  for (std::size_t c : s.extra_columns) columns += fmt::format(":{}", c + 1);
  const std::string color = s.color.empty() ? fmt::format("linecolor {}", index + 1)
                                            : fmt::format("linecolor rgb {}", quoted(s.color));
  const std::string points = fmt::format("pointtype {} pointsize {}", s.point_type, s.point_size);
  std::string with;
  switch (s.style) {
    case Style::lines:
      with = "lines linewidth line_width " + color;
      break;
    case Style::boxes:
      with = "boxes fillstyle solid 0.5 " + color;
      break;
    case Style::points:
      with = "points " + points + " " + color;
      break;
    case Style::xyerrorbars:
      with = "xyerrorbars " + points + " " + color;
      break;
    case Style::segments:
      with = "vectors nohead linewidth bond_width linecolor palette";
      break;
  }
  return fmt::format("{} index {} using {} with {} {}", index == 0 ? quoted(data_file) : std::string("''"),
                     s.block, columns, with,
                     s.title.empty() ? std::string("notitle") : "title " + quoted(s.title));
}

// Scale, tics and number format of one axis. Log axes label the decades as 10^n; one spanning less
// than two decades would show a single labelled tic or none, so it labels 1, 2 and 5 x 10^n instead.
std::string axis_settings(char axis, bool log, const std::string& range) {
  if (!log)
    return fmt::format("  unset logscale {0}\n  set {0}tics autofreq\n  set format {0} \"% h\"\n", axis);
  double low = 0.0, high = 0.0;
  if (std::sscanf(range.c_str(), "[%lf:%lf]", &low, &high) != 2 || !(low > 0.0) || !(high < 100.0 * low)) {
    return fmt::format("  set logscale {0} 10\n  set {0}tics autofreq\n  set format {0} \"10^{{%L}}\"\n",
                       axis);
  }
  std::vector<std::string> tics;
  for (int decade = static_cast<int>(std::floor(std::log10(low)));
       decade <= static_cast<int>(std::ceil(std::log10(high))); ++decade) {
    for (double mantissa : {1.0, 2.0, 5.0}) {
      const double value = mantissa * std::pow(10.0, decade);
      if (value >= low && value <= high) tics.push_back(fmt::format("{:g}", value));
    }
  }
  if (tics.size() < 2)
    return fmt::format("  set logscale {0} 10\n  set {0}tics autofreq\n  set format {0} \"%g\"\n", axis);
  return fmt::format("  set logscale {0} 10\n  set {0}tics ({1})\n  set format {0} \"%g\"\n", axis,
                     fmt::join(tics, ", "));
}

void append_panel(std::string& gp, const Panel& panel, const std::string& data_file) {
  gp += fmt::format("  set title {}\n  set xlabel {}\n  set ylabel {}\n  set xrange {}\n  set yrange {}\n",
                    quoted(panel.title), quoted(panel.xlabel), quoted(panel.ylabel), panel.xrange,
                    panel.yrange);
  // Every setting a panel may change is set again for each panel: multiplot panels share state.
  gp += axis_settings('x', panel.log_x, panel.xrange) + axis_settings('y', panel.log_y, panel.yrange);
  gp += panel.equal_axes ? "  set size ratio -1\n" : "  set size noratio\n";
  if (panel.cblabel.empty()) {
    gp += "  unset colorbox\n";
  } else {
    gp += fmt::format("  set colorbox\n  set cblabel {}\n  set cbrange {}\n  set palette @bond_palette\n",
                      quoted(panel.cblabel), panel.cbrange);
  }
  // The legend sits above the frame (below it, gnuplot lets it overlap the x label); none if no series has a
  // title.
  const bool any_title =
      std::any_of(panel.series.begin(), panel.series.end(), [](const Series& s) { return !s.title.empty(); });
  gp += any_title ? "  set key tmargin center horizontal box\n" : "  unset key\n";
  gp += "  unset arrow\n  unset label\n";
  for (std::size_t i = 0; i < panel.markers.size(); ++i) {
    const auto& m = panel.markers[i];
    gp += fmt::format(
        "  set arrow from {0}, graph 0 to {0}, graph 1 nohead dashtype 2 linewidth 1 linecolor rgb "
        "marker_color\n",
        number(m.x));
    // Labels step down the frame so that close markers (x_c and x_m often are) stay readable.
    gp += fmt::format(
        "  set label {} at {}, graph {} left offset character 0.4, 0 textcolor rgb marker_color boxed "
        "front\n",
        quoted(m.label), number(m.x), 0.95 - 0.06 * static_cast<double>(i));
  }
  std::string plots;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    plots += (i == 0 ? "" : ", \\\n    ") + series_plot(panel.series[i], i, data_file);
  }
  gp += "  plot " + plots + "\n";
}

}  // namespace

Formats parse_formats(const std::string& text) {
  if (text == "all") return {};
  if (text == "both") return {.png = true, .svg = true, .pdf = false};
  Formats formats{.png = false, .svg = false, .pdf = false};
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, end - start);
    if (name == "png")
      formats.png = true;
    else if (name == "svg")
      formats.svg = true;
    else if (name == "pdf")
      formats.pdf = true;
    else
      throw InputError("--format", fmt::format("unknown format '{}'", name),
                       "give png, svg and/or pdf, comma-separated, or all");
    if (end == text.size()) return formats;
    start = end + 1;
  }
}

std::string data_text(const Figure& figure) {
  std::string text;
  for (const auto& line : figure.provenance) text += "# " + line + "\n";
  for (std::size_t b = 0; b < figure.blocks.size(); ++b) {
    const auto& block = figure.blocks[b];
    if (b > 0) text += "\n\n";
    text += fmt::format("# index {}: {}\n# {}\n", b, block.title, fmt::join(block.header, " "));
    const std::size_t rows = block.columns.empty() ? 0 : block.columns.front().size();
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < block.columns.size(); ++c)
        text += (c == 0 ? "" : " ") + number(block.columns[c][r]);
      text += '\n';
    }
  }
  return text;
}

std::string script_text(const Figure& figure, Formats formats) {
  std::string listed;
  for (const auto& [wanted, name] :
       {std::pair{formats.png, "png"}, {formats.svg, "svg"}, {formats.pdf, "pdf"}})
    if (wanted) listed += (listed.empty() ? "" : " ") + std::string(name);
  const std::string data_file = figure.name + ".dat";
  std::string gp;
  for (const auto& line : figure.provenance) gp += "# " + line + "\n";
  gp += fmt::format(
      "# Draws {0}.png, {0}.svg and/or {0}.pdf from {1}. Rerun in this folder with: gnuplot {0}.gp\n"
      "# Restyle here: sizes, fonts, line width and colours; the formats drawn are listed in `formats`.\n"
      "formats = {2}\n"
      "width = {3}\n"
      "height = {4}\n"
      "font_spec = \"Sans,14\"\n"
      "line_width = 2\n"
      "bond_width = 1  # snapshots: line width of a bond\n"
      "bond_palette = \"defined (0 '#3b4cc0', 0.5 '#8c8c8c', 1 '#b40426')\"  # snapshots: compressed - "
      "unstretched (grey, visible on white) - stretched\n"
      "marker_color = \"#555555\"\n\n"
      "set datafile missing \"?\"\n"
      "set grid\n"
      "set tics out\n"
      "set style textbox opaque noborder  # marker labels stay readable over the curves\n\n"
      "do for [format in formats] {{\n"
      "  if (format eq \"png\") {{\n"
      "    # pngcairo draws antialiased text; the plain libgd png terminal is the fallback\n"
      "    if (strstrt(GPVAL_TERMINALS, \"pngcairo\") > 0) {{\n"
      "      set terminal pngcairo size width, height enhanced font font_spec\n"
      "    }} else {{\n"
      "      set terminal png size width, height enhanced font font_spec\n"
      "    }}\n"
      "    set output \"{0}.png\"\n"
      "  }}\n"
      "  if (format eq \"svg\") {{\n"
      "    set terminal svg size width, height enhanced font font_spec background rgb \"white\"\n"
      "    set output \"{0}.svg\"\n"
      "  }}\n"
      "  if (format eq \"pdf\") {{\n"
      "    # the page in points as the PNG is in pixels, so that the font keeps its size relative to it\n"
      "    set terminal pdfcairo size width / 72.0, height / 72.0 enhanced font font_spec\n"
      "    set output \"{0}.pdf\"\n"
      "  }}\n",
      figure.name, data_file, figures::quoted(listed), figure.width, figure.height);
  if (figure.panels.size() > 1) gp += fmt::format("  set multiplot layout {}, 1\n", figure.panels.size());
  for (const auto& panel : figure.panels) append_panel(gp, panel, data_file);
  if (figure.panels.size() > 1) gp += "  unset multiplot\n";
  gp += "  unset output\n}\n";
  return gp;
}

std::string run_gnuplot(const std::filesystem::path& folder, const std::string& script) {
  const char* override_program = std::getenv("RUPTURE_GNUPLOT");
  const std::string program = override_program && *override_program ? override_program : "gnuplot";
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0)
    throw RunError(fmt::format("cannot create a pipe for gnuplot: {}", std::strerror(errno)));
  const pid_t pid = ::fork();
  if (pid < 0) throw RunError(fmt::format("cannot start gnuplot: {}", std::strerror(errno)));
  if (pid == 0) {
    // Child: gnuplot's stdout and stderr both go to the pipe, so any message at all is seen.
    ::close(pipe_fds[0]);
    ::dup2(pipe_fds[1], STDOUT_FILENO);
    ::dup2(pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[1]);
    if (::chdir(folder.c_str()) != 0) ::_exit(exec_failed);
    ::execlp(program.c_str(), program.c_str(), script.c_str(), static_cast<char*>(nullptr));
    ::_exit(exec_failed);
  }
  ::close(pipe_fds[1]);
  std::string output;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n > 0)
      output.append(buffer, static_cast<std::size_t>(n));
    else if (n == 0 || errno != EINTR)
      break;
  }
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == exec_failed && output.empty()) {
    throw RunError(fmt::format(
        "cannot run '{}' (not installed or not on PATH); install it with `apt-get install gnuplot-nox`",
        program));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw RunError(fmt::format("gnuplot {} in {} failed: {}", script, folder.string(), output));
  }
  return output;
}

std::vector<std::filesystem::path> draw(const Figure& figure, const std::filesystem::path& folder,
                                        Formats formats) {
  const auto data = folder / (figure.name + ".dat");
  const auto gp = folder / (figure.name + ".gp");
  io::write_file_atomically(data, data_text(figure));
  io::write_file_atomically(gp, script_text(figure, formats));
  const std::string output = run_gnuplot(folder, gp.filename().string());
  if (!output.empty()) {
    // A warning means the picture is not what the script asked for (empty range, missing data).
    throw RunError(
        fmt::format("gnuplot {} in {} reported: {}", gp.filename().string(), folder.string(), output));
  }
  std::vector<std::filesystem::path> written{data, gp};
  if (formats.png) written.push_back(folder / (figure.name + ".png"));
  if (formats.svg) written.push_back(folder / (figure.name + ".svg"));
  if (formats.pdf) written.push_back(folder / (figure.name + ".pdf"));
  return written;
}

}  // namespace rupture::figures
