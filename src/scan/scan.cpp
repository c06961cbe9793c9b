#include "scan/scan.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "core/error.hpp"
#include "dem/system.hpp"
#include "io/atomic_file.hpp"
#include "io/quantity.hpp"
#include "loading/checkpoint.hpp"
#include "loading/schema.hpp"

namespace rupture::scan {

namespace {

// strtod, not stod: a subnormal such as 1e-308 must reach the range check, not throw.
double round6(double value) { return std::strtod(fmt::format("{:.6g}", value).c_str(), nullptr); }

// A TOML value as the text of a --set override; `where` names it in an error.
std::string toml_text(const toml::node& node, const std::string& where) {
  if (auto s = node.value_exact<std::string>()) return "\"" + *s + "\"";
  if (auto b = node.value_exact<bool>()) return *b ? "true" : "false";
  if (auto i = node.value_exact<std::int64_t>()) return fmt::format("{}", *i);
  if (auto d = node.value_exact<double>()) return fmt::format("{}", *d);
  if (const auto* array = node.as_array()) {
    std::string text = "[";
    for (std::size_t i = 0; i < array->size(); ++i)
      text += (i ? ", " : "") + toml_text(*array->get(i), where);
    return text + "]";
  }
  throw InputError(where, "a value that is not a string, number, boolean or array",
                   "write it as in a run config");
}

}  // namespace

namespace {

// [scan]'s keys as written; base and output become paths once read.
struct ScanSection {
  std::string base, output = ScanConfig{}.output.string();
  std::vector<std::string> set;
};

const std::vector<loading::schema::Key<ScanSection>>& scan_keys() {
  static const auto keys = [] {
    using namespace loading::schema;
    return std::vector<Key<ScanSection>>{
        number_key("scan", "base", "", "the run config every point starts from, relative to the scan config",
                   &ScanSection::base),
        number_key("scan", "output", "", "the scan folder, relative to the working directory",
                   &ScanSection::output),
        string_list_key("scan", "set", "run-config overrides for every point, as --set takes them",
                        &ScanSection::set)};
  }();
  return keys;
}

// [scan]: the base run config (relative to the scan config's folder), the output folder, set.
void read_scan_section(const toml::table& root, const std::string& source,
                       const std::filesystem::path& folder, ScanConfig& c) {
  ScanSection scan;
  loading::schema::read_optional_section(scan_keys(), root, "scan", scan,
                                         [&](const std::string& path) { return source + ": " + path; });
  if (scan.base.empty())
    throw InputError(source + ": scan.base", "missing", "name the run config, e.g. base = \"tissue.toml\"");
  c.base =
      std::filesystem::path(scan.base).is_relative() ? folder / scan.base : std::filesystem::path(scan.base);
  c.output = scan.output;
  c.set = scan.set;
}

// [sample]: keys that replace the base config's sample, as overrides.
void read_sample_section(const toml::table& root, const std::string& source,
                         const std::filesystem::path& folder, ScanConfig& c) {
  if (const auto* sample = root.get("sample")) {
    const auto* table = sample->as_table();
    if (table == nullptr) throw InputError(source + ": sample", "expects a table", "write [sample]");
    bool names_source = false;
    for (const auto& [key, value] : *table) {
      std::string name(key.str()), text = toml_text(value, source + ": sample." + name);
      if (name == "file" && value.is_string()) {
        const std::filesystem::path path = *value.value<std::string>();
        text = "\"" + (path.is_relative() ? (folder / path).string() : path.string()) + "\"";
      }
      names_source = names_source || name == "file" || name == "preset" || name == "lattice";
      c.sample.push_back("sample." + name + "=" + text);
    }
    // The scan's sample replaces the base config's: clear the sources it does not name.
    if (names_source)
      for (const char* other : {"file", "preset", "lattice"})
        if (!table->contains(other))
          c.sample.insert(c.sample.begin(), std::string("sample.") + other + "=\"\"");
  }
}

// The run-config keys a point sets: k_n and b_d take their units and plausible ranges from them.
constexpr const char* stiffness_key = "bonds.stiffness";
constexpr const char* break_distance_key = "bonds.break_distance";

// One [grid] range, { from, to, count }: from and to are values of the run-config key it scans.
std::vector<loading::schema::Key<LogRange>> range_keys(const std::string& section,
                                                       const std::string& run_key) {
  using namespace loading::schema;
  const std::string unit = loading::config_key_unit(run_key);
  const Range values = *loading::config_key_range(run_key);
  return {required_number_key(section, "from", unit, "the first value", &LogRange::from, values),
          required_number_key(section, "to", unit, "the last value", &LogRange::to, values),
          required_number_key(section, "count", "", "how many values, log-spaced", &LogRange::count,
                              Range{1, 100000})};
}

// A [grid] key: the { from, to, count } range of one run-config key.
loading::schema::Key<ScanConfig> grid_key(const std::string& name, const std::string& run_key,
                                          std::optional<LogRange> ScanConfig::*field) {
  loading::schema::Key<ScanConfig> key{"grid",
                                       name,
                                       loading::config_key_unit(run_key),
                                       "",
                                       "{ from, to, count }: log-spaced values of " + run_key,
                                       {},
                                       {},
                                       {},
                                       true};
  key.read = [=](const toml::node& node, ScanConfig& c, const std::string& where) {
    const auto* table = node.as_table();
    if (table == nullptr)
      throw InputError(where, "expects { from = ..., to = ..., count = ... }",
                       "write e.g. " + name + " = { from = 1e2, to = 1e5, count = 4 }");
    const std::string section = "grid." + name;
    LogRange range;
    loading::schema::read_section(
        range_keys(section, run_key), section, *table, range,
        [&](const std::string& path) { return where + path.substr(section.size()); });
    c.*field = range;
  };
  return key;
}

const std::vector<loading::schema::Key<ScanConfig>>& grid_keys() {
  static const std::vector<loading::schema::Key<ScanConfig>> keys = {
      grid_key("k_n", stiffness_key, &ScanConfig::grid_k_n),
      grid_key("b_d", break_distance_key, &ScanConfig::grid_b_d)};
  return keys;
}

// One [[points]] entry.
struct ListedPoint {
  double k_n = 0.0, b_d = 0.0;
};

const std::vector<loading::schema::Key<ListedPoint>>& point_keys() {
  static const auto keys = [] {
    using namespace loading::schema;
    return std::vector<Key<ListedPoint>>{
        required_number_key("points", "k_n", loading::config_key_unit(stiffness_key), "the bond stiffness",
                            &ListedPoint::k_n, *loading::config_key_range(stiffness_key)),
        required_number_key("points", "b_d", loading::config_key_unit(break_distance_key),
                            "the break distance", &ListedPoint::b_d,
                            *loading::config_key_range(break_distance_key))};
  }();
  return keys;
}

// [grid] and [[points]]: the (k_n, b_d) pairs, at least one and at most max_points.
void read_points(const toml::table& root, const std::string& source, ScanConfig& c) {
  const auto where = [&](const std::string& path) { return source + ": " + path; };
  loading::schema::read_optional_section(grid_keys(), root, "grid", c, where);
  if (const auto* points = root.get("points")) {
    const auto* array = points->as_array();
    if (array == nullptr)
      throw InputError(source + ": points", "expects [[points]] entries",
                       "write [[points]] k_n = 1e3 b_d = 0.05");
    for (std::size_t i = 0; i < array->size(); ++i) {
      const auto* entry = array->get(i)->as_table();
      if (entry == nullptr)
        throw InputError(fmt::format("{}: points[{}]", source, i), "expects a table", "write [[points]]");
      ListedPoint point;
      loading::schema::read_section(point_keys(), "points", *entry, point, [&](const std::string& path) {
        return fmt::format("{}: points[{}]{}", source, i, path.substr(std::string("points").size()));
      });
      c.listed.emplace_back(round6(point.k_n), round6(point.b_d));
    }
  }
  if (!c.grid_k_n && c.listed.empty())
    throw InputError(source, "no points", "add a [grid] with k_n and b_d ranges, or [[points]] entries");
  if (const double points = c.grid_k_n
                                ? double(c.grid_k_n->count) * c.grid_b_d->count + double(c.listed.size())
                                : double(c.listed.size());
      points > double(max_points))
    throw InputError(source,
                     fmt::format("{:g} points, more than the {} a scan folder holds", points, max_points),
                     "split the scan into several configs with their own [scan] output");
}

// [rules]: the per-point dt, ramp, stop strain and output interval, one key each (the run
// config's schema machinery: the single place for key, unit, default, range and help).
const std::vector<loading::schema::Key<ScanConfig>>& rules_keys() {
  static const auto keys = [] {
    using namespace loading::schema;
    std::vector<Key<ScanConfig>> k;
    k.push_back(auto_or_number_key(
        "rules", "dt", "s", "time step of every point, or \"auto\" = time.safety x the point's critical dt",
        &ScanConfig::dt, Range{1e-18, 1}));
    k.push_back(
        choice_key("rules", "ramp",
                   "speed ramp: \"scaled\" (ramp_steps x (ramp_b_d / b_d)^ramp_exponent), \"strain\" "
                   "(ends at ramp_fraction of the first-break strain) or \"base\" (the base config's)",
                   &ScanConfig::ramp, {"scaled", "strain", "base"}));
    k.push_back(number_key("rules", "ramp_fraction", "1",
                           "\"strain\": the ramp ends at this fraction of the first-break strain",
                           &ScanConfig::ramp_fraction, Range{0, 1, true}));
    k.push_back(number_key("rules", "ramp_steps", "steps", "\"scaled\": ramp steps at b_d = ramp_b_d",
                           &ScanConfig::ramp_steps, Range{0, 1e12}));
    k.push_back(number_key("rules", "ramp_b_d", "mm",
                           "\"scaled\": the b_d at which the ramp takes ramp_steps", &ScanConfig::ramp_b_d,
                           Range{0, 1e3, true}));
    k.push_back(number_key("rules", "ramp_exponent", "1",
                           "\"scaled\": ramp steps grow as (ramp_b_d / b_d)^this", &ScanConfig::ramp_exponent,
                           Range{-10, 10}));
    k.push_back(number_key("rules", "ramp_min_steps", "steps", "no point's ramp is shorter",
                           &ScanConfig::ramp_min_steps, Range{0, 1e12}));
    k.push_back(number_key("rules", "ramp_max_steps", "steps",
                           "no point's ramp is longer (>= ramp_min_steps)", &ScanConfig::ramp_max_steps,
                           Range{0, 1e12}));
    k.push_back(choice_key("rules", "max_strain",
                           "stop strain: \"scaled\" (max_strain_factor x the first-break strain) or \"base\" "
                           "(the base config's stop.max_strain)",
                           &ScanConfig::max_strain, {"scaled", "base"}));
    k.push_back(number_key("rules", "max_strain_factor", "1",
                           "\"scaled\": stop at this multiple of the first-break strain",
                           &ScanConfig::max_strain_factor, Range{0, 1e6, true}));
    k.push_back(number_key("rules", "max_strain_min", "%", "\"scaled\": never stop below this strain",
                           &ScanConfig::max_strain_min, Range{0, 1e6, true}));
    k.push_back(
        choice_key("rules", "interval",
                   "curve rows: \"scaled\" (rows_to_first_break rows below the first-break strain) or "
                   "\"base\" (the base config's output.interval)",
                   &ScanConfig::interval, {"scaled", "base"}));
    k.push_back(number_key("rules", "rows_to_first_break", "rows",
                           "\"scaled\": curve rows below the first-break strain",
                           &ScanConfig::rows_to_first_break, Range{10, 1e6}));
    return k;
  }();
  return keys;
}

void read_rules(const toml::table& root, const std::string& source, ScanConfig& c) {
  loading::schema::read_optional_section(rules_keys(), root, "rules", c,
                                         [&](const std::string& path) { return source + ": " + path; });
  if (c.ramp_max_steps < c.ramp_min_steps)
    throw InputError(source + ": rules.ramp_max_steps",
                     fmt::format("{} is below ramp_min_steps = {}", c.ramp_max_steps, c.ramp_min_steps),
                     "make ramp_max_steps >= ramp_min_steps");
}

}  // namespace

std::string rules_reference() {
  return loading::schema::reference(rules_keys(),
                                    "# rupture scan: the [rules] every point's run follows, with units and "
                                    "defaults.\n# The other sections: docs/scan.md.\n");
}

ScanConfig load_scan_config(const std::filesystem::path& file) {
  const std::string source = file.string();
  const toml::table root = loading::parse_toml(io::read_text_file(file, io::max_config_bytes), source);
  for (const auto& [key, value] : root) {
    (void)value;
    const std::string name(key.str());
    if (name != "scan" && name != "sample" && name != "grid" && name != "points" && name != "rules")
      throw InputError(source + ": " + name, "unknown section",
                       "sections: [scan], [sample], [grid], [[points]], [rules]");
  }
  ScanConfig c;
  c.file = file;
  read_scan_section(root, source, file.parent_path(), c);
  read_sample_section(root, source, file.parent_path(), c);
  read_points(root, source, c);
  read_rules(root, source, c);
  return c;
}

nlohmann::json to_json(const ScanConfig& c) {
  const auto range = [](const std::optional<LogRange>& r) {
    return r ? nlohmann::json{{"from", r->from}, {"to", r->to}, {"count", r->count}}
             : nlohmann::json(nullptr);
  };
  nlohmann::json listed = nlohmann::json::array();
  for (const auto& [k, b] : c.listed) listed.push_back({{"k_n", k}, {"b_d", b}});
  return {{"file", c.file.string()},
          {"scan", {{"base", c.base.string()}, {"output", c.output.string()}, {"set", c.set}}},
          {"sample", c.sample},
          {"grid", {{"k_n", range(c.grid_k_n)}, {"b_d", range(c.grid_b_d)}}},
          {"points", listed},
          {"rules", loading::schema::to_json(rules_keys(), c)["rules"]}};
}

namespace {

// The base config with the scan's [sample] keys and set (strings the scan config holds as a user
// wrote them, so they go the --set way); errors name the scan file as their place.
loading::RunConfig load_base_config(const std::filesystem::path& base,
                                    const std::vector<std::string>& overrides, const std::string& scan_file) {
  try {
    return loading::load_config(base, overrides);
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (!message.starts_with("--set ")) throw;
    throw InputError(scan_file + " ([sample] or [scan] set)", message.substr(6));
  }
}

std::vector<std::string> base_overrides(const ScanConfig& config) {
  std::vector<std::string> overrides = config.sample;
  overrides.insert(overrides.end(), config.set.begin(), config.set.end());
  return overrides;
}

}  // namespace

loading::RunConfig base_config(const ScanConfig& config) {
  return load_base_config(config.base, base_overrides(config), config.file.string());
}

std::vector<double> log_spaced(const LogRange& range) {
  std::vector<double> values;
  for (int i = 0; i < range.count; ++i) {
    const double t = range.count == 1 ? 0.0 : double(i) / double(range.count - 1);
    values.push_back(round6(range.from * std::pow(range.to / range.from, t)));
  }
  return values;
}

namespace {

// What the per-point rules need of the sample: its critical dt at one stiffness (every spring of
// the sample is a multiple of k_n, so the limit scales as 1/sqrt(k_n)) and the plate separation.
struct StepScale {
  double k_n = 0.0;               // N/mm, where critical_dt was measured
  double critical_dt = 0.0;       // s
  double plate_separation = 0.0;  // mm
};

StepScale step_scale(const loading::RunConfig& base, const Sample& sample) {
  const dem::System system(sample, base.dem_params(sample.density));
  return {base.bond_stiffness, system.critical_dt(), system.initial_plate_separation()};
}

// Steps the plate needs at full speed to reach `strain_percent` at stiffness k_n.
double steps_to_strain(const StepScale& scale, const loading::RunConfig& base, const ScanConfig& config,
                       double k_n, double strain_percent) {
  const double dt = config.dt ? *config.dt : base.dt_safety * scale.critical_dt * std::sqrt(scale.k_n / k_n);
  return strain_percent / 100.0 * scale.plate_separation / (base.speed * dt);
}

void check_dt(const Plan& plan, const StepScale& scale, double dt, const std::filesystem::path& file) {
  std::vector<std::string> too_large;
  double smallest = INFINITY;
  for (const auto& p : plan.points) {
    const double limit = scale.critical_dt * std::sqrt(scale.k_n / p.k_n);
    smallest = std::min(smallest, limit);
    if (dt > limit) too_large.push_back(fmt::format("{} (limit {:.3g} s)", p.name, limit));
  }
  if (too_large.empty()) return;
  const std::size_t shown = std::min<std::size_t>(3, too_large.size());
  std::string names;
  for (std::size_t i = 0; i < shown; ++i) names += (i ? ", " : "") + too_large[i];
  throw InputError(
      file.string() + ": rules.dt",
      fmt::format("dt = {:.3g} s exceeds the stability limit at {} of {} points: {}{}", dt, too_large.size(),
                  plan.points.size(), names, too_large.size() > shown ? ", ..." : ""),
      fmt::format("use dt = \"auto\", or dt <= {:.3g} s", smallest));
}

}  // namespace

std::string fingerprint_text(std::uint64_t fingerprint) { return fmt::format("{:016x}", fingerprint); }

std::string point_name(double k_n, double b_d) { return fmt::format("kn_{}_bd_{}", k_n, b_d); }

Plan make_plan(const ScanConfig& config, const Sample& sample) {
  const loading::RunConfig base = base_config(config);
  const double rest_length = dem::mean_rest_length(sample);
  const bool needs_steps = config.ramp == "strain" || config.interval == "scaled" || config.dt.has_value();
  const StepScale scale = needs_steps ? step_scale(base, sample) : StepScale{};
  Plan plan;
  plan.folder = config.output;
  if (std::error_code ec;
      std::filesystem::exists(plan.folder, ec) && !std::filesystem::is_directory(plan.folder, ec))
    throw InputError(plan.folder.string(), "is a file, not a scan folder",
                     "give [scan] output (or -o) a folder path");
  plan.sample_fingerprint = loading::sample_fingerprint(sample);
  plan.base = config.base;
  plan.base_config = base;
  plan.base_overrides = base_overrides(config);
  plan.dt = config.dt;
  plan.scan_config = to_json(config);
  std::vector<std::pair<double, double>> pairs;
  if (config.grid_k_n)
    for (double k : log_spaced(*config.grid_k_n))
      for (double b : log_spaced(*config.grid_b_d)) pairs.emplace_back(k, b);
  pairs.insert(pairs.end(), config.listed.begin(), config.listed.end());
  std::set<std::pair<double, double>> seen;
  for (const auto& [k, b] : pairs) {
    if (!seen.insert({k, b}).second) continue;
    Point p;
    p.index = plan.points.size();
    p.k_n = k;
    p.b_d = b;
    p.name = point_name(k, b);
    // A gentler start for small b_d (paper section 3: 10^4 steps for large breaking strains, up to
    // 10^6 where samples break at small strains): the shock of the start must stay below the strain
    // that breaks a bond, which scales with b_d.
    // "strain" instead ends the ramp at a fraction of the first-break strain whatever k_n is, so the
    // plate reaches full speed before anything breaks (a ramp in steps is long in strain at small k_n,
    // where dt is large); the wave transit time is the same number of steps at every k_n.
    // The rules measure strain in the nominal break strain (b_d / mean r0, or b), a scale that every
    // point shares; dem::first_break_strain, the affine prediction, lies 30-40 % below it.
    dem::Params rule = base.dem_params(sample.density);
    rule.break_distance = b;
    const double first_break = 100.0 * dem::nominal_break_strain(rule, rest_length);  // %
    p.ramp_steps = base.ramp_steps;
    if (config.ramp == "scaled" || config.ramp == "strain") {
      // The ramp v/2 (1 - cos) covers half the strain that full speed would in the same steps.
      const double steps =
          config.ramp == "scaled"
              ? double(config.ramp_steps) * std::pow(config.ramp_b_d / b, config.ramp_exponent)
              : 2.0 * config.ramp_fraction * steps_to_strain(scale, base, config, k, first_break);
      p.ramp_steps = std::clamp(std::int64_t(std::llround(std::min(steps, 9e18))), config.ramp_min_steps,
                                config.ramp_max_steps);
    }
    // Curve rows fine enough to resolve a peak wherever it lies: the steps to the first-break strain
    // differ by orders of magnitude between points.
    p.output_interval = base.output_interval;
    if (config.interval == "scaled")
      p.output_interval = std::max<std::int64_t>(
          1, std::llround(std::min(
                 steps_to_strain(scale, base, config, k, first_break) / config.rows_to_first_break, 1e12)));
    // Stop a fixed multiple past the strain where bonds start to break (b_d / r0), never later than
    // the base config's max_strain: runs differ by orders of magnitude in the strain they need.
    p.max_strain = base.max_strain;
    if (config.max_strain == "scaled") {
      p.max_strain = round6(std::clamp(config.max_strain_factor * first_break,
                                       std::min(config.max_strain_min, base.max_strain), base.max_strain));
    }
    plan.points.push_back(std::move(p));
  }
  // Bad input fails before anything runs: every point's config, and a given dt against each point's
  // stability limit, which scales as 1/sqrt(k_n) (every spring of the sample is a multiple of k_n).
  for (const auto& p : plan.points) (void)point_config(plan, p, 1);
  if (config.dt && !base.allow_unstable_dt) check_dt(plan, scale, *config.dt, config.file);
  return plan;
}

nlohmann::json point_settings(const Plan& plan, const Point& point, int threads) {
  nlohmann::json settings = {{"bonds", {{"stiffness", point.k_n}, {"break_distance", point.b_d}}},
                             {"time", {{"dt", plan.dt ? nlohmann::json(*plan.dt) : nlohmann::json("auto")}}},
                             {"loading", {{"ramp_steps", point.ramp_steps}}},
                             {"stop", {{"max_strain", point.max_strain}}},
                             {"run", {{"threads", threads}}}};
  if (point.output_interval > 0) settings["output"]["interval"] = point.output_interval;
  return settings;
}

loading::RunConfig point_config(const Plan& plan, const Point& point, int threads) {
  return loading::with_values(plan.base_config, point_settings(plan, point, threads),
                              fmt::format("{} (scan point {})", plan.base.string(), point.name));
}

std::string point_command(const Plan& plan, const Point& point, int threads) {
  std::string command = "rupture run '" + plan.base.string() + "'";
  for (const auto& o : plan.base_overrides) command += " --set '" + o + "'";
  const nlohmann::json settings = point_settings(plan, point, threads);  // kept alive for items()
  for (const auto& [section, keys] : settings.items())
    for (const auto& [name, value] : keys.items()) {
      const std::string text =
          value.is_number_float() ? fmt::format("{}", value.get<double>()) : value.dump();
      command += fmt::format(" --set '{}.{}={}'", section, name, text);
    }
  return command;
}

nlohmann::json to_json(const Plan& plan) {
  nlohmann::json points = nlohmann::json::array();
  const std::string k_n_unit = loading::bond_stiffness_unit(plan.base_config),
                    b_d_unit = loading::break_distance_unit(plan.base_config);
  for (const auto& p : plan.points)
    points.push_back({{"index", p.index},
                      {"k_n", io::quantity(p.k_n, k_n_unit)},
                      {"b_d", io::quantity(p.b_d, b_d_unit)},
                      {"folder", "points/" + p.name},
                      {"ramp_steps", p.ramp_steps},
                      {"max_strain", io::quantity(p.max_strain, "%")},
                      {"output_interval", p.output_interval}});
  return {{"base", plan.base.string()},
          {"base_config", loading::to_json(plan.base_config)},
          {"scan_config", plan.scan_config},
          {"sample_fingerprint", fingerprint_text(plan.sample_fingerprint)},
          {"points", points}};
}

Plan plan_from_json(const nlohmann::json& document, const std::filesystem::path& folder) {
  Plan plan;
  plan.folder = folder;
  plan.base = document.at("base").get<std::string>();
  plan.scan_config = document.at("scan_config");
  const auto& scan_config = plan.scan_config;
  plan.base_overrides = scan_config.at("sample").get<std::vector<std::string>>();
  for (const auto& o : scan_config.at("scan").at("set")) plan.base_overrides.push_back(o.get<std::string>());
  // Earlier plans name the time step "dt_s"; the rules schema writes the config's own key, "dt".
  const auto& rules = scan_config.at("rules");
  if (const auto& dt = rules.contains("dt") ? rules.at("dt") : rules.at("dt_s"); dt.is_number())
    plan.dt = dt.get<double>();
  // Plans of rupture 0.1 lack the resolved base config: it is read as they read it.
  plan.base_config =
      document.contains("base_config")
          ? loading::config_from_json(document.at("base_config"), plan.base)
          : load_base_config(plan.base, plan.base_overrides, scan_config.at("file").get<std::string>());
  if (document.contains("sample_fingerprint"))
    plan.sample_fingerprint =
        std::strtoull(document.at("sample_fingerprint").get<std::string>().c_str(), nullptr, 16);
  // Plans before the JSON convention wrote bare numbers under unit-suffixed keys.
  const auto number = [](const nlohmann::json& point, const char* key, const char* earlier_key) {
    const auto& q = point.contains(key) ? point.at(key) : point.at(earlier_key);
    return (q.is_object() ? q.at("value") : q).get<double>();  // a json type_error when not a number
  };
  for (const auto& j : document.at("points")) {
    Point p;
    p.index = j.at("index").get<std::size_t>();
    p.k_n = number(j, "k_n", "k_n_N_per_mm");
    p.b_d = number(j, "b_d", "b_d_mm");
    p.name = point_name(p.k_n, p.b_d);
    p.ramp_steps = j.at("ramp_steps").get<std::int64_t>();
    p.max_strain = number(j, "max_strain", "max_strain_percent");
    p.output_interval = j.value("output_interval", std::int64_t{0});  // plans of 0.1 lack it
    plan.points.push_back(std::move(p));
  }
  return plan;
}

void write_plan(const Plan& plan) {
  std::filesystem::create_directories(plan.folder);
  io::write_json_atomically(plan.folder / "plan.json", to_json(plan));
}

Plan read_plan(const std::filesystem::path& folder) {
  const auto file = folder / "plan.json";
  if (!std::filesystem::exists(file))
    throw InputError(folder.string(), "not a scan folder (no plan.json)",
                     "give the folder a scan wrote ([scan] output)");
  try {
    return plan_from_json(nlohmann::json::parse(io::read_text_file(file)), folder);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string(), std::string("unreadable: ") + e.what(), "rerun the scan to rewrite it");
  }
}

}  // namespace rupture::scan
