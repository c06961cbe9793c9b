// loading/snapshot: what a run's ParaView snapshot holds (particles with their id, radius, group
// and velocity; intact bonds with their extension), taken from the engine's state. Not: the VTK
// file format (io/vtk) or when snapshots are due (loading/run).
#pragma once

#include <filesystem>
#include <string>

#include "dem/system.hpp"
#include "sample/sample.hpp"

namespace rupture::loading {

// Writes `system`'s state as a VTK PolyData file; particles in sample order; `provenance` becomes
// the file's comment.
void write_snapshot(const dem::System& system, const Sample& sample, const std::filesystem::path& path,
                    const std::string& provenance);

}  // namespace rupture::loading
