#include "loading/snapshot.hpp"

#include <cstdint>
#include <vector>

#include "io/vtk.hpp"

namespace rupture::loading {

namespace {

// Three components per particle, as VTK's vector arrays hold them.
void put(std::vector<double>& out, std::size_t a, const Vec3& v) {
  out[3 * a] = v.x;
  out[3 * a + 1] = v.y;
  out[3 * a + 2] = v.z;
}

}  // namespace

void write_snapshot(const dem::System& system, const Sample& sample, const std::filesystem::path& path,
                    const std::string& provenance) {
  io::VtkPolyData data;
  data.comments = {provenance, "group: 0 free, 1 glued to the bottom plate, 2 glued to the top plate"};
  const std::size_t n = sample.size();
  std::vector<double> radius(n), displacement(3 * n), velocity(3 * n), force(3 * n);
  std::vector<std::int64_t> ids(n), groups(n);
  data.points.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    data.points[a] = system.position(a);
    put(displacement, a, data.points[a] - sample.position[a]);
    put(velocity, a, system.velocity(a));
    put(force, a, system.force(a));
    radius[a] = sample.radius[a];
    ids[a] = sample.id[a];
    groups[a] = static_cast<std::int64_t>(sample.group[a]);
  }
  // Intact bonds with their extension r - r0 (mm) and relative extension (r - r0) / r0.
  std::vector<double> extension, relative;
  for (std::size_t b = 0; b < sample.bonds.size(); ++b) {
    if (!system.bond_intact(b)) continue;
    data.lines.push_back({sample.bonds[b].i, sample.bonds[b].j});
    extension.push_back(system.bond_extension(b));
    relative.push_back(extension.back() / sample.bonds[b].rest_length);
  }
  data.point_data = {{"id", 1, ids},
                     {"radius_mm", 1, radius},
                     {"group", 1, groups},
                     {"displacement_mm", 3, displacement},
                     {"velocity_mm_per_s", 3, velocity},
                     {"force_N", 3, force}};
  data.line_data = {{"extension_mm", 1, extension}, {"relative_extension", 1, relative}};
  io::write_vtp(path, data);
}

}  // namespace rupture::loading
