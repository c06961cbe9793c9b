// The load-free separation rule on hand-made force histories (the connectivity rule is exercised by
// the tissue runs).
#include "loading/separation.hpp"

#include <gtest/gtest.h>

namespace rupture::loading {
namespace {

// Feeds `steps` equal forces and checks at `strain`.
bool interval(LoadFreeWatch& watch, double force, int steps, double strain, bool broken = true) {
  for (int i = 0; i < steps; ++i) watch.add(force);
  return watch.check(strain, broken);
}

TEST(LoadFreeWatch, SeparatesAfterTheForceStaysLowOverTheWindow) {
  LoadFreeWatch watch(0.1, 0.2);
  EXPECT_FALSE(interval(watch, 50.0, 10, 0.1));
  EXPECT_FALSE(interval(watch, 100.0, 10, 0.2));  // peak of interval means: 100 N
  EXPECT_FALSE(interval(watch, 9.0, 10, 0.3));    // below 10 N since 0.2 %
  EXPECT_FALSE(interval(watch, 9.0, 10, 0.35));   // 0.15 % of the 0.2 % window
  EXPECT_TRUE(interval(watch, 9.0, 10, 0.4));     // 0.2 % below: load-free
}

TEST(LoadFreeWatch, AnIntervalAboveTheFractionRestartsTheWindow) {
  // Strains are exact binary fractions so that the window comparison is exact.
  LoadFreeWatch watch(0.1, 0.25);
  interval(watch, 100.0, 10, 0.25);
  EXPECT_FALSE(interval(watch, 5.0, 10, 0.375));
  EXPECT_FALSE(interval(watch, 20.0, 10, 0.5));   // the force came back
  EXPECT_FALSE(interval(watch, 5.0, 10, 0.625));  // the stretch restarts at 0.5 %
  EXPECT_TRUE(interval(watch, 5.0, 10, 0.75));
}

TEST(LoadFreeWatch, OneRingingStepIsAveragedOut) {
  LoadFreeWatch watch(0.1, 0.2);
  interval(watch, 100.0, 10, 0.2);
  watch.add(60.0);  // one spike among nine quiet steps: interval mean 6 N < 10 N
  EXPECT_FALSE(interval(watch, 0.0, 9, 0.3));
  EXPECT_TRUE(interval(watch, 0.0, 10, 0.4));
}

TEST(LoadFreeWatch, NeverBeforeABondBreaksNorWhenSwitchedOff) {
  LoadFreeWatch intact(0.1, 0.2);
  interval(intact, 100.0, 10, 0.2, false);
  for (double x = 0.3; x < 2.0; x += 0.1) EXPECT_FALSE(interval(intact, 0.0, 10, x, false));
  LoadFreeWatch off(0.0, 0.2);
  interval(off, 100.0, 10, 0.2);
  for (double x = 0.3; x < 2.0; x += 0.1) EXPECT_FALSE(interval(off, 0.0, 10, x));
}

TEST(LoadFreeWatch, ResumesFromItsState) {
  LoadFreeWatch first(0.1, 0.2);
  interval(first, 100.0, 10, 0.2);
  interval(first, 5.0, 10, 0.3);
  first.add(5.0);
  LoadFreeWatch resumed(0.1, 0.2, first.state());
  for (int i = 0; i < 9; ++i) {
    first.add(5.0);
    resumed.add(5.0);
  }
  EXPECT_EQ(first.check(0.4, true), resumed.check(0.4, true));
  EXPECT_TRUE(resumed.state().load_free);
  EXPECT_DOUBLE_EQ(resumed.state().free_since, 0.2);
}

}  // namespace
}  // namespace rupture::loading
