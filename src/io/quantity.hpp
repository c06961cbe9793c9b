// io/quantity: the one JSON form of a number with a unit, used by every rupture output
// (docs/formats.md, "Numbers in JSON outputs"): {"value": v, "unit": "u"}, with "error" (one
// standard deviation, same unit) beside the value when it has an uncertainty. `value` may be a
// number, a list (a curve, a range [low, high]) or null (undefined). A bare JSON number is
// dimensionless and exact: a count, an index, a fraction or a ratio whose key says what it is
// relative to. Keys never carry units.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rupture::io {

// {"value": v, "unit": u}; a NaN is written as null (JSON has no NaN).
nlohmann::json quantity(double value, std::string_view unit);
// {"value": v, "error": e, "unit": u}
nlohmann::json quantity(double value, double error, std::string_view unit);
// {"value": [v, ...], "unit": u}: a curve, or a range {low, high}.
nlohmann::json quantity(const std::vector<double>& values, std::string_view unit);
// null when `value` is empty.
nlohmann::json quantity(const std::optional<double>& value, std::string_view unit);

// The unit of a quotient, e.g. "mJ" / "%" -> "mJ/%"; a dimensionless denominator drops out.
std::string unit_ratio(const std::string& numerator, const std::string& denominator);

// The number a quantity holds: its "value", or a bare number as files of builds before this
// convention wrote it; nullopt when `q` is null, absent or holds no number.
std::optional<double> quantity_value(const nlohmann::json& q);

}  // namespace rupture::io
