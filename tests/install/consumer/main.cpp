// Prints the ELS maxima of the uniform bundle and the FBM band, through the installed headers and
// libraries: x_p = 1/3, x_c = 1/2, x_m = 2/3 and A_r's band 0.837-1.333.
#include <cstdio>

#include "analysis/analysis.hpp"
#include "fbm/distribution.hpp"
#include "fbm/els_theory.hpp"
#include "rupture/version.hpp"

int main() {
  const auto dist =
      rupture::fbm::parse_distribution_spec("uniform", [](const std::string&) { return std::string(); });
  const auto c = rupture::fbm::theory_characteristics(*dist);
  const auto& band = rupture::analysis::power_law_band();
  std::printf("rupture %s: x_p %.6f x_c %.6f x_m %.6f A_r band %.3f-%.3f\n", rupture::version_string, c.x_p,
              c.x_c, *c.x_m, band.energy_ratio_low, band.energy_ratio_high);
}
