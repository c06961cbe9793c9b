#include "loading/config.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "loading/schema.hpp"
#include "sample/checks.hpp"

namespace rupture::loading {

namespace {

using schema::auto_or_number_key;
using schema::choice_key;
using schema::in_range;
using schema::number_key;
using schema::Range;
using schema::read_integer;
using schema::read_number;
using Key = schema::Key<RunConfig>;

const Range density_range{min_plausible_density, max_plausible_density};

// The table of every key (long: one entry per key): the single place for key, type, unit,
// default, range and help, which parsing, --help-config and to_json all read.
const std::vector<Key>& run_keys() {
  static const std::vector<Key> keys = [] {
    std::vector<Key> k;
    k.push_back(number_key(
        "sample", "file", "",
        "sample file (rupture's own format, LAMMPS data or LSMGeometry), relative to this config's folder",
        &RunConfig::sample_file));
    k.push_back(number_key("sample", "preset", "",
                           "generate a preset sample instead: \"tissue\" or \"tissue-small\"",
                           &RunConfig::sample_preset));
    k.push_back(choice_key("sample", "lattice", "or a regular test lattice: \"chain\" or \"block\"",
                           &RunConfig::sample_lattice, {"", "chain", "block"}));
    {
      Key cells{"sample",
                "lattice_cells",
                "1",
                "[1, 10, 1]",
                "lattice particles along x, y, z (block; chain uses y)",
                Range{1, 1000},
                {},
                {}};
      cells.read = [range = *cells.range](const toml::node& node, RunConfig& c, const std::string& where) {
        const auto* array = node.as_array();
        if (array == nullptr || array->size() != 3)
          throw InputError(where, "expects three whole numbers", "write e.g. [4, 10, 2]");
        for (std::size_t d = 0; d < 3; ++d)
          c.lattice_cells[d] = std::int64_t(
              in_range(double(read_integer(*array->get(d), where)), range, "", "[1, 10, 1]", where));
      };
      cells.write = [](const RunConfig& c) { return nlohmann::json(c.lattice_cells); };
      k.push_back(std::move(cells));
    }
    k.push_back(number_key("sample", "lattice_radius", "mm", "lattice particle radius",
                           &RunConfig::lattice_radius, Range{1e-6, 1e3}));
    k.push_back(number_key("sample", "seed", "1", "generator seed (preset)", &RunConfig::seed));
    {
      Key density{
          "sample",      "density", "g/mm^3", "(the sample's)", "particle density; overrides the sample's",
          density_range, {},        {}};
      density.read = [](const toml::node& node, RunConfig& c, const std::string& where) {
        c.density = in_range(read_number(node, where), density_range, "g/mm^3",
                             fmt::format("{:g}", default_density), where);
      };
      density.write = [](const RunConfig& c) {
        return c.density ? nlohmann::json(*c.density) : nlohmann::json(nullptr);
      };
      k.push_back(std::move(density));
    }
    k.push_back(number_key("bonds", "stiffness", "N/mm",
                           "k_n, bond spring constant (with scale_stiffness: ESyS normalK in N/mm^2)",
                           &RunConfig::bond_stiffness, Range{1e-6, 1e12}));
    k.push_back(number_key(
        "bonds", "break_distance", "mm",
        "b_d: a bond breaks when r - r0 > b_d (relative rule: b, a strain, breaks when r - r0 > b r0)",
        &RunConfig::break_distance, Range{1e-9, 1e3}));
    k.push_back(choice_key("bonds", "break_rule",
                           "\"absolute\" (the paper's text) or \"relative\" (ESyS-Particle)",
                           &RunConfig::break_rule, {"absolute", "relative"}));
    k.push_back(number_key("bonds", "scale_stiffness", "",
                           "ESyS stiffness scaling k = stiffness * r0 / 4 per bond",
                           &RunConfig::scale_stiffness));
    k.push_back(number_key("contacts", "stiffness_factor", "1", "contact stiffness as a multiple of k_n",
                           &RunConfig::contact_stiffness_factor, Range{0, 1e6}));
    k.push_back(number_key("contacts", "skin", "mm",
                           "Verlet-list skin to start from (widens up to 4x when lists last under 50 steps; "
                           "results do not depend on it)",
                           &RunConfig::skin, Range{1e-6, 1e3}));
    k.push_back(
        choice_key("glue", "mode",
                   "\"spring\" (stiff springs to the plate) or \"rigid\" (glued layers move with the plate)",
                   &RunConfig::glue_mode, {"spring", "rigid"}));
    k.push_back(number_key("glue", "stiffness_factor", "1",
                           "glue spring stiffness as a multiple of k_n (spring mode)",
                           &RunConfig::glue_stiffness_factor, Range{1e-6, 1e6}));
    k.push_back(number_key("loading", "speed", "mm/s", "top plate speed after the ramp", &RunConfig::speed,
                           Range{1e-9, 1e9}));
    k.push_back(number_key("loading", "ramp_steps", "steps", "smooth speed ramp from 0 to speed",
                           &RunConfig::ramp_steps, Range{0, 1e12}));
    k.push_back(number_key("loading", "damping", "1/s", "viscous damping rate (force -damping m v); 0 = off",
                           &RunConfig::damping, Range{0, 1e12}));
    k.push_back(auto_or_number_key("time", "dt", "s", "time step, or \"auto\" = safety * critical dt",
                                   &RunConfig::dt, Range{1e-18, 1}));
    k.push_back(number_key("time", "safety", "1", "automatic dt as a fraction of the critical dt",
                           &RunConfig::dt_safety, Range{0, 1, true}));
    k.push_back(number_key("time", "allow_unstable_dt", "", "accept a dt above the stability limit",
                           &RunConfig::allow_unstable_dt));
    k.push_back(number_key("stop", "at_separation", "",
                           "stop extra_strain after the sample separated (false: pull on to max_strain or "
                           "max_steps; the separation is still recorded)",
                           &RunConfig::stop_at_separation));
    k.push_back(number_key("stop", "extra_strain", "%", "strain to keep pulling after the sample separated",
                           &RunConfig::extra_strain, Range{0, 1e4}));
    k.push_back(number_key("stop", "max_strain", "%", "stop at this strain", &RunConfig::max_strain,
                           Range{0, 1e4, true}));
    k.push_back(number_key("stop", "max_steps", "steps", "stop after this many steps", &RunConfig::max_steps,
                           Range{1, 1e15}));
    k.push_back(number_key("stop", "separation_check_interval", "steps", "steps between connectivity checks",
                           &RunConfig::separation_check_interval, Range{1, 1e12}));
    k.push_back(
        number_key("stop", "load_free_fraction", "1",
                   "also separated when the mean top-plate force stays below this fraction of its peak "
                   "(0: connectivity only)",
                   &RunConfig::load_free_fraction, Range{0, 1, false, true}));
    k.push_back(number_key("stop", "load_free_strain", "%", "over this much strain (the load-free rule)",
                           &RunConfig::load_free_strain, Range{0, 1e4, true}));
    k.push_back(
        number_key("monitor", "enabled", "",
                   "run the live precursor monitor on every curves.csv row; its warning goes to run.json",
                   &RunConfig::monitor));
    k.push_back(number_key("monitor", "window", "rows", "rows per causal cubic fit",
                           &RunConfig::monitor_window, Range{7, 1e5}));
    k.push_back(number_key("monitor", "drop", "1",
                           "fraction by which the energy rate must fall below its maximum",
                           &RunConfig::monitor_drop, Range{0, 1, true, true}));
    k.push_back(number_key("monitor", "confirm", "rows",
                           "consecutive rows below that level that confirm the maximum",
                           &RunConfig::monitor_confirm, Range{1, 1e5}));
    k.push_back(number_key("output", "folder", "", "output folder (relative to the working directory)",
                           &RunConfig::output_folder));
    k.push_back(number_key("output", "interval", "steps", "steps between rows of curves.csv",
                           &RunConfig::output_interval, Range{1, 1e12}));
    k.push_back(number_key("output", "snapshot_interval", "steps", "steps between VTK snapshots (0: none)",
                           &RunConfig::snapshot_interval, Range{0, 1e12}));
    k.push_back(number_key("checkpoint", "every", "steps",
                           "steps between restart checkpoints (0: by wall time only)",
                           &RunConfig::checkpoint_every, Range{0, 1e15}));
    k.push_back(number_key("checkpoint", "minutes", "min",
                           "wall-clock minutes between restart checkpoints (0: by steps only)",
                           &RunConfig::checkpoint_minutes, Range{0, 1e6}));
    k.push_back(number_key("checkpoint", "keep", "1", "newest checkpoints kept (older ones are removed)",
                           &RunConfig::checkpoint_keep, Range{1, 100}));
    k.push_back(number_key("run", "threads", "1", "OpenMP threads (results do not depend on it)",
                           &RunConfig::threads, Range{1, 1024}));
    return k;
  }();
  return keys;
}

std::string valid_keys() { return schema::valid_keys(run_keys()); }

// Applies "a.b=value" to the table, reading value as TOML (a bare word becomes a string); returns
// the key's path.
std::string apply_override(toml::table& table, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set " + assignment, "expects key=value", "write e.g. --set bonds.stiffness=1e4");
  const std::string path = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  const auto dot = path.find('.');
  if (dot == std::string::npos || schema::find_key(run_keys(), path) == nullptr)
    throw InputError("--set " + path, "unknown key", "valid keys: " + valid_keys());
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", value}};
  }
  const std::string section = path.substr(0, dot), name = path.substr(dot + 1);
  if (!table.contains(section)) table.insert(section, toml::table{});
  auto* sub = table[section].as_table();
  if (sub == nullptr) throw InputError("--set " + path, "'" + section + "' is not a table in the config");
  sub->insert_or_assign(name, *parsed.get("v"));
  return path;
}

void check(bool ok, const std::string& where, const std::string& problem, const std::string& fix) {
  if (!ok) throw InputError(where, problem, fix);
}

// Where a key's value came from, for messages: the config file, or the --set that overrode it.
struct Origin {
  std::string file;
  std::set<std::string> overridden;  // "section.key" paths given by --set
  std::string at(const std::string& path) const {
    return overridden.contains(path) ? "--set " + path : file + ": " + path;
  }
};

// The relations between keys; each number's own range is checked as it is read (Range).
void validate(const RunConfig& c, const Origin& origin) {
  const std::string& file = origin.file;
  const int sources =
      int(!c.sample_file.empty()) + int(!c.sample_preset.empty()) + int(!c.sample_lattice.empty());
  check(sources == 1, file, sources == 0 ? "no sample given" : "more than one sample given",
        "set exactly one of sample.file, sample.preset, sample.lattice");
  if (c.sample_lattice == "chain" || c.sample_lattice == "block")
    check(c.lattice_cells[1] >= 2, origin.at("sample.lattice_cells"), "needs at least 2 particles along y",
          "write e.g. [1, 10, 1]");
  const auto& n = c.lattice_cells;
  const double particles =
      c.sample_lattice == "chain" ? double(n[1]) : double(n[0]) * double(n[1]) * double(n[2]);
  check(particles <= max_particles, origin.at("sample.lattice_cells"),
        fmt::format("{:g} particles would need about {:.3g} GB to run", particles,
                    particles * run_bytes_per_particle / 1e9),
        fmt::format("use at most {:g} particles", max_particles));
}

// Reads every key of `table` into `config` through the schema (unknown keys refused), then checks
// the relations between keys.
RunConfig read_keys(RunConfig config, const toml::table& table, const Origin& origin) {
  const std::string& source = origin.file;
  for (const auto& [section_key, section_node] : table) {
    const std::string section(section_key.str());
    const auto* sub = section_node.as_table();
    if (sub == nullptr) {
      throw InputError(source + ": " + section, "unknown key (every key belongs to a [section])",
                       "valid keys: " + valid_keys());
    }
    schema::read_section(run_keys(), section, *sub, config,
                         [&](const std::string& path) { return origin.at(path); });
  }
  validate(config, origin);
  return config;
}

RunConfig from_table(const toml::table& table, const Origin& origin) {
  RunConfig defaults;
  defaults.config_file = origin.file;
  return read_keys(std::move(defaults), table, origin);
}

// A resolved config (to_json's form) as a TOML table, so that it is read and checked by the same
// keys as a file; null (density: the sample's own) leaves the key out.
toml::table table_from_json(const nlohmann::json& resolved, const std::string& source) {
  toml::table table;
  if (!resolved.is_object())
    throw InputError(source, "the stored configuration is not a JSON object", "start the run again");
  for (const auto& [section, keys] : resolved.items()) {
    if (!keys.is_object())
      throw InputError(source + ": " + section, "is not a table in the stored configuration",
                       "start the run again");
    toml::table sub;
    for (const auto& [name, v] : keys.items()) {
      if (v.is_null()) continue;
      if (v.is_boolean())
        sub.insert(name, v.get<bool>());
      else if (v.is_number_integer())
        sub.insert(name, v.get<std::int64_t>());
      else if (v.is_number())
        sub.insert(name, v.get<double>());
      else if (v.is_string())
        sub.insert(name, v.get<std::string>());
      else if (v.is_array()) {
        toml::array array;
        for (const auto& e : v) {
          if (!e.is_number_integer())
            throw InputError(source + ": " + section + "." + name, "holds a list of other than whole numbers",
                             "start the run again");
          array.push_back(e.get<std::int64_t>());
        }
        sub.insert(name, std::move(array));
      } else {
        throw InputError(source + ": " + section + "." + name, "holds a value of no config type",
                         "start the run again");
      }
    }
    table.insert(section, std::move(sub));
  }
  return table;
}

}  // namespace

dem::Params RunConfig::dem_params(double sample_density) const {
  dem::Params p;
  p.bond_stiffness = bond_stiffness;
  p.break_distance = break_distance;
  p.break_rule = break_rule == "relative" ? dem::BreakRule::relative : dem::BreakRule::absolute;
  p.scale_stiffness = scale_stiffness;
  p.contact_stiffness = contact_stiffness_factor * bond_stiffness;
  p.glue_stiffness = glue_stiffness_factor * bond_stiffness;
  p.glue_mode = glue_mode == "rigid" ? dem::GlueMode::rigid : dem::GlueMode::spring;
  p.density = density.value_or(sample_density);
  p.damping = damping;
  p.skin = skin;
  return p;
}

toml::table parse_toml(std::string_view text, const std::string& source) {
  io::require_text(text, source);
  try {
    return toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}", source, e.source().begin.line), std::string(e.description()),
                     "fix the TOML syntax");
  }
}

RunConfig parse_config(const std::string& toml_text, const std::string& source,
                       const std::vector<std::string>& overrides) {
  toml::table table = parse_toml(toml_text, source);
  Origin origin{source, {}};
  for (const auto& assignment : overrides) origin.overridden.insert(apply_override(table, assignment));
  return from_table(table, origin);
}

RunConfig load_config(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  RunConfig config = parse_config(io::read_text_file(file, io::max_config_bytes), file.string(), overrides);
  config.config_file = file;
  return config;
}

RunConfig config_from_json(const nlohmann::json& resolved, const std::filesystem::path& config_file) {
  RunConfig config =
      from_table(table_from_json(resolved, config_file.string()), Origin{config_file.string(), {}});
  config.config_file = config_file;
  return config;
}

RunConfig with_values(RunConfig base, const nlohmann::json& values, const std::string& source) {
  return read_keys(std::move(base), table_from_json(values, source), Origin{source, {}});
}

std::string config_reference() {
  return schema::reference<RunConfig>(run_keys(),
                                      "# rupture run configuration: every key with its unit and default.\n"
                                      "# Give exactly one of sample.file, sample.preset, sample.lattice.\n",
                                      [](const Key& key) {
                                        return key.default_text == "(the sample's)"
                                                   ? fmt::format("{:g}  # default: the sample's own",
                                                                 default_density)
                                                   : key.default_text;
                                      });
}

std::string config_key_unit(const std::string& path) {
  const Key* key = schema::find_key(run_keys(), path);
  return key ? key->unit : std::string();
}

std::string bond_stiffness_unit(const RunConfig& config) {
  return config.scale_stiffness ? "N/mm^2" : "N/mm";
}

std::string break_distance_unit(const RunConfig& config) {
  return config.break_rule == "relative" ? "1" : "mm";
}

std::optional<schema::Range> config_key_range(const std::string& path) {
  const Key* key = schema::find_key(run_keys(), path);
  return key ? key->range : std::nullopt;
}

nlohmann::json to_json(const RunConfig& config) { return schema::to_json(run_keys(), config); }

}  // namespace rupture::loading
