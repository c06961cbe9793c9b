// The cubic peak fit: where a maximum is on an exact curve, and what it says where the data end just
// past the maximum.
#include "analysis/peak_fit.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

namespace rupture::analysis {
namespace {

struct Sampled {
  std::vector<double> x, y;
};

// y(x) on x = 0, step, ... up to `end` (inclusive within rounding).
template <class Curve>
Sampled sampled(Curve curve, double step, double end) {
  Sampled s;
  for (std::size_t i = 0; static_cast<double>(i) * step <= end + 1e-12; ++i) {
    s.x.push_back(static_cast<double>(i) * step);
    s.y.push_back(curve(s.x.back()));
  }
  return s;
}

// A cubic is fitted exactly, so its maximum comes out to rounding.
TEST(PeakFit, FindsTheMaximumOfACubic) {
  const auto cubic = [](double x) {
    return 1.0 - (x - 0.5) * (x - 0.5) + 0.3 * (x - 0.5) * (x - 0.5) * (x - 0.5);
  };
  const auto s = sampled(cubic, 0.01, 1.0);
  const PeakFit fit = fit_peak(s.x, s.y, 0.0, 1.0);
  ASSERT_TRUE(fit.found) << fit.problem;
  EXPECT_NEAR(fit.x, 0.5, 1e-9);
  EXPECT_NEAR(fit.value, 1.0, 1e-12);
}

// A maximum two samples before the end: its window would need three samples past it, so it is not
// found, and the fit says the data end too soon (a cut loading is fitted across its onset instead).
TEST(PeakFit, AMaximumWithinMinSideOfTheEndIsCutShort) {
  const auto parabola = [](double x) { return 1.0 - (x - 0.5) * (x - 0.5); };
  const auto s = sampled(parabola, 0.01, 0.52);
  const PeakFit fit = fit_peak(s.x, s.y, 0.0, 1.0, {}, "%");
  EXPECT_FALSE(fit.found);
  EXPECT_TRUE(fit.cut_short);
  EXPECT_NE(fit.problem.find("at the end of the data (x = 0.5 %)"), std::string::npos) << fit.problem;
}

}  // namespace
}  // namespace rupture::analysis
