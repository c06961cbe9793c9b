// sample/presets: the named samples everyone starts from (CLI default, tests, benchmarks, study).
// Owns: the preset names and their generator parameters. Not: the generator itself.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sample/generator.hpp"
#include "sample/sample.hpp"

namespace rupture {

// "tissue": the paper's standard sample, 80 x 25 x 5 mm, radii 0.2-0.6 mm (~25,000 particles).
// "tissue-small": the same material in 20 x 10 x 5 mm (a few thousand particles, about a second),
// used by the tests and the default study.
std::vector<std::string> preset_names();
// Throws InputError listing the presets when `name` is unknown.
PackingParams preset_params(std::string_view name);
Sample make_preset(std::string_view name, std::uint64_t seed, GenerationReport* report = nullptr);

}  // namespace rupture
