#include "sample/presets.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.hpp"

namespace rupture {

std::vector<std::string> preset_names() { return {"tissue", "tissue-small"}; }

PackingParams preset_params(std::string_view name) {
  PackingParams params;  // the defaults are the tissue's material: radii, spread, bonds
  if (name == "tissue") return params;
  if (name == "tissue-small") {
    params.size = {20.0, 10.0, 5.0};
    return params;
  }
  throw InputError("--preset", fmt::format("unknown sample preset '{}'", name),
                   fmt::format("use one of: {}", fmt::join(preset_names(), ", ")));
}

Sample make_preset(std::string_view name, std::uint64_t seed, GenerationReport* report) {
  Sample sample = generate_sample(preset_params(name), seed, report);
  sample.provenance.insert(sample.provenance.begin() + 1, fmt::format("preset: {}", name));
  return sample;
}

}  // namespace rupture
