#include "fbm/distribution.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/math/distributions/uniform.hpp>
#include <boost/math/distributions/weibull.hpp>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/tokens.hpp"

namespace rupture::fbm {

namespace {

constexpr const char* dist_option = "--dist";
constexpr const char* dist_forms =
    "use uniform[:a=A,b=B], powerlaw:alpha=A, weibull:k=K[,lambda=L] or file:PATH";

using tokens::trim;

bool parse_number(std::string_view text, double& value) {
  const auto parsed = tokens::number<double>(trim(text));
  if (!parsed || !std::isfinite(*parsed)) return false;
  value = *parsed;
  return true;
}

// "k=2,lambda=1" -> {k: 2, lambda: 1}; every key must be in `allowed`.
std::map<std::string, double> parse_parameters(std::string_view name, std::string_view text,
                                               const std::vector<std::string>& allowed) {
  std::map<std::string, double> values;
  const std::string usage = fmt::format("{} takes {}", name, fmt::join(allowed, ", "));
  while (!text.empty()) {
    const auto comma = text.find(',');
    const std::string_view item = trim(text.substr(0, comma));
    text = comma == std::string_view::npos ? std::string_view{} : text.substr(comma + 1);
    const auto equals = item.find('=');
    if (equals == std::string_view::npos)
      throw InputError(dist_option, fmt::format("'{}' is not of the form key=value", excerpt(item)), usage);
    const std::string key(trim(item.substr(0, equals)));
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      throw InputError(dist_option, fmt::format("unknown parameter '{}' for {}", excerpt(key), name), usage);
    double value = 0.0;
    if (!parse_number(item.substr(equals + 1), value))
      throw InputError(
          dist_option,
          fmt::format("{}='{}' is not a finite number", key, excerpt(trim(item.substr(equals + 1)))), usage);
    if (!values.emplace(key, value).second)
      throw InputError(dist_option, fmt::format("parameter '{}' given twice", key), usage);
  }
  return values;
}

double get_or(const std::map<std::string, double>& values, const std::string& key, double fallback) {
  const auto it = values.find(key);
  return it == values.end() ? fallback : it->second;
}

}  // namespace

// ---- Uniform ------------------------------------------------------------------------------------

Uniform::Uniform(double a, double b) : a_(a), b_(b) {
  if (!(a >= 0.0 && b > a && std::isfinite(b)))
    throw InputError(dist_option, fmt::format("uniform needs 0 <= a < b (got a={}, b={})", a, b),
                     "e.g. --dist uniform:a=0.2,b=1");
}
std::string Uniform::spec() const { return fmt::format("uniform:a={},b={}", a_, b_); }
double Uniform::quantile(double u) const {
  return boost::math::quantile(boost::math::uniform_distribution<>(a_, b_), u);
}
double Uniform::pdf(double x) const {
  return x < a_ || x > b_ ? 0.0 : boost::math::pdf(boost::math::uniform_distribution<>(a_, b_), x);
}
double Uniform::pdf_derivative(double) const { return 0.0; }
double Uniform::cdf(double x) const {
  return x <= a_ ? 0.0 : x >= b_ ? 1.0 : boost::math::cdf(boost::math::uniform_distribution<>(a_, b_), x);
}

// ---- PowerLaw -----------------------------------------------------------------------------------
// Written out: p = (1+α) x^α has no Boost counterpart with the α in (-1, 0) range convenient.

PowerLaw::PowerLaw(double alpha) : alpha_(alpha) {
  if (!(alpha > -1.0))
    throw InputError(dist_option, fmt::format("powerlaw needs alpha > -1 (got alpha={})", alpha),
                     "p(x) = (1+alpha) x^alpha is normalisable on [0, 1] only for alpha > -1, e.g. --dist "
                     "powerlaw:alpha=2");
}
std::string PowerLaw::spec() const { return fmt::format("powerlaw:alpha={}", alpha_); }
double PowerLaw::quantile(double u) const { return std::pow(u, 1.0 / (1.0 + alpha_)); }
double PowerLaw::pdf(double x) const {
  if (x < 0.0 || x > 1.0) return 0.0;
  return (1.0 + alpha_) * std::pow(x, alpha_);
}
double PowerLaw::pdf_derivative(double x) const {
  if (x <= 0.0 || x > 1.0 || alpha_ == 0.0) return 0.0;
  return alpha_ * (1.0 + alpha_) * std::pow(x, alpha_ - 1.0);
}
double PowerLaw::cdf(double x) const { return x <= 0.0 ? 0.0 : x >= 1.0 ? 1.0 : std::pow(x, 1.0 + alpha_); }

// ---- Weibull ------------------------------------------------------------------------------------

Weibull::Weibull(double shape_k, double scale_lambda) : k_(shape_k), lambda_(scale_lambda) {
  if (!(k_ > 0.0))
    throw InputError(dist_option, fmt::format("weibull needs k > 0 (got k={})", k_),
                     "e.g. --dist weibull:k=2,lambda=1");
  if (!(lambda_ > 0.0))
    throw InputError(dist_option, fmt::format("weibull needs lambda > 0 (got lambda={})", lambda_),
                     "e.g. --dist weibull:k=2,lambda=1");
}
std::string Weibull::spec() const { return fmt::format("weibull:k={},lambda={}", k_, lambda_); }
double Weibull::quantile(double u) const {
  return boost::math::quantile(boost::math::weibull_distribution<>(k_, lambda_), u);
}
double Weibull::pdf(double x) const {
  if (x < 0.0) return 0.0;
  // Boost reports p(0) for k < 1 as an overflow error; the density does diverge there.
  if (x == 0.0) return k_ < 1.0 ? std::numeric_limits<double>::infinity() : k_ == 1.0 ? 1.0 / lambda_ : 0.0;
  return boost::math::pdf(boost::math::weibull_distribution<>(k_, lambda_), x);
}
double Weibull::pdf_derivative(double x) const {
  if (x <= 0.0) return 0.0;
  // p'(x) = p(x) [(k-1)/x - k x^(k-1) / λ^k]
  const double z = std::pow(x / lambda_, k_);
  return pdf(x) * ((k_ - 1.0) - k_ * z) / x;
}
double Weibull::cdf(double x) const {
  return x <= 0.0 ? 0.0 : boost::math::cdf(boost::math::weibull_distribution<>(k_, lambda_), x);
}

// ---- Empirical ----------------------------------------------------------------------------------

Empirical::Empirical(std::vector<double> thresholds, std::string source)
    : sorted_(std::move(thresholds)), source_(std::move(source)) {
  if (sorted_.empty())
    throw InputError(source_, "no thresholds", "write one threshold (a breaking strain) per line");
  std::sort(sorted_.begin(), sorted_.end());
}
double Empirical::quantile(double u) const {
  const auto n = sorted_.size();
  const auto i = static_cast<std::size_t>(u * static_cast<double>(n));
  return sorted_[std::min(i, n - 1)];
}

std::vector<double> parse_thresholds(std::string_view text, const std::string& source) {
  std::vector<double> thresholds;
  std::size_t line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const auto newline = text.find('\n');
    std::string_view line = text.substr(0, newline);
    text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
    line = trim(line.substr(0, line.find('#')));
    if (line.empty()) continue;
    double value = 0.0;
    const std::string where = fmt::format("{}:{}", source, line_number);
    if (!parse_number(line, value))
      throw InputError(where, fmt::format("'{}' is not a number", excerpt(line)),
                       "write one threshold (a breaking strain) per line; '#' starts a comment");
    if (value < 0.0)
      throw InputError(where, fmt::format("threshold {} is negative", value),
                       "thresholds are breaking strains, >= 0");
    thresholds.push_back(value);
  }
  if (thresholds.empty())
    throw InputError(source, "no thresholds in the file", "write one threshold (a breaking strain) per line");
  return thresholds;
}

std::unique_ptr<StrengthDistribution> parse_distribution_spec(
    std::string_view spec, const std::function<std::string(const std::string& path)>& read_text) {
  spec = trim(spec);
  const auto colon = spec.find(':');
  const std::string name(trim(spec.substr(0, colon)));
  const std::string_view rest = colon == std::string_view::npos ? std::string_view{} : spec.substr(colon + 1);
  if (name == "uniform") {
    const auto values = parse_parameters(name, rest, {"a", "b"});
    return std::make_unique<Uniform>(get_or(values, "a", 0.0), get_or(values, "b", 1.0));
  }
  if (name == "powerlaw") {
    const auto values = parse_parameters(name, rest, {"alpha"});
    if (!values.count("alpha"))
      throw InputError(dist_option, "powerlaw needs alpha", "e.g. --dist powerlaw:alpha=2");
    return std::make_unique<PowerLaw>(values.at("alpha"));
  }
  if (name == "weibull") {
    const auto values = parse_parameters(name, rest, {"k", "lambda"});
    if (!values.count("k"))
      throw InputError(dist_option, "weibull needs the shape k", "e.g. --dist weibull:k=2,lambda=1");
    return std::make_unique<Weibull>(values.at("k"), get_or(values, "lambda", 1.0));
  }
  if (name == "file") {
    const std::string path(trim(rest));
    if (path.empty()) throw InputError(dist_option, "file needs a path", "e.g. --dist file:thresholds.txt");
    return std::make_unique<Empirical>(parse_thresholds(read_text(path), path), path);
  }
  throw InputError(dist_option, fmt::format("unknown distribution '{}'", excerpt(name)), dist_forms);
}

}  // namespace rupture::fbm
