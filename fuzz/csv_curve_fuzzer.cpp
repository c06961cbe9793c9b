// Fuzzes the CSV reader and the choice of the loading-curve columns that `rupture analyze` makes
// from it (default column names).
#include "analysis/analysis.hpp"
#include "fuzz_support.hpp"
#include "io/csv.hpp"

// Seeds: a short loading curve with units in the header, and an FBM-style one (force_top).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rupture::fuzz::write_seeds_if_asked([] {
    return rupture::fuzz::Seeds{
        {"curve.csv",
         "# strain in %\nstrain [%],force [N],elastic_energy "
         "[mJ]\n0,0,0\n0.5,1.2,0.3\n1,2.0,1.1\n1.5,1.1,0.9\n"},
        {"dem.csv",
         "step,strain,force_top,force_bottom,elastic_energy\n0,0,0,0,0\n10,1e-3,2.5,-2.5,1e-6\n"
         "20,2e-3,\"3.5\",-3.5,2e-6\n"}};
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  fuzz::expect_value_or_clean_rejection("fuzz.csv", [&] {
    const io::CsvTable table = io::parse_csv(fuzz::as_text(data, size), "fuzz.csv");
    (void)analysis::select_curve(table);
  });
  return 0;
}
