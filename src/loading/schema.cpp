#include "loading/schema.hpp"

namespace rupture::loading::schema {

std::string Range::text(const std::string& unit) const {
  return fmt::format("{}{:g}, {:g}{}{}", low_open ? "(" : "[", low, high, high_open ? ")" : "]",
                     unit.empty() || unit == "1" ? "" : " " + unit);
}

double read_number(const toml::node& node, const std::string& where) {
  if (auto v = node.value<double>()) return *v;
  throw InputError(where, "expects a number", "write e.g. 1e3 (no quotes)");
}

double in_range(double value, const std::optional<Range>& range, const std::string& unit,
                const std::string& default_text, const std::string& where) {
  if (range && !range->contains(value))
    throw InputError(
        where,
        fmt::format("{:g} is {} the plausible range {}", value,
                    std::isfinite(value) ? "outside" : "not a finite number in", range->text(unit)),
        default_text.empty()          ? std::string("give a value inside it (the key has no default)")
        : unit.empty() || unit == "1" ? fmt::format("the default is {}", default_text)
                                      : fmt::format("the default is {} (values in {})", default_text, unit));
  return value;
}

std::int64_t read_integer(const toml::node& node, const std::string& where) {
  if (node.is_integer()) return *node.value<std::int64_t>();
  if (auto v = node.value<double>(); v && *v == std::floor(*v) && std::abs(*v) < 9e18)
    return std::int64_t(*v);
  throw InputError(where, "expects a whole number", "write e.g. 1000");
}

bool read_bool(const toml::node& node, const std::string& where) {
  if (auto v = node.value<bool>()) return *v;
  throw InputError(where, "expects true or false");
}

std::string read_string(const toml::node& node, const std::string& where) {
  if (auto v = node.value<std::string>()) return *v;
  throw InputError(where, "expects a string", "put the value in double quotes");
}

}  // namespace rupture::loading::schema
