// sample/lattice: regular bonded lattices with known answers, for analytic tests of the DEM engine.
// Owns: a straight bonded chain along y and a simple-cubic block with axial bonds. Not: random
// packings (sample/generator) or files (sample/formats).
#pragma once

#include <cstdint>

#include "sample/sample.hpp"

namespace rupture {

// n touching spheres of radius `radius` (mm) stacked along y, centres 2*radius apart, bonded to
// their neighbours; the first is glued to the bottom plate, the last to the top plate (n >= 2).
inline Sample make_chain(std::uint32_t n, double radius, double density = default_density) {
  Sample sample;
  sample.density = density;
  const double spacing = 2.0 * radius;
  for (std::uint32_t k = 0; k < n; ++k) {
    sample.id.push_back(k);
    sample.position.push_back({0.0, k * spacing, 0.0});
    sample.radius.push_back(radius);
    sample.group.push_back(k == 0 ? ParticleGroup::bottom
                                  : (k + 1 == n ? ParticleGroup::top : ParticleGroup::free));
    if (k > 0) sample.bonds.push_back({k - 1, k, spacing});
  }
  sample.box = {{-radius, -radius, -radius}, {radius, (n - 1) * spacing + radius, radius}};
  return sample;
}

// nx * ny * nz touching spheres on a simple-cubic lattice (spacing 2*radius), each bonded to its
// axis neighbours only, so that under tension along y the block is nx*nz parallel chains of ny-1
// bonds: its stiffness is known exactly. The layer y = 0 is glued to the bottom plate, the layer
// y = max to the top plate. Index = (iy * nz + iz) * nx + ix.
inline Sample make_cubic_block(std::uint32_t nx, std::uint32_t ny, std::uint32_t nz, double radius,
                               double density = default_density) {
  Sample sample;
  sample.density = density;
  const double spacing = 2.0 * radius;
  const auto index = [&](std::uint32_t ix, std::uint32_t iy, std::uint32_t iz) {
    return (iy * nz + iz) * nx + ix;
  };
  for (std::uint32_t iy = 0; iy < ny; ++iy)
    for (std::uint32_t iz = 0; iz < nz; ++iz)
      for (std::uint32_t ix = 0; ix < nx; ++ix) {
        sample.id.push_back(index(ix, iy, iz));
        sample.position.push_back({ix * spacing, iy * spacing, iz * spacing});
        sample.radius.push_back(radius);
        sample.group.push_back(iy == 0 ? ParticleGroup::bottom
                                       : (iy + 1 == ny ? ParticleGroup::top : ParticleGroup::free));
      }
  // Bonds sorted by (i, j): for each particle, its +x, +z, +y neighbours in increasing index.
  for (std::uint32_t iy = 0; iy < ny; ++iy)
    for (std::uint32_t iz = 0; iz < nz; ++iz)
      for (std::uint32_t ix = 0; ix < nx; ++ix) {
        const std::uint32_t i = index(ix, iy, iz);
        if (ix + 1 < nx) sample.bonds.push_back({i, index(ix + 1, iy, iz), spacing});
        if (iz + 1 < nz) sample.bonds.push_back({i, index(ix, iy, iz + 1), spacing});
        if (iy + 1 < ny) sample.bonds.push_back({i, index(ix, iy + 1, iz), spacing});
      }
  sample.box = {{-radius, -radius, -radius},
                {(nx - 1) * spacing + radius, (ny - 1) * spacing + radius, (nz - 1) * spacing + radius}};
  return sample;
}

}  // namespace rupture
