// Fuzzes rupture's own sample reader (`rupture-sample 1`). Whatever it accepts must survive a write
// and a re-read unchanged: format_own(parse_own(format_own(s))) == format_own(s).
#include "fuzz_support.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"

// Seed: a small bonded block as the writer of this format writes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  using namespace rupture;
  fuzz::write_seeds_if_asked([] {
    const Sample block = make_cubic_block(3, 4, 2, 0.5);
    return fuzz::Seeds{
        {"block.sample", format_own(block)},
    };
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  fuzz::expect_value_or_clean_rejection("fuzz.sample", [&] {
    const std::string once = format_own(parse_own(fuzz::as_text(data, size), "fuzz.sample"));
    const std::string twice = format_own(parse_own(once, "fuzz.sample"));
    if (once != twice) fuzz::defect("written sample does not read back the same", once);
  });
  return 0;
}
