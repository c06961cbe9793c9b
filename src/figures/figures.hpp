// figures: the pictures of the paper drawn from rupture's own outputs — loading curves of a DEM run
// (with x_p, x_c, x_m and the delta_x posterior from analysis.json, bond-breaking rate from breaks.csv,
// bond snapshots), the ELS curves of an FBM CSV, and a scan's summary figures 15-17.
// Owns: what each figure shows. Not: script text (gnuplot.hpp), the report page (report/).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "figures/gnuplot.hpp"

namespace rupture::figures {

struct PlotOptions {
  Formats formats;
  // Strains [%] at which to draw the bond snapshots (the nearest recorded snapshot to each);
  // empty: the snapshots nearest x_p and x_c from analysis.json and the last one.
  std::vector<double> snapshot_strains;
};

// One figure drawn: its name (file stem), a caption and the files written (NAME.dat, NAME.gp, pictures).
struct Drawn {
  std::string name;
  std::string caption;
  std::vector<std::filesystem::path> files;
  std::filesystem::path png() const;  // the PNG among `files`; empty if none was drawn
};

// `input` is a run folder (curves.csv, optional analysis.json, breaks.csv and snapshots.pvd), a run's
// curves.csv, an FBM curve CSV (strain, force, elastic_energy, energy_rate columns) or a scan folder
// (results.csv). Figures go to `out` (created if needed). Bad input throws InputError; gnuplot trouble
// RunError.
std::vector<Drawn> plot(const std::filesystem::path& input, const std::filesystem::path& out,
                        const PlotOptions& options = {});

// The folder `plot` uses when no --out is given: `figures` inside the run or scan folder or beside the CSV.
std::filesystem::path default_out(const std::filesystem::path& input);

// A scan folder holds results.csv (and scan.json) rather than curves.csv.
bool is_scan_folder(const std::filesystem::path& input);

}  // namespace rupture::figures
