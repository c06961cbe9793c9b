// loading/schema: how a config is described once — one Key per setting (section, name, unit,
// default, plausible range, help, how it is read from TOML and written to JSON) — and the readers,
// range check, JSON form and commented reference every such table shares. The run config
// (loading/config.cpp) and the scan config's [scan], [grid], [[points]] and [rules] (scan/scan.cpp)
// are tables of it. Not: the keys themselves, nor the checks between keys.
#pragma once

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.hpp"

namespace rupture::loading::schema {

// The values a number key accepts: finite and inside [low, high] (an end excluded when open).
// The ranges are wide (orders of magnitude around any run we know of); what they catch is a typo,
// inf or nan, 1e308, and a value in the wrong unit (a density in t/mm^3 where g/mm^3 belongs).
struct Range {
  double low, high;
  bool low_open = false, high_open = false;
  std::string text(const std::string& unit) const;
  bool contains(double v) const {
    return std::isfinite(v) && (low_open ? v > low : v >= low) && (high_open ? v < high : v <= high);
  }
};

double read_number(const toml::node& node, const std::string& where);
std::int64_t read_integer(const toml::node& node, const std::string& where);
bool read_bool(const toml::node& node, const std::string& where);
std::string read_string(const toml::node& node, const std::string& where);
// The one check every number of a config passes; the error names the range and the default.
double in_range(double value, const std::optional<Range>& range, const std::string& unit,
                const std::string& default_text, const std::string& where);

// One configuration key of a Config struct: where it lives, its unit, default (as text for the
// reference) and plausible range, what it means, how to read it in and how to write it back out.
template <class Config>
struct Key {
  std::string section, name, unit, default_text, help;
  std::optional<Range> range;
  std::function<void(const toml::node&, Config&, const std::string& where)> read;
  std::function<nlohmann::json(const Config&)> write;
  bool required = false;  // no default: a section that is read lacks it only by mistake
  std::string path() const { return section + "." + name; }
};

// A key read straight into one field: a number (checked against `range`), a whole number, a
// boolean or a string.
template <class Config, class T>
Key<Config> number_key(std::string section, std::string name, std::string unit, std::string help,
                       T Config::*field, std::optional<Range> range = std::nullopt) {
  const Config defaults;
  Key<Config> key{std::move(section),
                  std::move(name),
                  std::move(unit),
                  fmt::format("{}", defaults.*field),
                  std::move(help),
                  range,
                  {},
                  {},
                  false};
  if constexpr (std::is_same_v<T, std::string>) key.default_text = fmt::format("\"{}\"", defaults.*field);
  if constexpr (std::is_same_v<T, bool>) key.default_text = (defaults.*field) ? "true" : "false";
  key.read = [field, range, unit = key.unit, fallback = key.default_text](const toml::node& node, Config& c,
                                                                          const std::string& where) {
    if constexpr (std::is_same_v<T, double>)
      c.*field = in_range(read_number(node, where), range, unit, fallback, where);
    else if constexpr (std::is_same_v<T, bool>)
      c.*field = read_bool(node, where);
    else if constexpr (std::is_same_v<T, std::string>)
      c.*field = read_string(node, where);
    else
      c.*field = static_cast<T>(in_range(double(read_integer(node, where)), range, unit, fallback, where));
  };
  key.write = [field](const Config& c) { return nlohmann::json(c.*field); };
  return key;
}

// A number key without a default (a section that is read must give it), checked against `range`.
template <class Config, class T>
Key<Config> required_number_key(std::string section, std::string name, std::string unit, std::string help,
                                T Config::*field, Range range) {
  Key<Config> key{
      std::move(section), std::move(name), std::move(unit), "", std::move(help), range, {}, {}, true};
  key.read = [field, range, unit = key.unit](const toml::node& node, Config& c, const std::string& where) {
    const double value = std::is_integral_v<T> ? double(read_integer(node, where)) : read_number(node, where);
    c.*field = static_cast<T>(in_range(value, range, unit, "", where));
  };
  key.write = [field](const Config& c) { return nlohmann::json(c.*field); };
  return key;
}

// A string key that takes one of a few words.
template <class Config>
Key<Config> choice_key(std::string section, std::string name, std::string help, std::string Config::*field,
                       std::vector<std::string> choices) {
  Key<Config> key = number_key(std::move(section), std::move(name), "", std::move(help), field);
  key.read = [field, choices = std::move(choices)](const toml::node& node, Config& c,
                                                   const std::string& where) {
    const std::string value = read_string(node, where);
    std::string list;
    for (const auto& choice : choices) {
      if (value == choice) {
        c.*field = value;
        return;
      }
      list += (list.empty() ? "" : ", ") + fmt::format("\"{}\"", choice);
    }
    throw InputError(where, fmt::format("\"{}\" is not a valid choice", excerpt(value)),
                     "use one of " + list);
  };
  return key;
}

// A number key that may instead say "auto" (empty optional), such as a time step.
template <class Config>
Key<Config> auto_or_number_key(std::string section, std::string name, std::string unit, std::string help,
                               std::optional<double> Config::*field, Range range) {
  Key<Config> key{std::move(section),
                  std::move(name),
                  std::move(unit),
                  "\"auto\"",
                  std::move(help),
                  range,
                  {},
                  {},
                  false};
  key.read = [field, range, unit = key.unit](const toml::node& node, Config& c, const std::string& where) {
    if (node.is_string()) {
      if (read_string(node, where) != "auto")
        throw InputError(where, fmt::format("expects a number ({}) or \"auto\"", unit));
      (c.*field).reset();
    } else {
      c.*field = in_range(read_number(node, where), range, unit, "\"auto\"", where);
    }
  };
  key.write = [field](const Config& c) {
    return c.*field ? nlohmann::json(*(c.*field)) : nlohmann::json("auto");
  };
  return key;
}

// A key that takes an array of strings.
template <class Config>
Key<Config> string_list_key(std::string section, std::string name, std::string help,
                            std::vector<std::string> Config::*field) {
  Key<Config> key{
      std::move(section), std::move(name), "", "[]", std::move(help), std::nullopt, {}, {}, false};
  key.read = [field, name = key.name](const toml::node& node, Config& c, const std::string& where) {
    const auto* array = node.as_array();
    if (array == nullptr)
      throw InputError(where, "expects an array of strings",
                       fmt::format("write {} = [\"...\", \"...\"]", name));
    (c.*field).clear();
    for (std::size_t i = 0; i < array->size(); ++i)
      (c.*field).push_back(read_string(*array->get(i), fmt::format("{}[{}]", where, i)));
  };
  key.write = [field](const Config& c) { return nlohmann::json(c.*field); };
  return key;
}

template <class Config>
std::string valid_keys(const std::vector<Key<Config>>& keys) {
  std::string list;
  for (const auto& key : keys) list += (list.empty() ? "" : ", ") + key.path();
  return list;
}

template <class Config>
const Key<Config>* find_key(const std::vector<Key<Config>>& keys, const std::string& path) {
  for (const auto& key : keys)
    if (key.path() == path) return &key;
  return nullptr;
}

// Reads every key of one [section] table into `config` (an unknown key is refused with the list of
// valid ones, a missing required one by name); `where(path)` names a key's origin in messages.
template <class Config, class Where>
void read_section(const std::vector<Key<Config>>& keys, const std::string& section, const toml::table& table,
                  Config& config, const Where& where) {
  for (const auto& [name_key, node] : table) {
    const std::string path = section + "." + std::string(name_key.str());
    const Key<Config>* key = find_key(keys, path);
    if (key == nullptr) throw InputError(where(path), "unknown key", "valid keys: " + valid_keys(keys));
    key->read(node, config, where(path));
  }
  for (const auto& key : keys)
    if (key.required && key.section == section && !table.contains(key.name))
      throw InputError(where(key.path()), "missing", fmt::format("add {} = ... ({})", key.name, key.help));
}

// Reads `root`'s [section] with read_section when it is there; a value that is not a table is refused.
template <class Config, class Where>
void read_optional_section(const std::vector<Key<Config>>& keys, const toml::table& root,
                           const std::string& section, Config& config, const Where& where) {
  const auto* node = root.get(section);
  if (node == nullptr) return;
  const auto* table = node->as_table();
  if (table == nullptr) throw InputError(where(section), "expects a table", "write [" + section + "]");
  read_section(keys, section, *table, config, where);
}

// {"section": {"name": value}} for every key.
template <class Config>
nlohmann::json to_json(const std::vector<Key<Config>>& keys, const Config& config) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& key : keys) out[key.section][key.name] = key.write(config);
  return out;
}

// Every key with its unit, plausible range and default as a commented TOML document, after
// `header`; `default_text` turns a key's default into the text written (a default that is not a
// value, such as the sample's own density, becomes one).
template <class Config>
std::string reference(const std::vector<Key<Config>>& keys, std::string header,
                      const std::function<std::string(const Key<Config>&)>& default_text = {}) {
  std::string section;
  for (const auto& key : keys) {
    if (key.section != section) {
      section = key.section;
      header += fmt::format("\n[{}]\n", section);
    }
    const std::string unit = key.unit.empty() ? "" : fmt::format(" [{}]", key.unit);
    const std::string plausible = key.range ? "; plausible " + key.range->text(key.unit) : "";
    header += fmt::format("# {}{}{}\n{} = {}\n", key.help, unit, plausible, key.name,
                          default_text ? default_text(key) : key.default_text);
  }
  return header;
}

}  // namespace rupture::loading::schema
