#include "analysis/curve_file.hpp"

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/quantity.hpp"
#include "rupture/version.hpp"

namespace rupture::analysis {

namespace {

// The filter as `rupture analyze --filter` names it.
const char* filter_option(FilterKind kind) {
  switch (kind) {
    case FilterKind::butterworth:
      return "butterworth";
    case FilterKind::savitzky_golay:
      return "savgol";
    case FilterKind::none:
      return "none";
  }
  return "?";
}

nlohmann::json inputs_json(const CurveFileInputs& in, const std::string& breaks_used) {
  const auto& a = in.options;
  const auto& c = in.columns;
  return {{"curves", in.curves.string()},
          {"breaks", breaks_used.empty() ? nlohmann::json(nullptr) : nlohmann::json(breaks_used)},
          {"columns", {{"strain", c.strain}, {"force", c.force}, {"energy", c.energy}}},
          {"scales", {{"strain", c.strain_scale}, {"force", c.force_scale}, {"energy", c.energy_scale}}},
          {"filter", filter_option(a.filter.kind)},
          {"cutoff", a.filter.cutoff},
          {"butterworth_order", a.filter.butterworth_order},
          {"savgol_window", a.filter.savgol_window},
          {"savgol_order", a.filter.savgol_order},
          {"derivative_window", a.derivative_window},
          {"peak_drop", a.peak.drop},
          {"delay_method", to_string(a.delay_method)},
          {"force_peak_form", to_string(a.force_peak_form)},
          {"smoothing_floor_share", a.smoothing_floor_share},
          {"replicates", a.uncertainty.replicates},
          {"bootstrap_seed", a.uncertainty.seed},
          {"walk_profile", a.uncertainty.walk_profile},
          {"delay_window_drop", a.delay.window_drop},
          {"grid_points", a.delay.grid_points}};
}

// The mean heights (mm) of the glued layers from a rupture run.json beside the breaks (a run of
// another code has none: its breaks then carry no heights).
std::optional<std::pair<double, double>> glued_layer_heights(const std::filesystem::path& run_json) {
  if (!std::filesystem::exists(run_json)) return std::nullopt;
  try {
    const auto run = nlohmann::json::parse(io::read_text_file(run_json, io::max_config_bytes));
    const auto& layers = run.at("sample").at("glued_layer_heights");
    const auto bottom = io::quantity_value(layers.at("bottom")), top = io::quantity_value(layers.at("top"));
    if (!bottom || !top) return std::nullopt;
    return std::pair{*bottom, *top};
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // a run.json of rupture 0.1, or not rupture's
  }
}

}  // namespace

CurveFileAnalysis analyze_curve_file(const CurveFileInputs& in, const std::string& tool) {
  const auto table = io::read_csv(in.curves);
  const auto curve = select_curve(table, in.columns);
  std::string breaks_path = in.no_breaks ? std::string() : in.breaks;
  if (breaks_path.empty() && !in.no_breaks) {
    const auto beside = in.curves.parent_path() / "breaks.csv";
    if (std::filesystem::exists(beside)) breaks_path = beside.string();
  }
  BreakLog breaks;
  if (!breaks_path.empty())
    breaks =
        select_breaks(io::read_csv(breaks_path), in.columns.strain_scale,
                      glued_layer_heights(std::filesystem::path(breaks_path).parent_path() / "run.json"));
  CurveFileAnalysis out;
  out.result = analyze_curve(curve, in.options, breaks);
  out.document = {{"tool", tool}, {"version", version_string}, {"inputs", inputs_json(in, breaks_path)}};
  out.document.update(to_json(out.result));
  return out;
}

}  // namespace rupture::analysis
