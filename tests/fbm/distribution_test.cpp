// Distributions and the --dist spec language: values, round trips, and bad input rejected with a
// message that names the option (or file:line) and the fix.
#include "fbm/distribution.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace rupture::fbm {
namespace {

using ::testing::HasSubstr;

std::string no_file(const std::string& path) { throw InputError(path, "unexpected file read"); }

std::unique_ptr<StrengthDistribution> parse(const std::string& spec) {
  return parse_distribution_spec(spec, no_file);
}

// The message of the InputError that `spec` raises ("" if none).
std::string error_of(const std::string& spec, const std::string& file_text = {}) {
  try {
    parse_distribution_spec(spec, [&](const std::string&) { return file_text; });
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

TEST(DistributionSpec, ParsesEveryFormAndRoundTripsItsSpec) {
  EXPECT_EQ(parse("uniform")->spec(), "uniform:a=0,b=1");
  EXPECT_EQ(parse("uniform:a=0.2,b=1")->spec(), "uniform:a=0.2,b=1");
  EXPECT_EQ(parse("powerlaw:alpha=2.5")->spec(), "powerlaw:alpha=2.5");
  EXPECT_EQ(parse("weibull:k=2")->spec(), "weibull:k=2,lambda=1");
  EXPECT_EQ(parse(" weibull: k=1.5 , lambda=3 ")->spec(), "weibull:k=1.5,lambda=3");
  for (const char* spec : {"uniform:a=0.2,b=1", "powerlaw:alpha=-0.5", "weibull:k=0.7,lambda=2"})
    EXPECT_EQ(parse(parse(spec)->spec())->spec(), parse(spec)->spec());
}

TEST(DistributionSpec, BadSpecsNameTheOptionAndTheFix) {
  EXPECT_THAT(error_of("foo"), HasSubstr("--dist: unknown distribution 'foo'; use uniform"));
  EXPECT_THAT(error_of("powerlaw:alpha=-1"), HasSubstr("alpha > -1"));
  EXPECT_THAT(error_of("powerlaw:alpha=-3"), HasSubstr("alpha > -1"));
  EXPECT_THAT(error_of("powerlaw"), HasSubstr("powerlaw needs alpha"));
  EXPECT_THAT(error_of("weibull:k=0"), HasSubstr("k > 0"));
  EXPECT_THAT(error_of("weibull:k=-2"), HasSubstr("k > 0"));
  EXPECT_THAT(error_of("weibull:k=2,lambda=0"), HasSubstr("lambda > 0"));
  EXPECT_THAT(error_of("uniform:a=1,b=0.5"), HasSubstr("0 <= a < b"));
  EXPECT_THAT(error_of("uniform:c=1"), HasSubstr("unknown parameter 'c'"));
  EXPECT_THAT(error_of("weibull:k=two"), HasSubstr("'two' is not a finite number"));
  EXPECT_THAT(error_of("weibull:k=2,k=3"), HasSubstr("given twice"));
  EXPECT_THAT(error_of("file:"), HasSubstr("file needs a path"));
  for (const char* spec : {"foo", "powerlaw:alpha=-1", "weibull:k=0"})
    EXPECT_THAT(error_of(spec), HasSubstr("--dist"));
}

TEST(Thresholds, CommentsAndBlankLinesAreSkipped) {
  const auto t = parse_thresholds("# measured strains\n0.3\n\n0.1  # weakest\n  0.2\r\n", "t.txt");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0], 0.3);
  EXPECT_EQ(t[1], 0.1);
  EXPECT_EQ(t[2], 0.2);
  const auto empirical = parse_distribution_spec(
      "file:t.txt", [](const std::string&) { return std::string("0.3\n0.1\n0.2\n"); });
  EXPECT_EQ(empirical->spec(), "file:t.txt");
  EXPECT_EQ(empirical->lower(), 0.1);
  EXPECT_EQ(empirical->upper(), 0.3);
  EXPECT_EQ(empirical->quantile(0.0), 0.1);
  EXPECT_EQ(empirical->quantile(0.5), 0.2);
  EXPECT_EQ(empirical->quantile(0.999), 0.3);
}

TEST(Thresholds, BadFilesNameFileAndLine) {
  EXPECT_THAT(error_of("file:t.txt", ""), HasSubstr("t.txt: no thresholds"));
  EXPECT_THAT(error_of("file:t.txt", "# only a comment\n\n"), HasSubstr("t.txt: no thresholds"));
  EXPECT_THAT(error_of("file:t.txt", "0.1\n0.2\nabc\n"), HasSubstr("t.txt:3: 'abc' is not a number"));
  EXPECT_THAT(error_of("file:t.txt", "0.1\n-0.2\n"), HasSubstr("t.txt:2: threshold -0.2 is negative"));
  EXPECT_THAT(error_of("file:t.txt", "0.1 0.2\n"), HasSubstr("t.txt:1:"));
}

TEST(Distributions, QuantileInvertsTheCdf) {
  for (const char* spec : {"uniform:a=0.2,b=1", "powerlaw:alpha=-0.6", "powerlaw:alpha=3",
                           "weibull:k=0.6,lambda=2", "weibull:k=3"}) {
    const auto d = parse(spec);
    const auto& c = dynamic_cast<const ContinuousDistribution&>(*d);
    for (double u : {1e-6, 0.1, 0.5, 0.9, 0.999999})
      EXPECT_NEAR(c.cdf(c.quantile(u)), u, 1e-12) << spec << " u=" << u;
  }
}

TEST(Distributions, DensityDerivativeMatchesFiniteDifferences) {
  for (const char* spec : {"powerlaw:alpha=-0.6", "powerlaw:alpha=3", "weibull:k=0.6,lambda=2", "weibull:k=3",
                           "uniform:a=0.2,b=1"}) {
    const auto d = parse(spec);
    const auto& c = dynamic_cast<const ContinuousDistribution&>(*d);
    for (double u : {0.1, 0.4, 0.8}) {
      const double x = c.quantile(u), h = 1e-5 * x;
      const double numeric = (c.pdf(x + h) - c.pdf(x - h)) / (2 * h);
      EXPECT_NEAR(c.pdf_derivative(x), numeric, 1e-6 * (std::abs(numeric) + c.pdf(x) / x))
          << spec << " x=" << x;
      // p = dP/dx as well.
      EXPECT_NEAR(c.pdf(x), (c.cdf(x + h) - c.cdf(x - h)) / (2 * h), 1e-7 * c.pdf(x)) << spec << " x=" << x;
    }
  }
}

}  // namespace
}  // namespace rupture::fbm
