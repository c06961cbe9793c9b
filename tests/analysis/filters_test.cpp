// Filters and Savitzky–Golay weights against SciPy's output (fixtures from data/make_fixtures.py),
// plus the properties the pipeline relies on.
#include "analysis/filters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "core/random.hpp"
#include "io/csv.hpp"

namespace rupture::analysis {
namespace {

const std::string data_dir = ANALYSIS_DATA_DIR;

struct Fixture {
  io::CsvTable input = io::read_csv(data_dir + "filters_input.csv");
  io::CsvTable expected = io::read_csv(data_dir + "filters_expected.csv");
  const std::vector<double>& y() const { return input.column("y"); }
  double step() const { return input.column("x")[1] - input.column("x")[0]; }
};

void expect_close(const std::vector<double>& actual, const std::vector<double>& expected, double tolerance,
                  const std::string& what) {
  ASSERT_EQ(actual.size(), expected.size()) << what;
  double scale = 0.0;
  for (double v : expected) scale = std::max(scale, std::abs(v));
  for (std::size_t i = 0; i < actual.size(); ++i) {
    ASSERT_NEAR(actual[i], expected[i], tolerance * scale) << what << " at sample " << i;
  }
}

TEST(SavitzkyGolay, SmoothingMatchesScipy) {
  const Fixture f;
  for (auto [w, p] : {std::pair{11, 3}, {21, 2}, {7, 3}}) {
    const auto name = "sg_" + std::to_string(w) + "_" + std::to_string(p);
    expect_close(savgol_filter(f.y(), w, p), f.expected.column(name), 1e-12, name);
  }
}

TEST(SavitzkyGolay, DerivativesMatchScipy) {
  const Fixture f;
  for (auto [w, p] : {std::pair{15, 3}, {9, 3}}) {
    const auto name = "sgd1_" + std::to_string(w) + "_" + std::to_string(p);
    expect_close(savgol_filter(f.y(), w, p, 1, f.step()), f.expected.column(name), 1e-11, name);
  }
  expect_close(savgol_filter(f.y(), 13, 4, 2, f.step()), f.expected.column("sgd2_13_4"), 1e-10, "sgd2_13_4");
}

TEST(SavitzkyGolay, CubicDerivativeIsExactForCubics) {
  std::vector<double> y(50);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double x = 0.1 * static_cast<double>(i);
    y[i] = 2.0 - x + 0.5 * x * x - 0.25 * x * x * x;
  }
  const auto d = savgol_filter(y, 9, 3, 1, 0.1);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double x = 0.1 * static_cast<double>(i);
    EXPECT_NEAR(d[i], -1.0 + x - 0.75 * x * x, 1e-10) << i;
  }
}

TEST(Butterworth, DesignMatchesScipyTransferFunction) {
  const auto table = io::read_csv(data_dir + "butter_sos.csv");
  for (auto [order, cutoff] : {std::pair{4, 0.1}, {3, 0.25}, {2, 0.05}, {6, 0.4}}) {
    const auto ours = butterworth_lowpass(order, cutoff);
    // Compare the cascade's frequency response (section order and pairing are free choices).
    for (double omega : {0.0, 0.3, 1.0, 2.0, 3.0}) {
      const std::complex<double> z = std::exp(std::complex<double>(0.0, -omega));
      std::complex<double> h_ours = 1.0, h_scipy = 1.0;
      for (const auto& s : ours) h_ours *= (s.b0 + s.b1 * z + s.b2 * z * z) / (1.0 + s.a1 * z + s.a2 * z * z);
      for (std::size_t r = 0; r < table.rows(); ++r) {
        if (table.column("order")[r] != order || table.column("cutoff")[r] != cutoff) continue;
        const auto c = [&](const char* name) { return table.column(name)[r]; };
        h_scipy *= (c("b0") + c("b1") * z + c("b2") * z * z) / (c("a0") + c("a1") * z + c("a2") * z * z);
      }
      EXPECT_NEAR(std::abs(h_ours - h_scipy), 0.0, 1e-12)
          << "order " << order << " cutoff " << cutoff << " omega " << omega;
    }
    // Half power at the cutoff: |H(e^{iπ Wn})|² = 1/2.
    const std::complex<double> z = std::exp(std::complex<double>(0.0, -3.14159265358979323846 * cutoff));
    std::complex<double> h = 1.0;
    for (const auto& s : ours) h *= (s.b0 + s.b1 * z + s.b2 * z * z) / (1.0 + s.a1 * z + s.a2 * z * z);
    EXPECT_NEAR(std::norm(h), 0.5, 1e-12);
  }
}

TEST(Butterworth, SosfiltfiltMatchesScipy) {
  const Fixture f;
  for (auto [order, cutoff, name] : {std::tuple{4, 0.1, "bw_4_0.1"},
                                     {3, 0.25, "bw_3_0.25"},
                                     {2, 0.05, "bw_2_0.05"},
                                     {6, 0.4, "bw_6_0.4"}}) {
    const auto sections = butterworth_lowpass(order, cutoff);
    expect_close(sosfiltfilt(sections, f.y()), f.expected.column(name), 1e-10, name);
  }
}

TEST(Noise, DifferenceEstimatorRecoversWhiteNoiseOnATrend) {
  Rng rng(7, RandomStream::analysis_noise);
  std::vector<double> y(20000);
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(y.size());
    y[i] = 3.0 * x * (1.0 - x) + 0.01 * rng.normal();
  }
  EXPECT_NEAR(noise_from_differences(y), 0.01, 0.0005);
  std::vector<double> white(20000);
  for (auto& v : white) v = 0.5 * rng.normal();
  EXPECT_NEAR(robust_scale(white), 0.5, 0.02);
  EXPECT_LT(correlation_length(white), 1.2);
  // A moving average over 9 samples: correlation length 9.
  std::vector<double> smooth(white.size() - 8);
  for (std::size_t i = 0; i < smooth.size(); ++i) {
    for (std::size_t k = 0; k < 9; ++k) smooth[i] += white[i + k];
  }
  EXPECT_NEAR(correlation_length(smooth), 9.0, 1.5);
}

TEST(AutomaticFilter, SmoothsNoiseButKeepsThePeak) {
  Rng rng(11, RandomStream::analysis_noise);
  const std::size_t n = 2000;
  std::vector<double> clean(n), noisy(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(n - 1);
    clean[i] = x * (1.0 - x);
    noisy[i] = clean[i] + 0.002 * rng.normal();
  }
  for (auto kind : {FilterKind::butterworth, FilterKind::savitzky_golay}) {
    FilterSettings settings;
    settings.kind = kind;
    const auto filtered = apply_filter(settings, noisy);
    double square = 0.0;
    for (std::size_t i = 0; i < n; ++i) square += (filtered[i] - clean[i]) * (filtered[i] - clean[i]);
    // The filtered curve is much closer to the truth than the noise level (0.002) is.
    EXPECT_LT(std::sqrt(square / n), 0.4 * 0.002) << to_string(kind);
    if (kind == FilterKind::butterworth)
      EXPECT_LT(settings.cutoff, 0.1);
    else
      EXPECT_GT(settings.savgol_window, 31);
  }
}

// The cap on smoothing only ever weakens a filter, to a period of at most the given samples, and
// never past the weakest filter each kind has.
TEST(AutomaticFilter, LimitOnSmoothingOnlyWeakensTheFilter) {
  FilterSettings strong;
  strong.cutoff = 0.01;  // a period of 200 samples
  limit_smoothing(strong, 50.0);
  EXPECT_DOUBLE_EQ(strong.cutoff, 0.04);
  FilterSettings weak;
  weak.cutoff = 0.1;  // 20 samples: already within 50
  limit_smoothing(weak, 50.0);
  EXPECT_DOUBLE_EQ(weak.cutoff, 0.1);
  limit_smoothing(weak, 1.0);
  EXPECT_DOUBLE_EQ(weak.cutoff, 0.95);
  FilterSettings window;
  window.kind = FilterKind::savitzky_golay;
  window.savgol_window = 101;
  limit_smoothing(window, 31.0);
  EXPECT_EQ(window.savgol_window, 31);
  limit_smoothing(window, 40.0);
  EXPECT_EQ(window.savgol_window, 31);
  limit_smoothing(window, 2.0);
  EXPECT_EQ(window.savgol_window, 5);  // the smallest window of a cubic
}

// The floor on smoothing only ever strengthens a filter, to a period of at least the given samples,
// and never past the longest window the automatic choice tries.
TEST(AutomaticFilter, FloorOnSmoothingOnlyStrengthensTheFilter) {
  FilterSettings weak;
  weak.cutoff = 0.4;  // a period of 5 samples
  require_smoothing(weak, 50.0);
  EXPECT_DOUBLE_EQ(weak.cutoff, 0.04);
  FilterSettings strong;
  strong.cutoff = 0.01;  // 200 samples: already beyond 50
  require_smoothing(strong, 50.0);
  EXPECT_DOUBLE_EQ(strong.cutoff, 0.01);
  FilterSettings window;
  window.kind = FilterKind::savitzky_golay;
  window.savgol_window = 11;
  require_smoothing(window, 30.2);
  EXPECT_EQ(window.savgol_window, 31);
  require_smoothing(window, 20.0);
  EXPECT_EQ(window.savgol_window, 31);
  require_smoothing(window, 5000.0);
  EXPECT_EQ(window.savgol_window, max_auto_savgol_window);
}

// A piece cut short (the loading before a collapse) is continued by its trend before filtering: its
// filtered end follows the last noisy sample less than the plain padding's does, and stays unbiased. Straight
// line plus white noise of sd 1, 200 seeds, cutoff 0.05 (an edge of 20 samples).
TEST(CutEnd, FilteredEndFollowsTheTrendNotTheLastSample) {
  FilterSettings settings;
  settings.cutoff = 0.05;
  const std::size_t n = 400, seeds = 200;
  const auto line = [](std::size_t i) { return 0.01 * static_cast<double>(i); };
  double plain_square = 0.0, continued_square = 0.0, continued_sum = 0.0;
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    Rng rng(seed, RandomStream::analysis_noise);
    std::vector<double> y(n);
    for (std::size_t i = 0; i < n; ++i) y[i] = line(i) + rng.normal();
    FilterSettings chosen = settings;
    const double plain = apply_filter(chosen, y).back() - line(n - 1);
    const double continued = filter_continuing_end(settings, y).back() - line(n - 1);
    plain_square += plain * plain;
    continued_square += continued * continued;
    continued_sum += continued;
  }
  const double plain_sd = std::sqrt(plain_square / seeds), continued_sd = std::sqrt(continued_square / seeds);
  // Measured: 0.60 (the end follows the last sample, sd 1) against 0.39 (the end of the quadratic
  // through the last 60 samples, whose sd is sqrt(9/60) = 0.39; the line through 20 gave 0.42).
  EXPECT_GT(plain_sd, 0.5);
  EXPECT_LT(continued_sd, 0.8 * plain_sd);
  EXPECT_LT(std::abs(continued_sum / seeds), 3.0 * continued_sd / std::sqrt(static_cast<double>(seeds)));
}

// A concave top cut 5-30 samples past its maximum (a loading that came apart just past its force peak),
// cutoff 0.05 (an edge of 20 samples), no noise. Continued by its end's tangent, the filtered piece
// keeps its maximum on the top's sample and its end within 3·10⁻³ of the curve. The least-squares
// line through the last edge, continued, started above the concave end and rose at the slope of the
// window's middle: the filtered end 0.0065-0.0075 high and, cut 5 and 10 samples past the top, the
// maximum 5 and 2 samples late (at the end). A parabola is any quadratic's own shape, so this tells the
// tangent from the line, not how many edges the quadratic spans.
TEST(CutEnd, AConcaveTopCutPastItsMaximumKeepsItsMaximum) {
  FilterSettings settings;
  settings.cutoff = 0.05;
  const int top = 300;
  for (const int past : {5, 10, 20, 30}) {
    std::vector<double> y(static_cast<std::size_t>(top + past + 1));
    for (std::size_t i = 0; i < y.size(); ++i) {
      const double from_top = static_cast<double>(i) - top;
      y[i] = 1.0 - 1e-4 * from_top * from_top;
    }
    const auto filtered = filter_continuing_end(settings, y);
    const auto highest = std::max_element(filtered.begin(), filtered.end()) - filtered.begin();
    EXPECT_EQ(highest, top) << past;
    EXPECT_LT(std::abs(filtered.back() - y.back()), 3e-3) << past;
  }
}

// Away from the end, and on a piece too short to continue, the continued filter is the plain one.
TEST(CutEnd, LeavesTheStartAndShortPiecesAsThePlainFilterDoes) {
  FilterSettings settings;
  settings.cutoff = 0.05;
  Rng rng(3, RandomStream::analysis_noise);
  std::vector<double> y(400);
  for (auto& v : y) v = rng.normal();
  FilterSettings chosen = settings;
  const auto plain = apply_filter(chosen, y), continued = filter_continuing_end(settings, y);
  ASSERT_EQ(continued.size(), y.size());
  for (std::size_t i = 0; i < 50; ++i) EXPECT_NEAR(continued[i], plain[i], 1e-9) << i;
  const std::vector<double> short_piece(y.begin(), y.begin() + 39);  // under twice the edge of 20
  chosen = settings;
  EXPECT_EQ(filter_continuing_end(settings, short_piece), apply_filter(chosen, short_piece));
}

}  // namespace
}  // namespace rupture::analysis
