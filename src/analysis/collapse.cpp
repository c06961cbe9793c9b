// analysis/collapse: see collapse.hpp.
#include "analysis/collapse.hpp"

#include <algorithm>

namespace rupture::analysis {

std::optional<std::size_t> sharp_collapse_onset(std::span<const double> force, std::span<const double> energy,
                                                std::size_t force_top, double collapse_level,
                                                std::size_t width) {
  std::size_t fallen = force_top + 1;
  while (fallen < force.size() && force[fallen] >= collapse_level) ++fallen;
  if (fallen >= force.size() || width == 0) return std::nullopt;
  const std::size_t start = fallen > width ? fallen - width : 0;
  if (force[start] < 2.0 * collapse_level) return std::nullopt;
  std::size_t onset = fallen - 1;
  while (force[onset] < 2.0 * collapse_level) --onset;
  // A step counts as falling when it drops by more than the curve's noise: a noisy flat top would
  // otherwise carry the walk back by chance, a row at a time.
  const auto walk_back = [&](std::span<const double> y) {
    const double noise = noise_from_differences(y);
    while (onset > force_top + 1 && y[onset - 1] - y[onset] > noise) --onset;
  };
  walk_back(force);
  walk_back(energy);
  return onset;
}

std::size_t collapse_width(std::size_t force_top) { return std::max<std::size_t>(force_top / 20, 5); }

void filter_either_side(FilterSettings filter, std::span<const double> raw, std::size_t onset,
                        std::vector<double>& filtered) {
  const std::size_t need = minimum_samples(filter);
  if (onset + 1 < need) return;
  const auto loading = filter_continuing_end(filter, raw.first(onset + 1));
  std::copy(loading.begin(), loading.end(), filtered.begin());
  const auto collapse = raw.subspan(onset + 1);
  const auto smooth = collapse.size() < need ? std::vector<double>(collapse.begin(), collapse.end())
                                             : apply_filter(filter, collapse);
  std::copy(smooth.begin(), smooth.end(), filtered.begin() + static_cast<std::ptrdiff_t>(onset + 1));
  // The collapse's filtered start follows its padding, pinned to its first noisy sample: above the
  // loading's end it would stand as a maximum of the curve where the sample is coming apart.
  const std::size_t held = held_collapse_samples(filter, onset, raw.size());
  for (std::size_t i = onset + 1; i <= onset + held; ++i)
    filtered[i] = std::min(filtered[i], filtered[onset]);
}

std::size_t held_collapse_samples(const FilterSettings& filter, std::size_t onset, std::size_t size) {
  if (onset + 1 < minimum_samples(filter) || onset + 1 >= size) return 0;
  return std::min(edge_samples(filter), size - onset - 1);
}

}  // namespace rupture::analysis
