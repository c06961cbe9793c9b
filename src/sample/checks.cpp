#include "sample/checks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "sample/cell_grid.hpp"

namespace rupture {

namespace {

void check_particles(const Sample& s, const std::string& source) {
  const std::string fix = "fix or re-export the sample (coordinates and radii in mm)";
  if (s.radius.size() != s.size() || s.group.size() != s.size() || s.id.size() != s.size())
    throw InputError(source, "the particle arrays differ in length", fix);
  for (std::size_t a = 0; a < s.size(); ++a) {
    const Vec3& p = s.position[a];
    for (double v : {p.x, p.y, p.z})
      if (!(std::abs(v) <= max_plausible_coordinate))
        throw InputError(source,
                         fmt::format("particle id {} is at ({:g}, {:g}, {:g}) mm, not within {:g} mm of the "
                                     "origin",
                                     s.id[a], p.x, p.y, p.z, max_plausible_coordinate),
                         fix);
    if (!(s.radius[a] >= min_plausible_radius && s.radius[a] <= max_plausible_radius))
      throw InputError(source,
                       fmt::format("particle id {} has radius {:g} mm, outside [{:g}, {:g}] mm", s.id[a],
                                   s.radius[a], min_plausible_radius, max_plausible_radius),
                       fix);
  }
}

// Pairs closer than max_overlap_fraction of their summed radii, found on a cell grid.
void check_spacing(const Sample& s, const std::string& source) {
  Box bounds{s.position.front(), s.position.front()};
  double largest = 0.0;
  for (std::size_t a = 0; a < s.size(); ++a) {
    const Vec3& p = s.position[a];
    bounds.lower = {std::min(bounds.lower.x, p.x), std::min(bounds.lower.y, p.y),
                    std::min(bounds.lower.z, p.z)};
    bounds.upper = {std::max(bounds.upper.x, p.x), std::max(bounds.upper.y, p.y),
                    std::max(bounds.upper.z, p.z)};
    largest = std::max(largest, s.radius[a]);
  }
  const Vec3 extent = bounds.size();
  // Cells wide enough to hold every close pair in neighbouring cells, and at most ~200 per axis.
  const double cell = std::max({2.0 * largest, extent.x / 200.0, extent.y / 200.0, extent.z / 200.0});
  sample_detail::CellGrid grid(bounds, cell);
  for (std::uint32_t a = 0; a < s.size(); ++a) {
    grid.for_each_near(s.position[a], [&](std::uint32_t b) {
      const double limit = max_overlap_fraction * (s.radius[a] + s.radius[b]);
      if (norm(s.position[a] - s.position[b]) < limit)
        throw InputError(
            source,
            fmt::format("particles id {} and id {} are {:.3g} mm apart, with radii {:g} and {:g} mm "
                        "(a duplicate, or an export that lost precision)",
                        s.id[b], s.id[a], norm(s.position[a] - s.position[b]), s.radius[b], s.radius[a]),
            "remove the duplicate, or re-export the sample with full precision");
    });
    grid.insert(a, s.position[a]);
  }
}

void check_bonds(const Sample& s, const std::string& source) {
  for (const Bond& b : s.bonds) {
    const bool exist = b.i < s.size() && b.j < s.size();
    const std::string which = exist ? fmt::format("bond id {} - id {}", s.id[b.i], s.id[b.j])
                                    : fmt::format("bond {} - {} (storage indices)", b.i, b.j);
    if (!exist || b.i == b.j)
      throw InputError(
          source, which + (exist ? " joins a particle to itself" : " names a particle that does not exist"),
          "fix the bond list, or let rupture find the bonds (rupture sample generate)");
    if (!(b.rest_length > 0.0 && std::isfinite(b.rest_length)))
      throw InputError(source, fmt::format("{} has rest length {:g} mm", which, b.rest_length),
                       "rest lengths are the initial centre distances (> 0 mm)");
  }
}

void check_layers(const Sample& s, const std::string& source) {
  double bottom_top = -INFINITY, top_bottom = INFINITY;
  std::size_t bottoms = 0, tops = 0;
  for (std::size_t a = 0; a < s.size(); ++a) {
    if (s.group[a] == ParticleGroup::bottom) bottom_top = std::max(bottom_top, s.position[a].y), ++bottoms;
    if (s.group[a] == ParticleGroup::top) top_bottom = std::min(top_bottom, s.position[a].y), ++tops;
  }
  if (bottoms == 0 || tops == 0)
    throw InputError(source,
                     fmt::format("needs particles glued to both plates ({} bottom, {} top)", bottoms, tops),
                     "mark the glued layers (groups 1 = bottom, 2 = top)");
  if (!(top_bottom > bottom_top))
    throw InputError(
        source,
        fmt::format("the top glued layer reaches down to y = {:g} mm, not above the bottom layer's "
                    "highest y = {:g} mm",
                    top_bottom, bottom_top),
        "loading pulls along +y: glue the top plate to the highest particles");
}

}  // namespace

void check_sample(const Sample& sample, const std::string& source) {
  if (sample.size() == 0) throw InputError(source, "the sample has no particles");
  if (!(sample.density >= min_plausible_density && sample.density <= max_plausible_density))
    throw InputError(source,
                     fmt::format("density {:g} g/mm^3 is outside the plausible [{:g}, {:g}] g/mm^3{}",
                                 sample.density, min_plausible_density, max_plausible_density,
                                 sample.density > 0 && sample.density < min_plausible_density
                                     ? " (a value in t/mm^3? multiply by 1e6)"
                                     : ""),
                     "give the density in g/mm^3 (water is 1e-3), or override it with sample.density");
  check_particles(sample, source);
  check_bonds(sample, source);
  check_spacing(sample, source);
  check_layers(sample, source);
}

}  // namespace rupture
