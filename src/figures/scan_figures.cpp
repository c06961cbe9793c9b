#include "figures/scan_figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "fbm/power_law.hpp"
#include "scan/results.hpp"

namespace rupture::figures {

namespace fs = std::filesystem;

namespace {

constexpr double gamma_far = 5.0;  // Γ above this: the energy maximum far behind x_c (stars, paper fig. 15)
constexpr double alpha_low = 0.0, alpha_high = 5.0;  // the FBM band of the paper's figures 16 and 17

// The four classes of the paper's section 5.2, each with its colour in figure 15.
struct ClassStyle {
  const char* name;
  const char* color;
};
// Classes of accepted points; ductile-like points are rejected (x_c cannot be identified) and drawn
// with the other rejected points.
constexpr ClassStyle class_styles[] = {
    {"brittle", "#1f77b4"}, {"hyper-elastic", "#d62728"}, {"semi-ductile", "#2ca02c"}};

using Point = scan::PointOutcome;

// A log-axis range around [low, high] with a margin of `factor` on each side.
std::string log_range(double low, double high, double factor = 2.0) {
  return fmt::format("[{}:{}]", low / factor, high * factor);
}

// Adds a block and a series drawing it; nothing when the group is empty (gnuplot warns on empty data).
void add_group(Figure& figure, Panel& panel, const std::string& title, std::vector<std::string> header,
               std::vector<std::vector<double>> columns, Series series) {
  if (columns.empty() || columns.front().empty()) return;
  series.block = figure.blocks.size();
  figure.blocks.push_back({title, std::move(header), std::move(columns)});
  panel.series.push_back(std::move(series));
}

// The FBM power-law prediction y(x) = slope x (δ_x against x_c) or y = const (A_r) as a two-point line.
void add_fbm_line(Figure& figure, Panel& panel, double alpha, double x_low, double x_high, double slope,
                  double constant, const std::string& y_header, const std::string& title, const char* color) {
  add_group(figure, panel, fmt::format("FBM power law, alpha = {}", alpha), {"x_c[%]", y_header},
            {{x_low, x_high}, {constant + slope * x_low, constant + slope * x_high}},
            {.title = title, .color = color});
}

std::optional<Figure> mechanism_map(const std::vector<Point>& points) {
  if (points.empty()) return std::nullopt;
  Figure figure;
  figure.name = "mechanism_map";
  Panel panel;
  panel.title = fmt::format("Breaking mechanisms over the scan ({} points)", points.size());
  panel.xlabel = "bond stiffness k_n [N/mm]";
  panel.ylabel = "breaking distance b_d [mm]";
  panel.log_x = panel.log_y = true;
  const auto [k_low, k_high] =
      std::minmax_element(points.begin(), points.end(), [](auto& a, auto& b) { return a.k_n < b.k_n; });
  const auto [b_low, b_high] =
      std::minmax_element(points.begin(), points.end(), [](auto& a, auto& b) { return a.b_d < b.b_d; });
  panel.xrange = log_range(k_low->k_n, k_high->k_n);
  panel.yrange = log_range(b_low->b_d, b_high->b_d);
  const std::vector<std::string> header{"k_n[N/mm]", "b_d[mm]"};
  const auto columns_where = [&](auto keep) {
    std::vector<std::vector<double>> c(2);
    for (const auto& p : points)
      if (keep(p)) c[0].push_back(p.k_n), c[1].push_back(p.b_d);
    return c;
  };
  for (const auto& style : class_styles) {
    add_group(figure, panel, std::string("class ") + style.name, header,
              columns_where([&](const Point& p) { return p.analysed() && p.mechanism == style.name; }),
              {.title = style.name, .style = Style::points, .color = style.color, .point_size = 2.0});
  }
  add_group(figure, panel, "rejected as ductile-like (x_c not identifiable)", header,
            columns_where([&](const Point& p) { return p.rejected() && p.ductile_like(); }),
            {.title = "rejected: ductile-like",
             .style = Style::points,
             .color = "#ff7f0e",
             .point_type = 2,
             .point_size = 2.0});
  add_group(figure, panel, "rejected for another reason (see results.csv why)", header,
            columns_where([&](const Point& p) { return p.rejected() && !p.ductile_like(); }),
            {.title = "rejected: peaks not resolved",
             .style = Style::points,
             .color = "#555555",
             .point_type = 2,
             .point_size = 2.0});
  add_group(figure, panel, "points not analysed (not separated, unstable, failed or unfinished)", header,
            columns_where([](const Point& p) { return p.status != scan::status::ok; }),
            {.title = "not separated, failed or not run",
             .style = Style::points,
             .color = "#aaaaaa",
             .point_type = 6,
             .point_size = 1.5});
  add_group(
      figure, panel, fmt::format("points with Gamma > {}", gamma_far), header,
      columns_where([](const Point& p) { return p.analysed() && p.gamma && *p.gamma > gamma_far; }),
      {.title = "Γ > 5", .style = Style::points, .color = "#000000", .point_type = 3, .point_size = 3.0});
  figure.panels.push_back(std::move(panel));
  figure.caption =
      "Mechanism map (the paper's figure 15): each scan point at its bond stiffness k_n and breaking "
      "distance b_d, coloured by its breaking-mechanism class (accepted points only); crosses are points "
      "the analysis rejected (orange: ductile-like, x_c not identifiable), circles runs that did not "
      "separate or failed; a star marks Γ > 5, an energy maximum far behind the force maximum.";
  return figure;
}

std::optional<Figure> delay_figure(const std::vector<Point>& points) {
  std::vector<std::vector<double>> c(6);
  std::size_t not_positive = 0;
  for (const auto& p : points) {
    if (!p.analysed() || !p.delta_x) continue;
    if (!(*p.delta_x > 0.0)) {
      ++not_positive;
      continue;
    }
    const double x_err = p.x_c_err.value_or(0.0);
    c[0].push_back(*p.x_c);
    c[1].push_back(*p.delta_x);
    c[2].push_back(*p.x_c - x_err);
    c[3].push_back(*p.x_c + x_err);
    c[4].push_back(p.delta_lo68.value_or(*p.delta_x));
    c[5].push_back(p.delta_hi68.value_or(*p.delta_x));
  }
  if (c[0].empty()) return std::nullopt;
  Figure figure;
  figure.name = "delay_vs_critical";
  Panel panel;
  // The count of points a log axis cannot show goes into the legend: in the title it ran off the
  // figure's right edge.
  panel.title =
      fmt::format("Delay of failure behind the precursor ({} analysed points)", c[0].size() + not_positive);
  panel.xlabel = "critical strain x_c [%]";
  panel.ylabel = "delay δ_x = x_c - x_p [%]";
  panel.log_x = panel.log_y = true;
  const auto [x_low, x_high] = std::minmax_element(c[0].begin(), c[0].end());
  const auto [y_low, y_high] = std::minmax_element(c[1].begin(), c[1].end());
  const double line_low = *x_low / 3.0, line_high = *x_high * 3.0;
  panel.xrange = log_range(*x_low, *x_high, 3.0);
  panel.yrange = log_range(std::min(*y_low, line_low * 0.1), std::max(*y_high, line_high / 3.0), 3.0);
  add_group(figure, panel, "analysed points: x_c, delta_x, x_c -/+ sd, delta_x 68 % interval",
            {"x_c[%]", "delta_x[%]", "x_c_low[%]", "x_c_high[%]", "delta_x_lo68[%]", "delta_x_hi68[%]"},
            std::move(c),
            {.title = not_positive ? fmt::format("DEM runs (68 % intervals; {} with δ_x ≤ 0 not on log axes)",
                                                 not_positive)
                                   : std::string("DEM runs (68 % intervals)"),
             .style = Style::xyerrorbars,
             .extra_columns = {2, 3, 4, 5},
             .color = "#1f77b4",
             .point_size = 1.3});
  // Eq. 16: x_c = r(α) x_p, so δ_x = (1 - 1/r(α)) x_c.
  for (const auto& [alpha, color] : {std::pair{alpha_low, "#d62728"}, std::pair{alpha_high, "#0000cc"}}) {
    const double slope = 1.0 - 1.0 / fbm::power_law::critical_to_precursor_ratio(alpha);
    add_fbm_line(figure, panel, alpha, line_low, line_high, slope, 0.0, "delta_x[%]",
                 fmt::format("FBM, α = {:g}: δ_x = {:.3g} x_c", alpha, slope), color);
  }
  figure.panels.push_back(std::move(panel));
  figure.caption =
      "δ_x against x_c (the paper's figure 16), log-log, with x_c ± 1σ and the 68 % posterior interval "
      "of δ_x as bars; lines: the FBM power-law relation δ_x = (1 - 1/r(α)) x_c for α = 0 and 5.";
  return figure;
}

std::optional<Figure> energy_ratio_figure(const std::vector<Point>& points) {
  // The paper's three groups: energy maximum just behind x_c (Γ < 1), intermediate, far behind (Γ > 5).
  struct Group {
    const char* title;
    const char* color;
    int point_type;
  };
  const Group groups[] = {{"Γ < 1", "#1f77b4", 7}, {"1 ≤ Γ ≤ 5", "#2ca02c", 5}, {"Γ > 5", "#000000", 9}};
  const auto group_of = [](double gamma) -> std::size_t {
    return gamma < 1.0 ? 0 : gamma <= gamma_far ? 1 : 2;
  };
  std::vector<const Point*> kept;
  for (const auto& p : points)
    if (p.analysed() && p.A_r && p.gamma) kept.push_back(&p);
  if (kept.empty()) return std::nullopt;
  Figure figure;
  figure.name = "energy_ratio_vs_critical";
  Panel panel;
  panel.title = fmt::format("Energy ratio A_r against critical strain ({} analysed points)", kept.size());
  panel.xlabel = "critical strain x_c [%]";
  panel.ylabel = "A_r = E_{max} / (x_p ℰ_{max}) [1]";
  panel.log_x = true;
  double x_low = INFINITY, x_high = 0.0, y_high = 0.0;
  for (const auto* p : kept) {
    x_low = std::min(x_low, *p->x_c);
    x_high = std::max(x_high, *p->x_c);
    y_high = std::max(y_high, *p->A_r + p->A_r_err.value_or(0.0));
  }
  panel.xrange = log_range(x_low, x_high, 3.0);
  panel.yrange = fmt::format("[0:{}]", std::max(y_high, 1.5) * 1.15);
  for (std::size_t g_index = 0; g_index < std::size(groups); ++g_index) {
    const Group& g = groups[g_index];
    std::vector<std::vector<double>> c(6);
    for (const auto* p : kept) {
      if (group_of(*p->gamma) != g_index) continue;
      const double x_err = p->x_c_err.value_or(0.0), y_err = p->A_r_err.value_or(0.0);
      c[0].push_back(*p->x_c);
      c[1].push_back(*p->A_r);
      c[2].push_back(*p->x_c - x_err);
      c[3].push_back(*p->x_c + x_err);
      c[4].push_back(*p->A_r - y_err);
      c[5].push_back(*p->A_r + y_err);
    }
    add_group(figure, panel, std::string("points with ") + g.title,
              {"x_c[%]", "A_r[1]", "x_c_low[%]", "x_c_high[%]", "A_r_low[1]", "A_r_high[1]"}, std::move(c),
              {.title = g.title,
               .style = Style::xyerrorbars,
               .extra_columns = {2, 3, 4, 5},
               .color = g.color,
               .point_type = g.point_type,
               .point_size = 1.5});
  }
  for (const auto& [alpha, color] : {std::pair{alpha_low, "#d62728"}, std::pair{alpha_high, "#0000cc"}}) {
    const double a_r = fbm::power_law::energy_ratio(alpha);
    add_fbm_line(figure, panel, alpha, x_low / 3.0, x_high * 3.0, 0.0, a_r, "A_r[1]",
                 fmt::format("FBM, α = {:g}: A_r = {:.3f}", alpha, a_r), color);
  }
  figure.panels.push_back(std::move(panel));
  figure.caption =
      "A_r against x_c (the paper's figure 17) with ±1σ bars, three symbols for Γ < 1, 1–5 and > 5; "
      "horizontal lines: the FBM power-law values for α = 0 (A_r = 4/3) and α = 5.";
  return figure;
}

}  // namespace

std::vector<Figure> scan_figures(const fs::path& scan_folder, const std::vector<std::string>& provenance) {
  const fs::path file = scan_folder / "results.csv";
  if (!fs::exists(file)) {
    throw InputError(
        scan_folder.string(), "no results.csv in this scan folder yet",
        "wait until `rupture scan` has finished a point (it rewrites results.csv after each one)");
  }
  const auto points = scan::read_outcomes(scan::read_results(file));
  std::vector<Figure> figures;
  for (auto figure : {mechanism_map(points), delay_figure(points), energy_ratio_figure(points)}) {
    if (!figure) continue;
    figure->provenance = provenance;
    figures.push_back(std::move(*figure));
  }
  if (figures.empty()) {
    throw InputError(file.string(), "no point with k_n and b_d to draw",
                     "plot a scan that has finished points");
  }
  return figures;
}

}  // namespace rupture::figures
