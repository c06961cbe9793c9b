// python/module: the `rupture._rupture` extension — the C++ API the command line uses, for Python.
// Numbers go out as numpy arrays (a sample's particles and bonds as views into the C++ sample, no
// copy), results as the same JSON documents the CLI writes (as dicts). The Python package around it
// (src/python/rupture/) adds DataFrames, config dicts and the readers of run and scan folders.
// Errors: InputError -> rupture.InputError (a ValueError), RunError -> rupture.RunError (a RuntimeError).
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/analysis.hpp"
#include "analysis/curve_file.hpp"
#include "analysis/option_words.hpp"
#include "core/error.hpp"
#include "fbm/bundle.hpp"
#include "fbm/distribution.hpp"
#include "fbm/els_theory.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "loading/config.hpp"
#include "loading/run.hpp"
#include "rupture/version.hpp"
#include "sample/formats.hpp"
#include "sample/generator.hpp"
#include "sample/presets.hpp"
#include "sample/stats.hpp"

namespace py = pybind11;
using nlohmann::json;

namespace rupture {
namespace {

py::object to_python(const json& value) {
  switch (value.type()) {
    case json::value_t::null:
      return py::none();
    case json::value_t::boolean:
      return py::bool_(value.get<bool>());
    case json::value_t::number_integer:
      return py::int_(value.get<std::int64_t>());
    case json::value_t::number_unsigned:
      return py::int_(value.get<std::uint64_t>());
    case json::value_t::number_float:
      return py::float_(value.get<double>());
    case json::value_t::string:
      return py::str(value.get<std::string>());
    case json::value_t::array: {
      py::list list;
      for (const auto& item : value) list.append(to_python(item));
      return list;
    }
    default: {
      py::dict dict;
      for (const auto& [key, item] : value.items()) dict[py::str(key)] = to_python(item);
      return dict;
    }
  }
}

std::unique_ptr<fbm::StrengthDistribution> distribution(const std::string& spec) {
  return fbm::parse_distribution_spec(spec, [](const std::string& path) { return io::read_text_file(path); });
}

// A sampled FBM curve as columns (copies: curves are small beside samples).
py::dict curve_columns(const std::vector<fbm::CurvePoint>& curve) {
  const auto column = [&](double fbm::CurvePoint::*field) {
    py::array_t<double> out(static_cast<py::ssize_t>(curve.size()));
    auto view = out.mutable_unchecked<1>();
    for (std::size_t i = 0; i < curve.size(); ++i) view(py::ssize_t(i)) = curve[i].*field;
    return out;
  };
  py::dict columns;
  columns["strain"] = column(&fbm::CurvePoint::x);
  columns["force"] = column(&fbm::CurvePoint::F);
  columns["elastic_energy"] = column(&fbm::CurvePoint::E_e);
  columns["damage_energy"] = column(&fbm::CurvePoint::E_d);
  columns["energy_rate"] = column(&fbm::CurvePoint::Erate);
  columns["broken_fraction"] = column(&fbm::CurvePoint::broken_fraction);
  return columns;
}

// The ELS theory evaluated at the strains a user chose (continuous distributions only).
py::dict theory_at(const std::string& spec,
                   const py::array_t<double, py::array::c_style | py::array::forcecast>& x) {
  const auto dist = distribution(spec);
  const auto* continuous = dynamic_cast<const fbm::ContinuousDistribution*>(dist.get());
  if (continuous == nullptr)
    throw InputError("dist", "'" + spec + "' is a list of thresholds, whose curve has no closed form",
                     "call curves(dist) without strains, or simulate() the bundle");
  const fbm::ElsTheory theory(*continuous);
  std::vector<fbm::CurvePoint> curve;
  const auto in = x.unchecked<1>();
  for (py::ssize_t i = 0; i < in.shape(0); ++i) {
    const double s = in(i);
    curve.push_back({s, theory.force(s), theory.elastic_energy(s), theory.damage_energy(s),
                     theory.energy_rate(s), continuous->cdf(s)});
  }
  return curve_columns(curve);
}

py::dict simulate(const std::string& spec, std::size_t fibers, std::uint64_t seed, const std::string& control,
                  const std::string& sharing, std::size_t points) {
  if (control != "strain" && control != "load")
    throw InputError("control", "'" + control + "' is not a loading control", "use \"strain\" or \"load\"");
  if (sharing != "els" && sharing != "lls")
    throw InputError("sharing", "'" + sharing + "' is not a load sharing", "use \"els\" or \"lls\"");
  if (control == "strain" && sharing == "lls")
    throw InputError("sharing", "local load sharing is simulated under load control only",
                     "use control=\"load\" with sharing=\"lls\"");
  const auto dist = distribution(spec);
  py::dict out;
  fbm::BundleCurve result;
  {
    py::gil_scoped_release release;
    auto thresholds = fbm::draw_thresholds(*dist, fibers, seed);
    if (control == "strain") {
      result = fbm::strain_controlled(std::move(thresholds), points);
    } else {
      auto load = sharing == "els" ? fbm::load_controlled_els(std::move(thresholds), points)
                                   : fbm::load_controlled_lls(thresholds, points);
      result = std::move(load.result);
      py::gil_scoped_acquire acquire;
      py::dict bursts;
      for (const auto& [size, count] : load.burst_counts) bursts[py::int_(size)] = count;
      out["bursts"] = bursts;
      out["final_burst"] = load.final_burst;
    }
  }
  out["curve"] = curve_columns(result.curve);
  out["measured"] = to_python(fbm::to_json(result.measured));
  return out;
}

// ---- samples: numpy views into the C++ sample (the Python object keeps it alive) -------------------

using SamplePtr = std::shared_ptr<Sample>;

py::array positions_view(const SamplePtr& s) {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 must be three packed doubles");
  return py::array_t<double>({py::ssize_t(s->size()), py::ssize_t(3)},
                             {py::ssize_t(sizeof(Vec3)), py::ssize_t(sizeof(double))},
                             reinterpret_cast<double*>(s->position.data()), py::cast(s));
}

template <class T>
py::array vector_view(std::vector<T>& values, const SamplePtr& owner) {
  return py::array_t<T>({py::ssize_t(values.size())}, {py::ssize_t(sizeof(T))}, values.data(),
                        py::cast(owner));
}

py::array groups_view(const SamplePtr& s) {
  return py::array_t<std::uint8_t>({py::ssize_t(s->size())}, {py::ssize_t(sizeof(ParticleGroup))},
                                   reinterpret_cast<std::uint8_t*>(s->group.data()), py::cast(s));
}

// Bonds are (i, j, rest length) records: two strided views into the same memory.
py::array bond_pairs_view(const SamplePtr& s) {
  return py::array_t<std::uint32_t>({py::ssize_t(s->bonds.size()), py::ssize_t(2)},
                                    {py::ssize_t(sizeof(Bond)), py::ssize_t(sizeof(std::uint32_t))},
                                    s->bonds.empty() ? nullptr : &s->bonds.front().i, py::cast(s));
}

py::array rest_lengths_view(const SamplePtr& s) {
  return py::array_t<double>({py::ssize_t(s->bonds.size())}, {py::ssize_t(sizeof(Bond))},
                             s->bonds.empty() ? nullptr : &s->bonds.front().rest_length, py::cast(s));
}

// A sample from a user's arrays: bonds are optional (then made from the gaps, as the generator does),
// glued layers from `groups` or from the particles' heights.
SamplePtr sample_from_arrays(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& positions,
    const py::array_t<double, py::array::c_style | py::array::forcecast>& radii,
    const std::optional<py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>>& groups,
    const std::optional<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>& bonds,
    double bond_tolerance, double density) {
  if (positions.ndim() != 2 || positions.shape(1) != 3)
    throw InputError("positions", "must be an (n, 3) array of x, y, z in mm",
                     "pass positions.reshape(-1, 3)");
  const auto n = positions.shape(0);
  if (radii.ndim() != 1 || radii.shape(0) != n)
    throw InputError("radii", "must hold one radius (mm) per particle", "pass an array of length n");
  auto sample = std::make_shared<Sample>();
  sample->density = density;
  const auto p = positions.unchecked<2>();
  const auto r = radii.unchecked<1>();
  Vec3 lower{1e300, 1e300, 1e300}, upper{-1e300, -1e300, -1e300};
  for (py::ssize_t k = 0; k < n; ++k) {
    const Vec3 at{p(k, 0), p(k, 1), p(k, 2)};
    if (!(r(k) > 0.0) || !std::isfinite(at.x) || !std::isfinite(at.y) || !std::isfinite(at.z))
      throw InputError(fmt::format("particle {}", k), "has a radius <= 0 or a coordinate that is not finite",
                       "give finite positions and positive radii (mm)");
    sample->id.push_back(k);
    sample->position.push_back(at);
    sample->radius.push_back(r(k));
    sample->group.push_back(ParticleGroup::free);
    lower = {std::min(lower.x, at.x - r(k)), std::min(lower.y, at.y - r(k)), std::min(lower.z, at.z - r(k))};
    upper = {std::max(upper.x, at.x + r(k)), std::max(upper.y, at.y + r(k)), std::max(upper.z, at.z + r(k))};
  }
  sample->box = {lower, upper};
  if (bonds) {
    if (bonds->ndim() != 2 || bonds->shape(1) != 2)
      throw InputError("bonds", "must be an (m, 2) array of particle indices", "pass pairs (i, j)");
    const auto b = bonds->unchecked<2>();
    for (py::ssize_t k = 0; k < b.shape(0); ++k) {
      auto i = b(k, 0), j = b(k, 1);
      if (i < 0 || j < 0 || i >= n || j >= n || i == j)
        throw InputError(fmt::format("bonds row {}", k),
                         fmt::format("({}, {}) is not a pair of particles 0..{}", i, j, n - 1),
                         "give two different particle indices per bond");
      if (i > j) std::swap(i, j);
      sample->bonds.push_back(
          {std::uint32_t(i), std::uint32_t(j), norm(sample->position[j] - sample->position[i])});
    }
    std::sort(sample->bonds.begin(), sample->bonds.end(),
              [](const Bond& a, const Bond& c) { return a.i != c.i ? a.i < c.i : a.j < c.j; });
  } else {
    make_bonds(*sample, bond_tolerance);
  }
  if (groups) {
    if (groups->ndim() != 1 || groups->shape(0) != n)
      throw InputError("groups", "must hold one group per particle (0 free, 1 bottom, 2 top)",
                       "pass an array of length n");
    const auto g = groups->unchecked<1>();
    for (py::ssize_t k = 0; k < n; ++k) {
      if (g(k) > 2)
        throw InputError(fmt::format("groups[{}]", k), "is not 0, 1 or 2", "0 free, 1 bottom, 2 top");
      sample->group[std::size_t(k)] = ParticleGroup(g(k));
    }
  } else {
    assign_glued_layers(*sample);
  }
  sample->provenance.push_back(
      fmt::format("rupture {} python: sample_from_arrays, {} particles", version_string, n));
  return sample;
}

// ---- runs --------------------------------------------------------------------------------------

// The run's progress hook for Python: after each curve row, with the GIL held, Python's pending signals
// are checked and the progress callback (if any) is called. Ctrl-C or an exception from the callback
// stops the run with a checkpoint; the exception is kept in `raised` and thrown after the run.
loading::RunOptions python_run_options(const std::optional<py::function>& progress,
                                       std::optional<py::error_already_set>& raised) {
  loading::RunOptions options;
  options.on_row = [&progress, &raised](const loading::RunProgress& p) {
    py::gil_scoped_acquire acquire;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (progress) {
        py::dict state;
        state["steps"] = p.steps;
        state["strain_percent"] = p.strain;
        state["force_N"] = p.force;
        state["broken_bonds"] = p.broken_bonds;
        (*progress)(state);
      }
    } catch (py::error_already_set& e) {
      raised = std::move(e);
      return false;
    }
    return true;
  };
  return options;
}

py::dict summary_dict(const loading::RunSummary& summary, const std::filesystem::path& folder) {
  py::dict out;
  out["status"] = summary.status;
  out["stop_reason"] = summary.stop_reason;
  out["steps"] = summary.steps;
  out["strain_percent"] = summary.strain;
  out["broken_bonds"] = summary.broken_bonds;
  out["wall_s"] = summary.wall_seconds;
  out["max_relative_energy_error"] = summary.max_relative_energy_error;
  out["folder"] = folder;
  out["checkpoint"] =
      summary.checkpoint.empty() ? py::object(py::none()) : py::str(summary.checkpoint.string());
  return out;
}

// Runs with the GIL released (python_run_options for the rest). The config is a TOML file (relative
// sample paths from its folder) or, when `config_file` is empty, TOML text; the run goes into the
// config's output.folder.
py::dict run(const std::filesystem::path& config_file, const std::string& toml_text,
             const std::vector<std::string>& overrides, const std::string& command, bool overwrite,
             const std::optional<py::function>& progress) {
  const loading::RunConfig config = config_file.empty()
                                        ? loading::parse_config(toml_text, "<dict>", overrides)
                                        : loading::load_config(config_file, overrides);
  std::optional<py::error_already_set> raised;
  loading::RunOptions options = python_run_options(progress, raised);
  options.existing = overwrite ? loading::Existing::overwrite : loading::Existing::refuse;
  loading::RunSummary summary;
  {
    py::gil_scoped_release release;
    const Sample sample = loading::resolve_sample(config);
    summary = loading::run_simulation(config, sample, config.output_folder, command, options);
  }
  if (raised) throw std::move(*raised);
  return summary_dict(summary, config.output_folder);
}

// Continues an interrupted run from its newest checkpoint, as `rupture run --resume`.
py::dict resume(const std::filesystem::path& folder, const std::string& command,
                const std::optional<py::function>& progress) {
  std::optional<py::error_already_set> raised;
  const loading::RunOptions options = python_run_options(progress, raised);
  loading::RunSummary summary;
  {
    py::gil_scoped_release release;
    summary = loading::resume_simulation(folder, command, options);
  }
  if (raised) throw std::move(*raised);
  return summary_dict(summary, folder);
}

// ---- analysis ----------------------------------------------------------------------------------

// The value a keyword's word names, or an InputError naming the keyword, the word and the words allowed
// (`what`: what the word should have been; `or_else`: a fix beside the words, e.g. None's meaning).
template <class Value, std::size_t N>
Value chosen_word(const char* keyword, const py::handle& value,
                  const std::array<analysis::OptionWord<Value>, N>& words, std::string_view what,
                  std::string_view or_else = {}) {
  const auto word = value.cast<std::string>();
  const auto chosen = analysis::from_word(words, word);
  if (!chosen)
    throw InputError(keyword, fmt::format("'{}' is not {}", word, what),
                     fmt::format("use {}{}", analysis::quoted_words(words), or_else));
  return *chosen;
}

// What a row holds, from the keyword `rows` ("instants" or "interval-means"; absent or None: as the
// columns say, analysis::ColumnChoice::rows).
std::optional<analysis::RowKind> row_kind(const py::kwargs& given) {
  if (!given.contains("rows") || given["rows"].is_none()) return std::nullopt;
  return chosen_word("rows", given["rows"], analysis::row_kind_words, "what a row holds",
                     " (or None: as the columns say)");
}

// rupture.analyze's options, by keyword (the package passes all seven, with its defaults; docs/python.md
// names them): each keyword's reader checks its value and sets it. A new option is one more entry here,
// not one more argument down the call chain.
analysis::AnalysisOptions analysis_options(const py::kwargs& given) {
  using Reader = void (*)(const py::handle&, analysis::AnalysisOptions&);
  static const std::map<std::string, Reader, std::less<>> readers{
      {"rows", [](const py::handle&, analysis::AnalysisOptions&) {}},  // the curve's, not the analysis's
      {"delay_method",
       [](const py::handle& value, analysis::AnalysisOptions& options) {
         options.delay_method = chosen_word("delay_method", value, analysis::delay_method_words, "a method");
       }},
      {"force_peak_form",
       [](const py::handle& value, analysis::AnalysisOptions& options) {
         options.force_peak_form =
             chosen_word("force_peak_form", value, analysis::peak_form_words, "a form of the force's peak");
       }},
      {"replicates",
       [](const py::handle& value, analysis::AnalysisOptions& options) {
         const auto replicates = value.cast<long long>();
         if (replicates != 0 &&
             (replicates < analysis::min_replicates || replicates > analysis::max_replicates))
           throw InputError(
               "replicates", fmt::format("{} replicates", replicates),
               fmt::format("give 0 (the default {}) or {} to {}", analysis::BootstrapOptions{}.replicates,
                           analysis::min_replicates, analysis::max_replicates));
         if (replicates > 0) options.uncertainty.replicates = static_cast<int>(replicates);
       }},
      {"seed",
       [](const py::handle& value, analysis::AnalysisOptions& options) {
         const auto seed = value.cast<long long>();
         if (seed < 0) throw InputError("seed", fmt::format("{} is negative", seed), "give a seed >= 0");
         options.uncertainty.seed = static_cast<std::uint64_t>(seed);
       }},
      {"walk_profile",
       [](const py::handle& value, analysis::AnalysisOptions& options) {
         options.uncertainty.walk_profile = value.cast<bool>();
       }},
      {"smoothing_floor",
       [](const py::handle& value, analysis::AnalysisOptions& options) {
         const auto share = value.cast<double>();
         if (!(share >= 0.0 && share <= analysis::max_smoothing_floor_share))
           throw InputError("smoothing_floor",
                            fmt::format("{} is not a share of the rise to the force peak", share),
                            fmt::format("give a value in [0, {:g}] (0: the noise alone chooses the filter)",
                                        analysis::max_smoothing_floor_share));
         options.smoothing_floor_share = share;
       }},
  };
  analysis::AnalysisOptions options;
  for (const auto& [key, value] : given) {
    const auto name = key.cast<std::string>();
    const auto reader = readers.find(name);
    if (reader == readers.end()) {
      std::vector<std::string> names;
      for (const auto& [known, unused] : readers) names.push_back(known);
      throw InputError("analyze", "'" + name + "' is not an option",
                       "use " + analysis::listed(names, " or "));
    }
    reader->second(value, options);
  }
  return options;
}

py::dict analyze_arrays(std::vector<double> strain, std::vector<double> force, std::vector<double> energy,
                        const std::string& strain_unit, const std::string& force_unit,
                        const std::string& energy_unit, const py::kwargs& given) {
  if (strain.size() != force.size() || strain.size() != energy.size())
    throw InputError("analyze",
                     fmt::format("strain, force and energy have {}, {} and {} values", strain.size(),
                                 force.size(), energy.size()),
                     "pass three arrays of one length");
  analysis::Curve curve;
  curve.source = "<arrays>";
  curve.strain = std::move(strain);
  curve.force = std::move(force);
  curve.energy = std::move(energy);
  curve.strain_unit = strain_unit;
  curve.force_unit = force_unit;
  curve.energy_unit = energy_unit;
  curve.strain_column = "strain";
  curve.force_column = "force";
  curve.energy_column = "elastic_energy";
  curve.rows = row_kind(given).value_or(analysis::RowKind::instants);
  const auto options = analysis_options(given);
  json document;
  {
    py::gil_scoped_release release;
    document = {{"tool", "rupture.analyze"}, {"version", version_string}};
    document.update(analysis::to_json(analysis::analyze_curve(curve, options)));
  }
  return to_python(document);
}

// The columns (strain, force, energy) rupture analyze reads from a table with this header
// (analysis::find_curve_columns), and what their rows hold: a DataFrame is read as its file would be.
std::tuple<std::size_t, std::size_t, std::size_t, std::string_view> columns_read(
    const std::vector<std::string>& header) {
  io::CsvTable table;
  table.source = "analyze: the DataFrame";
  table.header = header;
  const auto columns = analysis::find_curve_columns(table);
  return {columns.strain, columns.force, columns.energy,
          analysis::word_of(analysis::row_kind_words, columns.rows)};
}

py::dict analyze_file(const std::filesystem::path& curves, const py::kwargs& given) {
  analysis::CurveFileInputs inputs;
  inputs.curves = curves;
  inputs.columns.rows = row_kind(given);
  inputs.options = analysis_options(given);
  json document;
  {
    py::gil_scoped_release release;
    document = analysis::analyze_curve_file(inputs, "rupture.analyze").document;
  }
  return to_python(document);
}

}  // namespace
}  // namespace rupture

// The binding table (90 lines): one statement per Python name, in the order docs/python.md lists them.
PYBIND11_MODULE(_rupture, m) {
  using namespace rupture;
  m.doc() = "rupture's C++ core (use the `rupture` package, not this module)";
  m.attr("version") = version_string;
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<RunError> run_error(m, "RunError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const RunError& e) {
      run_error(e.what());
    }
  });

  m.def(
      "fbm_theory",
      [](const std::string& spec) {
        return to_python(fbm::to_json(fbm::theory_characteristics(*distribution(spec))));
      },
      py::arg("dist"));
  m.def(
      "fbm_curve",
      [](const std::string& spec, std::size_t points) {
        return curve_columns(fbm::theory_curve(*distribution(spec), points));
      },
      py::arg("dist"), py::arg("points"));
  m.def("fbm_theory_at", &theory_at, py::arg("dist"), py::arg("strain"));
  m.def("fbm_simulate", &simulate, py::arg("dist"), py::arg("fibers"), py::arg("seed"), py::arg("control"),
        py::arg("sharing"), py::arg("points"));

  py::class_<Sample, SamplePtr>(m, "Sample")
      .def_property_readonly("positions", &positions_view, "(n, 3) float64 view, mm")
      .def_property_readonly(
          "radii", [](const SamplePtr& s) { return vector_view(s->radius, s); }, "(n,) float64 view, mm")
      .def_property_readonly(
          "ids", [](const SamplePtr& s) { return vector_view(s->id, s); }, "(n,) int64 view")
      .def_property_readonly("groups", &groups_view, "(n,) uint8 view: 0 free, 1 bottom plate, 2 top plate")
      .def_property_readonly("bonds", &bond_pairs_view, "(m, 2) uint32 view of particle indices i < j")
      .def_property_readonly("rest_lengths", &rest_lengths_view, "(m,) float64 view, mm")
      .def_property_readonly(
          "box",
          [](const SamplePtr& s) {
            return py::make_tuple(py::make_tuple(s->box.lower.x, s->box.lower.y, s->box.lower.z),
                                  py::make_tuple(s->box.upper.x, s->box.upper.y, s->box.upper.z));
          },
          "((x, y, z) lower, (x, y, z) upper), mm")
      .def_property(
          "density", [](const SamplePtr& s) { return s->density; },
          [](const SamplePtr& s, double d) {
            if (!(d > 0.0)) throw InputError("density", "must be > 0", "give g/mm^3, e.g. 2.5e-4");
            s->density = d;
          },
          "g/mm^3")
      .def_property_readonly("provenance", [](const SamplePtr& s) { return s->provenance; })
      .def("__len__", [](const SamplePtr& s) { return s->size(); })
      .def(
          "stats", [](const SamplePtr& s) { return to_python(to_json(compute_stats(*s))); },
          "particles, bonds, solid fraction, coordination, radii, glued layers (as `rupture sample info "
          "--json`)");

  m.def(
      "sample_generate",
      [](const std::string& preset, std::uint64_t seed) {
        py::gil_scoped_release release;
        return std::make_shared<Sample>(make_preset(preset, seed));
      },
      py::arg("preset"), py::arg("seed"));
  m.def(
      "sample_load",
      [](const std::filesystem::path& path) { return std::make_shared<Sample>(load_sample(path)); },
      py::arg("path"));
  m.def(
      "sample_save", [](const SamplePtr& s, const std::filesystem::path& path) { save_sample(*s, path); },
      py::arg("sample"), py::arg("path"));
  m.def("sample_from_arrays", &sample_from_arrays, py::arg("positions"), py::arg("radii"), py::arg("groups"),
        py::arg("bonds"), py::arg("bond_tolerance"), py::arg("density"));

  m.def("run", &run, py::arg("config_file"), py::arg("toml_text"), py::arg("overrides"), py::arg("command"),
        py::arg("overwrite"), py::arg("progress"));
  m.def("resume", &resume, py::arg("folder"), py::arg("command"), py::arg("progress"));
  m.def("config_reference", &loading::config_reference);

  m.def("analyze_arrays", &analyze_arrays, py::arg("strain"), py::arg("force"), py::arg("energy"),
        py::arg("strain_unit"), py::arg("force_unit"), py::arg("energy_unit"));
  m.def("columns_read", &columns_read, py::arg("header"));
  m.def("analyze_file", &analyze_file, py::arg("curves"));
}
