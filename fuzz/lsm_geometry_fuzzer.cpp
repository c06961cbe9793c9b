// Fuzzes the ESyS-Particle / GenGeo LSMGeometry reader.
#include "fuzz_support.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"

// Seed: a small bonded block as the writer of this format writes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  using namespace rupture;
  fuzz::write_seeds_if_asked([] {
    const Sample block = make_cubic_block(3, 4, 2, 0.5);
    return fuzz::Seeds{
        {"block.geo", format_lsm_geometry(block)},
    };
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  fuzz::expect_value_or_clean_rejection(
      "fuzz.geo", [&] { (void)parse_lsm_geometry(fuzz::as_text(data, size), "fuzz.geo"); });
  return 0;
}
