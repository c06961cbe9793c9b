// analysis/collapse: a record that ends in a collapse (a brittle sample coming apart within a
// twentieth of its rise): where the drop begins, how wide a drop counts, and the filtering of the
// loading and the collapse each on its own. Not: choosing the filter or finding the maxima
// (analysis.cpp). docs/analysis.md, "A collapse the filter cannot follow" and "The loading's cut end".
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "analysis/filters.hpp"

namespace rupture::analysis {

// A collapse: after the force peak the raw force falls from above twice `collapse_level` to below it
// within `width` samples (collapse_width). A low-pass spreads such a drop backwards with an overshoot: ℰ,
// the derivative, then peaks on the filter's response just before the collapse, above any slope the rows
// hold, and F's peak is lifted there too (known-answer Weibull curves cut at 1.05-1.35 x_c: x_p found at
// the cut where it is 0.49; docs/analysis.md, "A collapse the filter cannot follow"). The onset is where
// the drop begins: from the last sample above twice the level, back while the raw force still falls and
// then while the raw E_e still falls (each step by more than the curve's noise, noise_from_differences),
// never past the force peak. F rings on a run and can stop the first walk a few rows into the drop; E_e,
// which does not, then takes it to where the sample began to come apart (docs/analysis.md, "Known answers
// that ring as a run does"). Nothing where the collapse is gradual or absent.
std::optional<std::size_t> sharp_collapse_onset(std::span<const double> force, std::span<const double> energy,
                                                std::size_t force_top, double collapse_level,
                                                std::size_t width);

// The widest drop (samples) taken for a collapse: a twentieth of the rise to the force peak (a slower
// one is the curve's own decline: a finite bundle recorded far past its peak falls gradually), and at
// least 5 samples: a run's means every 400 steps reach the peak in ~70 rows and take 3-4 to fall, and
// no filter follows a drop that short (docs/analysis.md, "A collapse over a few coarse rows"). It no
// longer depends on the filter: a weak filter (a run's rows every 100 steps, whose ringing reads as
// white noise) made a drop over ten rows one "the filter follows", and then nothing kept ℰ's search
// off its corner (docs/analysis.md, "Known answers that ring as a run does").
std::size_t collapse_width(std::size_t force_top);

// The loading and the collapse filtered each on its own, split at the onset, so that the drop's
// response does not reach back into the loading. The loading's cut end is continued by its trend
// (filter_continuing_end), the collapse's ends padded as usual; the collapse's first
// held_collapse_samples() are then held at most at the loading's filtered end. A collapse too short
// for the filter stays raw (its start held too); a loading too short leaves the whole record's
// filtering.
void filter_either_side(FilterSettings filter, std::span<const double> raw, std::size_t onset,
                        std::vector<double>& filtered);

// How many samples after the onset filter_either_side holds at the loading's filtered end: one filter
// edge, fewer where the record ends sooner, none where the loading was too short to filter apart.
std::size_t held_collapse_samples(const FilterSettings& filter, std::size_t onset, std::size_t size);

}  // namespace rupture::analysis
