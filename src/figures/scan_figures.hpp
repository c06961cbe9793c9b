// figures/scan_figures: the summary figures of a parameter scan, drawn from its results.csv —
// figure 15 (mechanism map over k_n, b_d), 16 (delta_x against x_c), 17 (A_r against x_c with the
// FBM lines). Owns: which rows each figure keeps and how groups are drawn. Not: the table (scan/results).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "figures/gnuplot.hpp"

namespace rupture::figures {

// The figures that have something to show; InputError when results.csv has no point to draw at all.
std::vector<Figure> scan_figures(const std::filesystem::path& scan_folder,
                                 const std::vector<std::string>& provenance);

}  // namespace rupture::figures
