// The cubic peak fit: where a maximum is on an exact curve, and what it says where the data end just
// past the maximum. The corner fit: where two lines meet at a maximum.
#include "analysis/peak_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <random>
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

// A tissue's top: rising at 0.4 and falling at 1.5 from a corner between two samples. Two lines fit it
// exactly, so the corner comes out to 1e-8 (the residual is quadratic about it); a cubic over it lands
// on the shallower side.
TEST(PeakFit, FindsTheCornerOfTwoLinesBetweenSamples) {
  const auto tent = [](double x) { return x < 0.4237 ? 1.0 - 0.4 * (0.4237 - x) : 1.0 - 1.5 * (x - 0.4237); };
  const auto s = sampled(tent, 0.002, 0.44);
  const PeakFit corner = fit_corner(s.x, s.y);
  ASSERT_TRUE(corner.found) << corner.problem;
  EXPECT_TRUE(corner.corner);
  EXPECT_NEAR(corner.x, 0.4237, 1e-8);
  EXPECT_NEAR(corner.value, 1.0, 1e-8);
  EXPECT_NEAR(corner.left_slope, 0.4, 1e-6);
  EXPECT_NEAR(corner.right_slope, -1.5, 1e-6);
  EXPECT_EQ(corner.index, 212u);
  const PeakFit cubic = fit_peak(s.x, s.y, 0.0, 1.0);
  ASSERT_TRUE(cubic.found) << cubic.problem;
  EXPECT_FALSE(cubic.corner);
  EXPECT_LT(cubic.x, 0.4237 - 0.002) << "the cubic over the corner is pulled to its shallower side";
}

// The same kind of corner under white noise of 0.5 % of its height lands within a few samples; a curve
// that only rises has no corner at a maximum.
TEST(PeakFit, ACornerUnderNoiseIsFoundAndARisingLineHasNone) {
  std::mt19937_64 engine(3);
  std::normal_distribution<double> noise(0.0, 0.005);
  double squares = 0.0;
  for (int draw = 0; draw < 20; ++draw) {
    auto s = sampled([](double x) { return x < 0.4 ? 1.0 - 0.5 * (0.4 - x) : 1.0 - 1.5 * (x - 0.4); }, 0.002,
                     0.43);
    for (double& y : s.y) y += noise(engine);
    const PeakFit corner = fit_corner(std::vector<double>(s.x.begin() + 150, s.x.end()),
                                      std::vector<double>(s.y.begin() + 150, s.y.end()));
    ASSERT_TRUE(corner.found) << corner.problem;
    squares += (corner.x - 0.4) * (corner.x - 0.4);
  }
  EXPECT_LT(std::sqrt(squares / 20.0), 0.004);
  const auto line = sampled([](double x) { return x; }, 0.002, 0.1);
  const PeakFit rising = fit_corner(line.x, line.y);
  EXPECT_FALSE(rising.found);
  EXPECT_NE(rising.problem.find("do not meet at a maximum"), std::string::npos) << rising.problem;
  // A line that turns down only in its last two samples: the corner would rest on three samples at the
  // window's end, where noise alone makes one.
  std::vector<double> x, y;
  for (int i = 0; i < 20; ++i) {
    x.push_back(i);
    y.push_back(i <= 17 ? i : 17 - (i - 17));
  }
  const PeakFit at_end = fit_corner(x, y);
  EXPECT_FALSE(at_end.found);
  EXPECT_TRUE(at_end.cut_short);
  EXPECT_NE(at_end.problem.find("at the end of the window"), std::string::npos) << at_end.problem;
  EXPECT_FALSE(fit_corner(std::vector<double>(line.x.begin(), line.x.begin() + 6),
                          std::vector<double>(line.y.begin(), line.y.begin() + 6))
                   .found)
      << "six samples cannot hold three on each side of a corner";
}

}  // namespace
}  // namespace rupture::analysis
