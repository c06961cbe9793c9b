// The cubic peak fit: where a maximum is on exact curves, and what it does where the data end at or
// just past the maximum (the loading of a sample that came apart, cut at its collapse's onset).
#include "analysis/peak_fit.hpp"

#include <gtest/gtest.h>

#include <cstddef>
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

// A cubic is fitted exactly, so its maximum comes out to rounding wherever the window falls.
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

// A maximum two samples before the end: with a closed end its window would need three samples past
// it, so it is not found (cut short); at an open end the window ends at the last sample and the
// maximum is found where it is.
TEST(PeakFit, AMaximumNextToAnOpenEndIsFittedByAWindowThatEndsThere) {
  const auto parabola = [](double x) { return 1.0 - (x - 0.5) * (x - 0.5); };
  const auto s = sampled(parabola, 0.01, 0.52);
  const PeakFit closed = fit_peak(s.x, s.y, 0.0, 1.0);
  EXPECT_FALSE(closed.found);
  EXPECT_TRUE(closed.cut_short);
  PeakFitOptions open;
  open.open_end = true;
  const PeakFit fit = fit_peak(s.x, s.y, 0.0, 1.0, open);
  ASSERT_TRUE(fit.found) << fit.problem;
  EXPECT_NEAR(fit.x, 0.5, 1e-9);
  EXPECT_NEAR(fit.window_high, 0.52, 1e-12);
  EXPECT_GE(fit.points, 2 * open.min_side + 1);
}

// A curve still rising where the data end: at an open end its maximum is the last sample (the force
// was still rising when the sample came apart), not the cubic's stationary point beyond the data.
TEST(PeakFit, ACurveStillRisingAtAnOpenEndPeaksAtItsLastSample) {
  const auto parabola = [](double x) { return 1.0 - (x - 0.5) * (x - 0.5); };
  const auto s = sampled(parabola, 0.01, 0.45);
  EXPECT_FALSE(fit_peak(s.x, s.y, 0.0, 1.0).found);
  PeakFitOptions open;
  open.open_end = true;
  const PeakFit fit = fit_peak(s.x, s.y, 0.0, 1.0, open);
  ASSERT_TRUE(fit.found) << fit.problem;
  EXPECT_NEAR(fit.x, 0.45, 1e-12);
  EXPECT_NEAR(fit.value, parabola(0.45), 1e-12);
  // The start stays closed: a curve falling from its first sample has no maximum to fit.
  const auto falling = sampled([](double x) { return -x; }, 0.01, 0.3);
  EXPECT_FALSE(fit_peak(falling.x, falling.y, 0.0, 1.0, open).found);
}

}  // namespace
}  // namespace rupture::analysis
