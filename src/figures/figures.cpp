#include "figures/figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
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
    throw InputError(source, fmt::format("{} is never positive, so it cannot be normalised to its maximum", what),
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

// Block 0 and the top panel shared by every loading-curve figure: F, E_e and ℰ, each over its maximum.
void add_loading_curves(Figure& figure, const std::string& strain_field, const std::vector<double>& x,
                        const std::vector<double>& force, const std::vector<double>& energy,
                        const std::vector<double>& rate, const std::string& rate_note, std::vector<Marker> markers,
                        const std::string& source) {
  const std::string unit = io::column_unit(strain_field).empty() ? "1" : io::column_unit(strain_field);
  figure.blocks.push_back({"loading curves normalised to their maxima" + rate_note,
                           {strain_field, "F/F_max[1]", "E_e/E_e,max[1]", "Erate/Erate_max[1]"},
                           {x, normalised(force, "the force", source), normalised(energy, "the elastic energy", source),
                            normalised(rate, "the energy rate dE_e/dx", source)}});
  Panel panel;
  panel.title = "Loading curves, each divided by its maximum";
  panel.xlabel = fmt::format("strain x [{}]", unit);
  panel.ylabel = "normalised value [1]";
  // Negative parts (unloading after failure) fall below the frame, as in the paper's figures.
  panel.yrange = "[0:1.12]";
  panel.series = {{0, 0, 1, "force F/F_{max}"},
                  {0, 0, 2, "elastic energy E_e/E_{e,max}"},
                  {0, 0, 3, "energy rate ℰ/ℰ_{max}, ℰ = dE_e/dx"}};
  panel.markers = std::move(markers);
  figure.panels.push_back(std::move(panel));
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
  std::vector<Marker> markers{{x[argmax(rate)], "x_p"}, {x[argmax(force)], "x_c"}, {x[argmax(energy)], "x_m"}};
  add_loading_curves(figure, table.header[table.require("strain")], x, force, energy, rate, "", std::move(markers),
                     table.source);
  figure.panels.front().title = "Fiber bundle: F, E_e and ℰ over their maxima";
  return figure;
}

std::optional<double> json_value(const nlohmann::json& analysis, const char* key) {
  const auto it = analysis.find(key);
  if (it == analysis.end() || it->is_null()) return std::nullopt;
  return it->at("value").get<double>();
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
  if (fs::exists(analysis_file)) {
    read.push_back(analysis_file);
    try {
      analysis = nlohmann::json::parse(io::read_text_file(analysis_file));
      const std::string strain_unit = analysis.at("units").at("strain").get<std::string>();
      if (strain_unit != io::column_unit(curves.header[strain_column])) {
        throw InputError(analysis_file.string(), fmt::format("strain unit '{}' differs from the curves' '{}'", strain_unit,
                                                             io::column_unit(curves.header[strain_column])),
                         "rerun `rupture analyze` on these curves");
      }
      for (const char* key : {"x_p", "x_c", "x_m"}) {
        if (const auto value = json_value(analysis, key)) markers.push_back({*value, key});
      }
    } catch (const nlohmann::json::exception& e) {
      throw InputError(analysis_file.string(), fmt::format("not an analysis.json: {}", e.what()),
                       "rerun `rupture analyze` to rewrite it");
    }
  }
  figure.provenance = provenance(input, read);
  add_loading_curves(figure, curves.header[strain_column], x, curves.column("force_top"), energy,
                     centred_difference(x, energy), " (energy rate by centred differences of E_e)", std::move(markers),
                     curves.source);
  if (!analysis.is_null() && analysis.contains("delta_x") && !analysis["delta_x"].is_null()) {
    const auto& delta = analysis["delta_x"];
    const auto& posterior = delta.at("posterior");
    const std::string unit = posterior.at("delta_unit").get<std::string>();
    const std::string density_unit = posterior.at("density_unit").get<std::string>();
    figure.blocks.push_back({"posterior density of the delay delta_x",
                             {fmt::format("delta_x[{}]", unit), fmt::format("density[{}]", density_unit)},
                             {posterior.at("delta").get<std::vector<double>>(), posterior.at("density").get<std::vector<double>>()}});
    Panel panel;
    panel.title = fmt::format("Delay between the ℰ and F maxima: δ_x = {:.3g} ± {:.2g} {}", delta.at("mean").get<double>(),
                              delta.at("sd").get<double>(), unit);
    panel.xlabel = fmt::format("delay δ_x [{}]", unit);
    panel.ylabel = fmt::format("posterior density [{}]", density_unit);
    panel.yrange = "[0:*]";
    panel.series = {{1, 0, 1, "posterior p(δ_x | F, ℰ)"}};
    panel.markers = {{delta.at("map").get<double>(), "MAP"}};
    figure.panels.push_back(std::move(panel));
    figure.height = 1100;
  }
  return figure;
}

// Bonds broken per unit strain, histogrammed over the run's strain range.
std::optional<Figure> breaks_figure(const io::CsvTable& breaks, const io::CsvTable& curves, const fs::path& input) {
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
  figure.blocks.push_back({fmt::format("bonds broken per unit strain, {} bins of {} {}", break_bins, width, unit),
                           {fmt::format("strain[{}]", unit), fmt::format("rate[1/{}]", unit)}, {centre, rate}});
  Panel panel;
  panel.title = fmt::format("Bond-breaking rate ({} bonds broken)", strain.size());
  panel.xlabel = fmt::format("strain x [{}]", unit);
  panel.ylabel = fmt::format("bonds broken per strain [1/{}]", unit);
  panel.yrange = "[0:*]";
  panel.series = {{0, 0, 1, "bond-breaking rate", "boxes"}};
  figure.panels.push_back(std::move(panel));
  return figure;
}

bool is_run_curves(const io::CsvTable& table) { return table.find("force_top").has_value(); }

}  // namespace

fs::path default_out(const fs::path& input) {
  return fs::is_directory(input) ? input / "figures" : input.parent_path() / "figures";
}

std::vector<fs::path> plot(const fs::path& input, const fs::path& out, Format format) {
  if (!fs::exists(input)) {
    throw InputError(input.string(), "no such file or folder", "give a run folder or a curves CSV");
  }
  const bool folder = fs::is_directory(input);
  const fs::path curves_file = folder ? input / "curves.csv" : input;
  if (folder && !fs::exists(curves_file)) {
    throw InputError(input.string(), "no curves.csv in this folder",
                     "give a folder written by `rupture run` or the path of a curves CSV");
  }
  const io::CsvTable curves = io::read_csv(curves_file);
  if (curves.rows() < 3) {
    throw InputError(curves_file.string(), fmt::format("{} rows; a loading curve needs at least 3", curves.rows()),
                     "plot a longer run");
  }
  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw RunError(fmt::format("cannot create {}: {}", out.string(), error.message()));

  std::vector<Figure> figures;
  if (is_run_curves(curves)) {
    const fs::path run_folder = curves_file.parent_path();
    figures.push_back(run_figure(curves, input, run_folder / "analysis.json"));
    if (fs::exists(run_folder / "breaks.csv")) {
      if (auto figure = breaks_figure(io::read_csv(run_folder / "breaks.csv"), curves, input)) figures.push_back(std::move(*figure));
    }
  } else {
    figures.push_back(fbm_figure(curves, input));
  }
  std::vector<fs::path> written;
  for (const auto& figure : figures) {
    const auto files = draw(figure, out, format);
    written.insert(written.end(), files.begin(), files.end());
  }
  return written;
}

}  // namespace rupture::figures
