// analysis/collapse: a record that ends in a collapse too sharp for the filter (a brittle sample
// coming apart within a few rows): where the drop begins, how wide a drop counts, and the filtering
// of the loading and the collapse each on its own. Not: choosing the filter or finding the maxima
// (analysis.cpp). docs/analysis.md, "A collapse the filter cannot follow" and "The loading's cut end".
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "analysis/filters.hpp"

namespace rupture::analysis {

// A collapse sharper than the filter can follow: after the force peak the raw force falls from
// above twice `collapse_level` to below it within `width` samples (collapse_width). A low-pass spreads
// such a drop backwards with an overshoot: ℰ, the derivative, then peaks on the filter's response
// just before the collapse, above any slope the rows hold, and F's peak is lifted there too
// (known-answer Weibull curves cut at 1.05-1.35 x_c: x_p found at the cut where it is 0.49;
// docs/analysis.md, "A collapse the filter cannot follow"). The onset is where the drop begins: from
// the last sample above twice the level, back while the raw force still falls. Nothing where the
// collapse is gradual or absent.
std::optional<std::size_t> sharp_collapse_onset(std::span<const double> force, std::size_t force_top,
                                                double collapse_level, std::size_t width);

// The widest drop (samples) taken for a collapse: one period of the filter's cutoff (a slower one
// the filter follows) and a twentieth of the rise to the force peak (a slower one is the curve's own
// decline: a finite bundle recorded far past its peak falls gradually, and its strong filter's
// period can span that fall).
std::size_t collapse_width(std::size_t force_top, const FilterSettings& filter);

// The loading and the collapse filtered each on its own, split at the onset, so that the drop's
// response does not reach back into the loading. The loading's cut end is continued by its trend
// (filter_continuing_end), the collapse's ends padded as usual. A piece too short for the filter
// stays raw; a loading too short leaves the whole record's filtering.
void filter_either_side(FilterSettings filter, std::span<const double> raw, std::size_t onset,
                        std::vector<double>& filtered);

}  // namespace rupture::analysis
