#include "sample/stats.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/units.hpp"
#include "io/quantity.hpp"
#include "sample/cell_grid.hpp"

namespace rupture {

SampleStats compute_stats(const Sample& sample, std::size_t histogram_bins) {
  SampleStats s;
  s.particles = sample.size();
  s.bonds = sample.bonds.size();
  const Vec3 size = sample.box.size();
  s.box_volume = size.x * size.y * size.z;
  if (s.particles == 0) return s;

  double volume = 0.0, radius_sum = 0.0;
  for (double r : sample.radius) {
    volume += units::sphere_volume(r);
    radius_sum += r;
  }
  s.solid_fraction = s.box_volume > 0.0 ? volume / s.box_volume : 0.0;
  s.mean_coordination = 2.0 * static_cast<double>(s.bonds) / static_cast<double>(s.particles);
  s.total_mass = units::mass_to_grams(units::density_from_g_per_mm3(sample.density) * volume);
  const auto [lo, hi] = std::minmax_element(sample.radius.begin(), sample.radius.end());
  s.r_min = *lo;
  s.r_max = *hi;
  s.r_mean = radius_sum / static_cast<double>(s.particles);

  histogram_bins = std::max<std::size_t>(histogram_bins, 1);
  s.radius_histogram.assign(histogram_bins, 0);
  for (std::size_t b = 0; b <= histogram_bins; ++b)
    s.radius_bin_edges.push_back(s.r_min + (s.r_max - s.r_min) * static_cast<double>(b) / histogram_bins);
  const double width = (s.r_max - s.r_min) / static_cast<double>(histogram_bins);
  for (double r : sample.radius) {
    const auto bin = width > 0.0 ? static_cast<std::size_t>((r - s.r_min) / width) : 0;
    ++s.radius_histogram[std::min(bin, histogram_bins - 1)];
  }

  std::vector<std::size_t> degree(s.particles, 0);
  for (const Bond& b : sample.bonds) ++degree[b.i], ++degree[b.j];
  s.isolated = static_cast<std::size_t>(std::count(degree.begin(), degree.end(), 0u));
  for (std::size_t i = 0; i < s.particles; ++i) {
    const ParticleGroup g = sample.group[i];
    s.bottom_layer += g == ParticleGroup::bottom;
    s.top_layer += g == ParticleGroup::top;
    if (g == ParticleGroup::bottom) s.bottom_layer_y += sample.position[i].y;
    if (g == ParticleGroup::top) s.top_layer_y += sample.position[i].y;
  }
  if (s.bottom_layer > 0) s.bottom_layer_y /= static_cast<double>(s.bottom_layer);
  if (s.top_layer > 0) s.top_layer_y /= static_cast<double>(s.top_layer);

  // Largest overlap: only pairs closer than 2 r_max can overlap, so the cell grid finds them all.
  sample_detail::CellGrid grid(sample.box, 2.0 * s.r_max);
  for (std::uint32_t i = 0; i < s.particles; ++i) grid.insert(i, sample.position[i]);
  for (std::uint32_t i = 0; i < s.particles; ++i)
    grid.for_each_near(sample.position[i], [&](std::uint32_t j) {
      if (j <= i) return;
      const double overlap =
          sample.radius[i] + sample.radius[j] - norm(sample.position[j] - sample.position[i]);
      s.max_overlap = std::max(s.max_overlap, overlap);
    });
  return s;
}

nlohmann::json to_json(const SampleStats& s) {
  return {{"particles", s.particles},
          {"bonds", s.bonds},
          {"solid_fraction", s.solid_fraction},
          {"mean_coordination", s.mean_coordination},  // bonds per particle
          {"isolated_particles", s.isolated},
          {"box_volume", io::quantity(s.box_volume, "mm^3")},
          {"radius",
           {{"min", io::quantity(s.r_min, "mm")},
            {"max", io::quantity(s.r_max, "mm")},
            {"mean", io::quantity(s.r_mean, "mm")}}},
          {"radius_histogram",
           {{"bin_edges", io::quantity(s.radius_bin_edges, "mm")}, {"counts", s.radius_histogram}}},
          {"glued_layers", {{"bottom", s.bottom_layer}, {"top", s.top_layer}}},
          // the mean y (the pull axis) of each glued layer
          {"glued_layer_heights",
           {{"bottom", io::quantity(s.bottom_layer_y, "mm")}, {"top", io::quantity(s.top_layer_y, "mm")}}},
          {"max_overlap", io::quantity(s.max_overlap, "mm")},
          {"total_mass", io::quantity(s.total_mass, "g")}};
}

}  // namespace rupture
