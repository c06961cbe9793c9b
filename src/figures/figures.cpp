#include "figures/figures.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "figures/scan_figures.hpp"
#include "figures/snapshots.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/quantity.hpp"
#include "rupture/version.hpp"

namespace rupture::figures {

namespace fs = std::filesystem;

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr int break_bins = 40;  // histogram bins over the run's strain range

std::size_t argmax(const std::vector<double>& v) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i] > v[best] || !std::isfinite(v[best])) best = i;
  return best;
}

// v / max(v); the paper's figures compare shapes, so each curve is scaled to a maximum of 1.
std::vector<double> normalised(std::vector<double> v, const std::string& what, const std::string& source) {
  const double top = v.empty() ? nan : v[argmax(v)];
  if (!(top > 0.0)) {
    throw InputError(source,
                     fmt::format("{} is never positive, so it cannot be normalised to its maximum", what),
                     "plot a curve that loads the sample");
  }
  for (auto& value : v) value /= top;
  return v;
}

// dy/dx by centred differences (one-sided at the ends); undefined (NaN) where the strain does not advance.
std::vector<double> centred_difference(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<double> d(n, nan);
  for (std::size_t i = 0; i < n && n > 1; ++i) {
    const std::size_t lo = i == 0 ? 0 : i - 1, hi = i + 1 == n ? n - 1 : i + 1;
    const double dx = x[hi] - x[lo];
    if (dx > 0.0) d[i] = (y[hi] - y[lo]) / dx;
  }
  return d;
}

std::vector<std::string> provenance(const fs::path& input, const std::vector<fs::path>& read) {
  std::vector<std::string> lines{fmt::format("rupture {} plot {}", version_string, input.string())};
  for (const auto& file : read) lines.push_back("read: " + file.string());
  return lines;
}

// The top panel shared by every loading-curve figure: F and E_e (block 0, columns 1 and 2, each over
// its maximum) and the energy rate ℰ (block `rate_block`, column `rate_column`), with the maxima marked.
Panel loading_panel(std::size_t rate_block, std::size_t rate_column, const std::string& strain_field,
                    std::vector<Marker> markers) {
  const std::string unit = io::column_unit(strain_field).empty() ? "1" : io::column_unit(strain_field);
  Panel panel;
  panel.title = "Loading curves, each divided by its maximum";
  panel.xlabel = fmt::format("strain x [{}]", unit);
  panel.ylabel = "normalised value [1]";
  // Negative parts (unloading after failure) fall below the frame, as in the paper's figures.
  panel.yrange = "[0:1.12]";
  panel.series = {
      {.y_column = 1, .title = "force F/F_{max}"},
      {.y_column = 2, .title = "elastic energy E_e/E_{e,max}"},
      {.block = rate_block, .y_column = rate_column, .title = "energy rate ℰ/ℰ_{max}, ℰ = dE_e/dx"}};
  panel.markers = std::move(markers);
  return panel;
}

Figure fbm_figure(const io::CsvTable& table, const fs::path& input) {
  const auto& x = table.column("strain");
  const auto& force = table.column("force");
  const auto& energy = table.column("elastic_energy");
  const auto& rate = table.column("energy_rate");
  Figure figure;
  figure.name = input.stem().string();
  figure.provenance = provenance(input, {input});
  // The three maxima of the ELS curves: x_p (ℰ) before x_c (F) before x_m (E_e), the paper's figure 3.
  std::vector<Marker> markers{
      {x[argmax(rate)], "x_p"}, {x[argmax(force)], "x_c"}, {x[argmax(energy)], "x_m"}};
  const std::string strain_field = table.header[table.require("strain")];
  figure.blocks.push_back({"ELS curves normalised to their maxima",
                           {strain_field, "F/F_max[1]", "E_e/E_e,max[1]", "Erate/Erate_max[1]"},
                           {x, normalised(force, "the force", table.source),
                            normalised(energy, "the elastic energy", table.source),
                            normalised(rate, "the energy rate dE_e/dx", table.source)}});
  figure.panels.push_back(loading_panel(0, 3, strain_field, std::move(markers)));
  figure.panels.front().title = "Fiber bundle: F, E_e and ℰ over their maxima";
  figure.caption =
      "Fiber bundle: force F, elastic energy E_e and energy rate ℰ = dE_e/dx, each over its maximum, "
      "with their maxima x_p (ℰ) < x_c (F) < x_m (E_e) marked (the paper's figure 3).";
  return figure;
}

std::optional<double> json_value(const nlohmann::json& analysis, const char* key) {
  const auto it = analysis.find(key);
  if (it == analysis.end()) return std::nullopt;
  return io::quantity_value(*it);
}

// ℰ = dE_e/dx as the analysis computed it (analysis.json's "curves": filtered, differentiated, on its
// uniform strain grid), divided by the fitted ℰ_max so that the marked x_p sits at the top of the curve.
// nullopt for an analysis.json of an earlier build, which did not carry the curves.
std::optional<DataBlock> analysed_rate(const nlohmann::json& analysis, const std::string& strain_field,
                                       const std::string& source) {
  const auto curves = analysis.find("curves");
  if (curves == analysis.end() || curves->at("energy_rate").at("value").empty()) return std::nullopt;
  const double x0 = curves->at("x0").at("value").get<double>(),
               step = curves->at("step").at("value").get<double>();
  std::vector<double> rate;
  for (const auto& v : curves->at("energy_rate").at("value"))  // null: a value JSON cannot hold (NaN)
    rate.push_back(v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>());
  std::vector<double> grid(rate.size());
  for (std::size_t i = 0; i < grid.size(); ++i) grid[i] = x0 + static_cast<double>(i) * step;
  if (const auto top = json_value(analysis, "Erate_max"); top && *top > 0.0) {
    for (auto& v : rate) v /= *top;
  } else {
    rate = normalised(std::move(rate), "the energy rate dE_e/dx", source);
  }
  return DataBlock{fmt::format("energy rate from the analysis: {} filter, Savitzky-Golay derivative over {} "
                               "samples, divided by Erate_max",
                               analysis.at("filter").at("kind").get<std::string>(),
                               analysis.at("derivative").at("window_samples").get<int>()),
                   {strain_field, "Erate/Erate_max[1]"},
                   {std::move(grid), std::move(rate)}};
}

// The lower panel of the loading figure: δ_x's sampling density (fitted maxima) or posterior (l1
// shift) from analysis.json, over its 95 % interval with the interval's width on each side.
void add_delay_panel(Figure& figure, const nlohmann::json& delta) {
  // fitted-maxima: the bootstrap's sampling distribution; shift-l1: the Bayesian posterior.
  const bool sampled = delta.contains("sampling_distribution");
  const auto& posterior = sampled ? delta.at("sampling_distribution") : delta.at("posterior");
  const std::string what = sampled ? "sampling density (bootstrap)" : "posterior density";
  const auto& delta_values = posterior.at("delta");
  const auto& density = posterior.at("density");
  // Every bootstrap replicate failed (a curve the analysis rejects can come to that): no density to
  // draw, and gnuplot refuses an empty block.
  if (density.at("value").empty()) return;
  const std::string unit = delta_values.at("unit").get<std::string>();
  const std::string density_unit = density.at("unit").get<std::string>();
  figure.blocks.push_back({what + " of the delay delta_x",
                           {fmt::format("delta_x[{}]", unit), fmt::format("density[{}]", density_unit)},
                           {delta_values.at("value").get<std::vector<double>>(),
                            density.at("value").get<std::vector<double>>()}});
  Panel panel;
  panel.title = fmt::format("Delay between the ℰ and F maxima: δ_x = {:.3g} ± {:.2g} {}",
                            delta.at("mean").get<double>(), delta.at("sd").get<double>(), unit);
  panel.xlabel = fmt::format("delay δ_x [{}]", unit);
  panel.ylabel = fmt::format("{} [{}]", what, density_unit);
  panel.yrange = "[0:*]";
  // The posterior grid spans the whole prior; show the 95 % interval with its own width on each side.
  const double low = delta.at("ci95").at(0).get<double>(), high = delta.at("ci95").at(1).get<double>();
  if (high > low) panel.xrange = fmt::format("[{}:{}]", low - (high - low), high + (high - low));
  panel.series = {{.block = figure.blocks.size() - 1,
                   .title = sampled ? "bootstrap replicates of δ_x" : "posterior p(δ_x | F, ℰ)"}};
  panel.markers = {{delta.at("map").get<double>(), sampled ? "δ_x" : "MAP"}};
  // The 95 % interval the analysis reports: with the fitted maxima the replicates' spread stretched by
  // the interval factors. The density drawn is widened by the 68 % factor only, so these ends can lie
  // inside or outside its own tails.
  if (high > low) panel.markers.insert(panel.markers.end(), {{low, "95 %"}, {high, "95 %"}});
  figure.panels.push_back(std::move(panel));
  figure.height = 1100;
}

Figure run_figure(const io::CsvTable& curves, const fs::path& input, const fs::path& analysis_file) {
  const std::size_t strain_column = curves.require("strain");
  const auto& x = curves.columns[strain_column];
  const auto& energy = curves.column("elastic_energy");
  Figure figure;
  figure.name = "loading";
  std::vector<fs::path> read{curves.source};
  std::vector<Marker> markers;
  nlohmann::json analysis;
  std::optional<DataBlock> analysed;  // ℰ from the analysis pipeline
  if (fs::exists(analysis_file)) {
    read.push_back(analysis_file);
    try {
      analysis = nlohmann::json::parse(io::read_text_file(analysis_file));
      const std::string strain_unit = analysis.at("curves").at("x0").at("unit").get<std::string>();
      if (strain_unit != io::column_unit(curves.header[strain_column])) {
        throw InputError(analysis_file.string(),
                         fmt::format("strain unit '{}' differs from the curves' '{}'", strain_unit,
                                     io::column_unit(curves.header[strain_column])),
                         "rerun `rupture analyze` on these curves");
      }
      for (const char* key : {"x_p", "x_c", "x_m"}) {
        if (const auto value = json_value(analysis, key)) markers.push_back({*value, key});
      }
      analysed = analysed_rate(analysis, curves.header[strain_column], analysis_file.string());
    } catch (const nlohmann::json::exception& e) {
      // An older build's file (bare arrays where quantities are now) lands here too.
      const std::string written_by =
          analysis.is_object() && analysis.contains("version") && analysis["version"].is_string()
              ? analysis["version"].get<std::string>()
              : "an unknown version";
      throw InputError(analysis_file.string(),
                       fmt::format("not an analysis.json of this format (written by {}; this is {}): {}",
                                   written_by, version_string, e.what()),
                       "rerun `rupture analyze` to rewrite it");
    }
  }
  figure.provenance = provenance(input, read);
  const std::string strain_field = curves.header[strain_column];
  DataBlock raw{"loading curves normalised to their maxima",
                {strain_field, "F/F_max[1]", "E_e/E_e,max[1]"},
                {x, normalised(curves.column("force_top"), "the force", curves.source),
                 normalised(energy, "the elastic energy", curves.source)}};
  if (!analysed) {
    // Not analysed (or by an earlier build): centred differences of the raw E_e, noisy but honest.
    raw.title += " (energy rate by centred differences of E_e)";
    raw.header.push_back("Erate/Erate_max[1]");
    raw.columns.push_back(
        normalised(centred_difference(x, energy), "the energy rate dE_e/dx", curves.source));
    figure.blocks.push_back(std::move(raw));
    figure.panels.push_back(loading_panel(0, 3, strain_field, std::move(markers)));
  } else {
    figure.blocks.push_back(std::move(raw));
    figure.blocks.push_back(std::move(*analysed));
    figure.panels.push_back(loading_panel(1, 1, strain_field, std::move(markers)));
  }
  if (!analysis.is_null() && analysis.contains("delta_x") && !analysis["delta_x"].is_null())
    add_delay_panel(figure, analysis["delta_x"]);
  figure.caption =
      "Loading curves: force on the top plate F, elastic energy E_e and energy rate ℰ = dE_e/dx against "
      "strain, each over its maximum";
  figure.caption +=
      !analysed
          ? " (ℰ by centred differences of the recorded E_e; run `rupture analyze` for the filtered one)"
          : " (ℰ as the analysis filtered and differentiated it, over the fitted ℰ_max)";
  if (!analysis.is_null()) figure.caption += "; dashed lines mark x_p, x_c and x_m from analysis.json";
  figure.caption +=
      figure.panels.size() > 1 ? ", and the lower panel the posterior density of δ_x = x_c - x_p." : ".";
  return figure;
}

// Bonds broken per unit strain, histogrammed over the run's strain range.
std::optional<Figure> breaks_figure(const io::CsvTable& breaks, const io::CsvTable& curves,
                                    const fs::path& input) {
  const std::size_t strain_column = breaks.require("strain");
  const auto& strain = breaks.columns[strain_column];
  if (strain.empty()) return std::nullopt;  // nothing broke: no histogram to draw
  const auto& run_strain = curves.column("strain");
  const double end = std::max(*std::max_element(run_strain.begin(), run_strain.end()),
                              *std::max_element(strain.begin(), strain.end()));
  if (!(end > 0.0)) return std::nullopt;
  const double width = end / break_bins;
  std::vector<double> centre(break_bins), rate(break_bins, 0.0);
  for (int b = 0; b < break_bins; ++b) centre[b] = (b + 0.5) * width;
  for (double s : strain) rate[std::clamp(static_cast<int>(s / width), 0, break_bins - 1)] += 1.0 / width;
  const std::string unit = io::column_unit(breaks.header[strain_column]);
  Figure figure;
  figure.name = "breaking_rate";
  figure.provenance = provenance(input, {breaks.source, curves.source});
  figure.blocks.push_back(
      {fmt::format("bonds broken per unit strain, {} bins of {} {}", break_bins, width, unit),
       {fmt::format("strain[{}]", unit), fmt::format("rate[1/{}]", unit)},
       {centre, rate}});
  Panel panel;
  panel.title = fmt::format("Bond-breaking rate ({} bonds broken)", strain.size());
  panel.xlabel = fmt::format("strain x [{}]", unit);
  panel.ylabel = fmt::format("bonds broken per strain [1/{}]", unit);
  panel.yrange = "[0:*]";
  panel.series = {{.title = "bond-breaking rate", .style = Style::boxes}};
  figure.panels.push_back(std::move(panel));
  figure.caption = fmt::format(
      "Bond-breaking rate: bonds broken per unit strain in {} bins; bar height times bin width "
      "counts each of the {} broken bonds once.",
      break_bins, strain.size());
  return figure;
}

bool is_run_curves(const io::CsvTable& table) { return table.find("force_top").has_value(); }

}  // namespace

fs::path Drawn::png() const {
  for (const auto& file : files)
    if (file.extension() == ".png") return file;
  return {};
}

bool is_scan_folder(const fs::path& input) {
  return fs::is_directory(input) && !fs::exists(input / "curves.csv") &&
         (fs::exists(input / "results.csv") || fs::exists(input / "scan.json"));
}

fs::path default_out(const fs::path& input) {
  return fs::is_directory(input) ? input / "figures" : input.parent_path() / "figures";
}

namespace {

// The snapshots to draw: at the strains asked for, else near x_p and x_c (from analysis.json) and the
// last one, else a third, two thirds and the end of the recorded ones.
std::vector<SnapshotFile> chosen_snapshots(const std::vector<SnapshotFile>& all,
                                           const fs::path& analysis_file, const std::vector<double>& wanted) {
  if (all.empty()) return {};
  if (!wanted.empty()) return nearest_snapshots(all, wanted);
  std::vector<double> strains;
  if (fs::exists(analysis_file)) {
    const auto analysis = nlohmann::json::parse(io::read_text_file(analysis_file), nullptr, false);
    for (const char* key : {"x_p", "x_c"}) {
      if (analysis.is_object() && analysis.contains(key))
        strains.push_back(io::quantity_value(analysis[key]).value_or(nan));
    }
  }
  strains.erase(std::remove_if(strains.begin(), strains.end(), [](double v) { return !std::isfinite(v); }),
                strains.end());
  if (strains.empty()) strains = {all[all.size() / 3].strain, all[2 * all.size() / 3].strain};
  strains.push_back(all.back().strain);
  return nearest_snapshots(all, strains);
}

std::vector<Figure> run_figures(const io::CsvTable& curves, const fs::path& input,
                                const PlotOptions& options) {
  const fs::path run_folder = curves.source.empty() ? fs::path() : fs::path(curves.source).parent_path();
  std::vector<Figure> figures;
  figures.push_back(run_figure(curves, input, run_folder / "analysis.json"));
  std::optional<io::CsvTable> breaks;
  if (fs::exists(run_folder / "breaks.csv")) {
    breaks = io::read_csv(run_folder / "breaks.csv");
    if (auto figure = breaks_figure(*breaks, curves, input)) figures.push_back(std::move(*figure));
  }
  const auto all = list_snapshots(run_folder, curves);
  if (all.empty() && !options.snapshot_strains.empty()) {
    throw InputError((run_folder / "snapshots").string(), "no snapshots recorded in this run",
                     "rerun with output.snapshot_interval > 0, or drop --snapshots-at");
  }
  const auto chosen = chosen_snapshots(all, run_folder / "analysis.json", options.snapshot_strains);
  if (!chosen.empty()) {
    const std::size_t strain_column = curves.require("strain");
    figures.push_back(snapshots_figure(chosen, io::column_unit(curves.header[strain_column]),
                                       provenance(input, {curves.source}), breaks ? &*breaks : nullptr));
  }
  return figures;
}

}  // namespace

std::vector<Drawn> plot(const fs::path& input, const fs::path& out, const PlotOptions& options) {
  if (!fs::exists(input)) {
    throw InputError(input.string(), "no such file or folder",
                     "give a run folder, a scan folder or a curves CSV");
  }
  std::vector<Figure> figures;
  if (is_scan_folder(input)) {
    figures = scan_figures(input, provenance(input, {input / "results.csv"}));
  } else {
    const bool folder = fs::is_directory(input);
    const fs::path curves_file = folder ? input / "curves.csv" : input;
    if (folder && !fs::exists(curves_file)) {
      throw InputError(
          input.string(), "no curves.csv or results.csv in this folder",
          "give a folder written by `rupture run` or `rupture scan`, or the path of a curves CSV");
    }
    const io::CsvTable curves = io::read_csv(curves_file);
    if (curves.rows() < 3) {
      throw InputError(curves_file.string(),
                       fmt::format("{} rows; a loading curve needs at least 3", curves.rows()),
                       "plot a longer run");
    }
    if (is_run_curves(curves))
      figures = run_figures(curves, input, options);
    else
      figures.push_back(fbm_figure(curves, input));
  }
  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw RunError(fmt::format("cannot create {}: {}", out.string(), error.message()));
  std::vector<Drawn> drawn;
  for (const auto& figure : figures)
    drawn.push_back({figure.name, figure.caption, draw(figure, out, options.formats)});
  return drawn;
}

}  // namespace rupture::figures
