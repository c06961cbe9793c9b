// Fuzzes the LAMMPS data file reader.
#include "fuzz_support.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"

// Seed: a small bonded block as the writer of this format writes it.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  using namespace rupture;
  fuzz::write_seeds_if_asked([] {
    const Sample block = make_cubic_block(3, 4, 2, 0.5);
    return fuzz::Seeds{
        {"block.data", format_lammps_data(block)},
        {"block-bpm.data", format_lammps_data(block, LammpsAtomStyle::bpm_sphere)},
    };
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  fuzz::expect_value_or_clean_rejection(
      "fuzz.data", [&] { (void)parse_lammps_data(fuzz::as_text(data, size), "fuzz.data"); });
  return 0;
}
