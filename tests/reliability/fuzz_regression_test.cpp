// Inputs the reader fuzzers (fuzz/) found, reduced to what triggers the defect, with the behaviour
// each must have now. Bad inputs a fuzzer finds go to bad_input_test.cpp instead.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "sample/formats.hpp"

namespace rupture {
namespace {

// sample_own_fuzzer: a provenance comment "#  units: ..." (two spaces) was kept as provenance
// "units: ...", written back as "# units: ...", and then skipped as the units line: the file did
// not read back the same. A comment that reads as the units line is now never provenance.
TEST(FuzzRegression, OwnSampleCommentThatReadsAsTheUnitsLineRoundTrips) {
  const std::string text =
      "rupture-sample 1\n#  units: x\n# made by hand\nbox 0 0 0 2 2 1\ndensity 0.00025\nparticles 1\n"
      "0 0.5 0.5 0.5 0.5 free\nbonds 0\nend\n";
  const Sample once = parse_own(text, "t.sample");
  EXPECT_EQ(once.provenance, std::vector<std::string>{"made by hand"});
  const std::string written = format_own(once);
  EXPECT_EQ(format_own(parse_own(written, "t.sample")), written);
}

// thresholds_fuzzer: a 2 kB file name in `--dist file:NAME` was cut to 400 bytes by the message's
// length net, so the message no longer began with the place it names. The place stays whole now;
// only the problem is capped (a quoted token is an excerpt of 80 bytes before that).
TEST(FuzzRegression, ALongPlaceIsKeptWholeAndOnlyTheProblemIsCapped) {
  const std::string place(2000, 'p'), problem(5000, 'q');
  const std::string message = InputError(place, problem, "fix").what();
  EXPECT_EQ(message.substr(0, place.size() + 2), place + ": ");
  EXPECT_EQ(message.size(), place.size() + 2 + 1000 + 5) << "1000 bytes of problem, then \"; fix\"";
  EXPECT_EQ(excerpt(problem), std::string(77, 'q') + "...");
}

}  // namespace
}  // namespace rupture
