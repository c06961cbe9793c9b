// figures: the pictures of the paper drawn from rupture's own outputs — loading curves of a DEM run
// (with x_p, x_c, x_m and the delta_x posterior from analysis.json, bond-breaking rate from breaks.csv)
// and the ELS curves of an FBM CSV. Owns: what each figure shows. Not: script text (gnuplot.hpp).
#pragma once

#include <filesystem>
#include <vector>

#include "figures/gnuplot.hpp"

namespace rupture::figures {

// `input` is a run folder (curves.csv, optional analysis.json and breaks.csv), a run's curves.csv, or
// an FBM curve CSV (strain, force, elastic_energy, energy_rate columns). Figures go to `out`
// (created if needed). Returns every file written. Bad input throws InputError; gnuplot trouble RunError.
std::vector<std::filesystem::path> plot(const std::filesystem::path& input, const std::filesystem::path& out,
                                        Format format);

// The folder `plot` uses when no --out is given: `figures` inside the run folder or beside the CSV.
std::filesystem::path default_out(const std::filesystem::path& input);

}  // namespace rupture::figures
