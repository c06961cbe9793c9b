#include "loading/snapshot.hpp"

#include <cstdint>
#include <vector>

#include "io/vtk.hpp"

namespace rupture::loading {

void write_snapshot(const dem::System& system, const Sample& sample, const std::filesystem::path& path,
                    const std::string& provenance) {
  io::VtkPolyData data;
  data.comments = {provenance};
  std::vector<double> radius(sample.size()), velocity(3 * sample.size());
  std::vector<std::int64_t> ids(sample.size()), groups(sample.size());
  data.points.resize(sample.size());
  for (std::size_t a = 0; a < sample.size(); ++a) {
    data.points[a] = system.position(a);
    const Vec3 v = system.velocity(a);
    velocity[3 * a] = v.x;
    velocity[3 * a + 1] = v.y;
    velocity[3 * a + 2] = v.z;
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
  data.point_data = {
      {"id", 1, ids}, {"radius_mm", 1, radius}, {"group", 1, groups}, {"velocity_mm_per_s", 3, velocity}};
  data.line_data = {{"extension_mm", 1, extension}, {"relative_extension", 1, relative}};
  io::write_vtp(path, data);
}

}  // namespace rupture::loading
