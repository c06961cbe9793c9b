#include "io/quantity.hpp"

#include <cmath>

namespace rupture::io {

namespace {

nlohmann::json number(double value) { return std::isfinite(value) ? nlohmann::json(value) : nullptr; }

}  // namespace

nlohmann::json quantity(double value, std::string_view unit) {
  return {{"value", number(value)}, {"unit", std::string(unit)}};
}

nlohmann::json quantity(double value, double error, std::string_view unit) {
  return {{"value", number(value)}, {"error", number(error)}, {"unit", std::string(unit)}};
}

nlohmann::json quantity(const std::vector<double>& values, std::string_view unit) {
  nlohmann::json list = nlohmann::json::array();
  for (const double v : values) list.push_back(number(v));
  return {{"value", std::move(list)}, {"unit", std::string(unit)}};
}

nlohmann::json quantity(const std::optional<double>& value, std::string_view unit) {
  return value ? quantity(*value, unit) : nlohmann::json(nullptr);
}

std::string unit_ratio(const std::string& numerator, const std::string& denominator) {
  if (denominator == "1") return numerator;
  return numerator + "/" +
         (denominator.find('/') != std::string::npos ? "(" + denominator + ")" : denominator);
}

std::optional<double> quantity_value(const nlohmann::json& q) {
  const nlohmann::json& number = q.is_object() && q.contains("value") ? q.at("value") : q;
  if (number.is_number()) return number.get<double>();
  return std::nullopt;
}

}  // namespace rupture::io
