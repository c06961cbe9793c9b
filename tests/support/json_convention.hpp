// The one JSON convention of rupture's outputs (docs/formats.md, "Numbers in JSON outputs"), checked
// over a whole document: a number with a unit is a quantity {"value", "unit"} (with "error" or
// summaries beside the value); no key names a unit, neither as a suffix (dt_s, plate_work_mJ) nor as
// a `units` object or a `*_unit` sibling.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace rupture::testing {

// Where `document` breaks the convention, as "path: what" lines (empty when it keeps it).
inline std::vector<std::string> json_convention_breaches(const nlohmann::json& document,
                                                         const std::string& path = "") {
  static constexpr std::array<std::string_view, 14> unit_suffixes = {
      "_s",    "_ms",    "_mJ",     "_mm",    "_N",       "_g",   "_percent",
      "_unit", "_per_s", "_per_mm", "_bytes", "_seconds", "_mm3", "_N_per_mm"};
  std::vector<std::string> breaches;
  if (document.is_array()) {
    for (std::size_t i = 0; i < document.size(); ++i) {
      auto inner = json_convention_breaches(document[i], path + "[" + std::to_string(i) + "]");
      breaches.insert(breaches.end(), inner.begin(), inner.end());
    }
    return breaches;
  }
  if (!document.is_object()) return breaches;
  if (document.contains("unit")) {
    if (!document["unit"].is_string()) breaches.push_back(path + ".unit: not a string");
    if (!document.contains("value")) breaches.push_back(path + ": a unit without a value");
  }
  for (const auto& [key, child] : document.items()) {
    const std::string where = path + "." + key;
    if (key == "units") breaches.push_back(where + ": a units object (give each number its own unit)");
    for (const auto suffix : unit_suffixes)
      if (key.size() > suffix.size() && key.ends_with(suffix))
        breaches.push_back(where + ": a unit in the key (write {\"value\", \"unit\"})");
    auto inner = json_convention_breaches(child, where);
    breaches.insert(breaches.end(), inner.begin(), inner.end());
  }
  return breaches;
}

}  // namespace rupture::testing
