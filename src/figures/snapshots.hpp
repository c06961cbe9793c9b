// figures/snapshots: pictures of the intact bonds coloured by their extension at chosen strains
// (paper figures 8, 12, 14), read from the ASCII VTK snapshots that `rupture run` writes.
// Owns: choosing snapshots and turning bonds into segments. Not: the snapshot format (io/vtk, loading/run).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "figures/gnuplot.hpp"
#include "io/csv.hpp"

namespace rupture::figures {

// The intact bonds of one snapshot, projected on the (x, y) plane: x across the width, y along the
// loading direction [mm]; `relative_extension` is (r - r0) / r0 [1] per bond.
struct SnapshotBonds {
  std::vector<double> x_a, y_a, x_b, y_b, relative_extension;
};

// Reads the points, the bond connectivity and `relative_extension` of a snapshot .vtp. InputError if
// malformed.
SnapshotBonds read_snapshot_bonds(const std::filesystem::path& vtp);

// A recorded snapshot: its file, step and strain [%] (interpolated in step from curves.csv).
struct SnapshotFile {
  std::filesystem::path file;
  std::uint64_t step = 0;
  double strain = 0.0;
};

// The snapshots/step_N.vtp files that the run folder's snapshots.pvd lists, in step order; empty if
// there is no snapshots.pvd. Files in snapshots/ that it does not list (left by something else) are
// never drawn as this run's.
std::vector<SnapshotFile> list_snapshots(const std::filesystem::path& run_folder, const io::CsvTable& curves);

// For each wanted strain the nearest snapshot, without repeats, in strain order.
std::vector<SnapshotFile> nearest_snapshots(const std::vector<SnapshotFile>& all,
                                            const std::vector<double>& strains);

// Stacked panels, one per snapshot, bonds coloured by relative extension [%] on one shared scale; with
// `breaks` (the run's breaks.csv) the bonds broken up to each snapshot as dots where they broke.
Figure snapshots_figure(const std::vector<SnapshotFile>& chosen, const std::string& strain_unit,
                        std::vector<std::string> provenance, const io::CsvTable* breaks = nullptr);

}  // namespace rupture::figures
