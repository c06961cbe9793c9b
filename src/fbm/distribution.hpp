// fbm/distribution: fiber strength-threshold distributions (thresholds are strains, dimensionless)
// and the `--dist` spec language that names them. Owns p(x), P(x), p'(x), the support and the
// quantile used to draw thresholds. Not: the bundle mechanics (els_theory, bundle) or file I/O
// (the caller passes a function that reads a thresholds file).
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rupture::fbm {

// Anything fiber thresholds can be drawn from.
class StrengthDistribution {
 public:
  virtual ~StrengthDistribution() = default;
  // Canonical `--dist` spec that reproduces this distribution, e.g. "weibull:k=2,lambda=1".
  virtual std::string spec() const = 0;
  // Support [lower, upper] of the thresholds; upper may be +infinity.
  virtual double lower() const = 0;
  virtual double upper() const = 0;
  // Inverse CDF for u in [0, 1): the transform that turns uniform random numbers into thresholds.
  virtual double quantile(double u) const = 0;
};

// A distribution with a density: the ELS theory of paper section 2 applies to it directly.
class ContinuousDistribution : public StrengthDistribution {
 public:
  // Density p(x) (0 outside the support; at a lower cut-off the value just inside it).
  virtual double pdf(double x) const = 0;
  // p'(x) inside the support, needed for dℰ/dx (paper eq. 13).
  virtual double pdf_derivative(double x) const = 0;
  virtual double cdf(double x) const = 0;
};

// Uniform on [a, b], 0 <= a < b.
class Uniform final : public ContinuousDistribution {
 public:
  Uniform(double a, double b);
  std::string spec() const override;
  double lower() const override { return a_; }
  double upper() const override { return b_; }
  double quantile(double u) const override;
  double pdf(double x) const override;
  double pdf_derivative(double x) const override;
  double cdf(double x) const override;

 private:
  double a_, b_;
};

// Power law p(x) = (1+α) x^α on [0, 1], α > -1 (paper eq. 15; α = 0 is the uniform case).
class PowerLaw final : public ContinuousDistribution {
 public:
  explicit PowerLaw(double alpha);
  std::string spec() const override;
  double lower() const override { return 0.0; }
  double upper() const override { return 1.0; }
  double quantile(double u) const override;
  double pdf(double x) const override;
  double pdf_derivative(double x) const override;
  double cdf(double x) const override;
  double alpha() const { return alpha_; }

 private:
  double alpha_;
};

// Weibull with shape k > 0 and scale λ > 0: P(x) = 1 - exp(-(x/λ)^k) on [0, ∞).
class Weibull final : public ContinuousDistribution {
 public:
  Weibull(double shape_k, double scale_lambda);
  std::string spec() const override;
  double lower() const override { return 0.0; }
  double upper() const override { return std::numeric_limits<double>::infinity(); }
  double quantile(double u) const override;
  double pdf(double x) const override;
  double pdf_derivative(double x) const override;
  double cdf(double x) const override;

 private:
  double k_, lambda_;
};

// The empirical distribution of a list of measured thresholds. It has no density: its theory is
// the exact curve of the finite bundle made of exactly these fibers (see els_theory.hpp), and
// drawing from it resamples the list (the inverse of the empirical step CDF).
class Empirical final : public StrengthDistribution {
 public:
  // `source` names where the thresholds came from (the file), for spec() and messages.
  Empirical(std::vector<double> thresholds, std::string source);
  std::string spec() const override { return "file:" + source_; }
  double lower() const override { return sorted_.front(); }
  double upper() const override { return sorted_.back(); }
  double quantile(double u) const override;
  const std::vector<double>& sorted_thresholds() const { return sorted_; }

 private:
  std::vector<double> sorted_;
  std::string source_;
};

// Thresholds file: one number per line, blank lines and '#' comments (whole-line or trailing)
// allowed. Throws InputError naming `source:line` for a bad entry, or `source` when it holds no
// thresholds at all. Thresholds must be finite and >= 0 (they are breaking strains).
std::vector<double> parse_thresholds(std::string_view text, const std::string& source);

// Parses a `--dist` spec: "uniform", "uniform:a=0.2,b=1", "powerlaw:alpha=2",
// "weibull:k=2,lambda=1" (lambda defaults to 1) or "file:PATH". `read_text` reads PATH for the
// empirical case (the CLI passes io::read_text_file). Throws InputError naming `--dist` and the fix.
std::unique_ptr<StrengthDistribution> parse_distribution_spec(
    std::string_view spec, const std::function<std::string(const std::string& path)>& read_text);

}  // namespace rupture::fbm
