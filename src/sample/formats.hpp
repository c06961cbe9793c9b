// sample/formats: reading and writing samples: rupture's own text format, LAMMPS data files,
// ESyS-Particle/GenGeo LSMGeometry files, and VTK PolyData (.vtp, write only). Specs: docs/sample.md.
// Every reader rejects malformed or truncated input with InputError naming file:line and the fix.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "io/vtk.hpp"
#include "sample/sample.hpp"

namespace rupture {

enum class SampleFormat { own, lammps, lsm, vtp };

// "own", "lammps", "lsm", "vtp"; throws InputError listing them.
SampleFormat sample_format_from_name(std::string_view name);
std::string_view sample_format_name(SampleFormat format);
// By extension: .geo/.lsm -> lsm, .data/.lmp/.lammps -> lammps, .vtp -> vtp, anything else -> own.
SampleFormat sample_format_for_path(const std::filesystem::path& path);

// Chooses the reader by content (first line "rupture-sample" or "LSMGeometry") and otherwise by
// extension (LAMMPS data); .vtp cannot be read back into a sample.
Sample load_sample(const std::filesystem::path& path);
// Writes atomically in the format the extension names (or the one given).
void save_sample(const Sample& sample, const std::filesystem::path& path);
void save_sample(const Sample& sample, const std::filesystem::path& path, SampleFormat format);

// rupture's own format, version 1 (`rupture-sample 1`): exact (shortest round-trip decimals).
std::string format_own(const Sample& sample);
Sample parse_own(std::string_view text, const std::string& source);

// LAMMPS data files. Written: atom style `hybrid sphere bond` (or `bpm/sphere`); read: those two,
// `hybrid bond sphere` and `sphere` (no bonds). LAMMPS atom-ID = rupture id + 1; atom types
// 1 free, 2 bottom, 3 top. Rest lengths are not part of the format: read back as initial distances.
enum class LammpsAtomStyle { hybrid_sphere_bond, bpm_sphere };
std::string format_lammps_data(const Sample& sample,
                               LammpsAtomStyle style = LammpsAtomStyle::hybrid_sphere_bond);
Sample parse_lammps_data(std::string_view text, const std::string& source);

// ESyS-Particle geometry (`LSMGeometry 1.2`): particles `x y z r id tag` (tag 0 free, 1 bottom,
// 2 top when written), connections `id1 id2 tag`. Glued layers are derived by the glue rule on
// reading, since tags mean whatever the script that made the file chose.
std::string format_lsm_geometry(const Sample& sample);
Sample parse_lsm_geometry(std::string_view text, const std::string& source);

// Particles as points (arrays id, radius [mm], group 0 free / 1 bottom / 2 top) and bonds as lines
// (array rest_length [mm]), in id order.
io::VtkPolyData to_polydata(const Sample& sample);

}  // namespace rupture
