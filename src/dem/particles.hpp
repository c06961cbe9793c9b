// dem/particles: the particle store. Particles live in storage order (a Z-order curve of their
// initial positions, so neighbours in space are neighbours in memory) as structure-of-arrays, split
// by how often the step touches them: HotParticles is read or written by every step's sweeps,
// ColdParticles only by glued particles, damping, energies and outputs. Owns: the arrays, the
// storage <-> sample index maps and the glued list. Not: what moves them (dem/integrator).
#pragma once

#include <cstdint>
#include <vector>

#include "dem/params.hpp"
#include "sample/sample.hpp"

namespace rupture::dem {

struct HotParticles {
  std::vector<double> x, y, z;      // mm
  std::vector<double> vx, vy, vz;   // mm/s
  std::vector<double> fx, fy, fz;   // N: the last force pass's forces (the next first half-kick needs them)
  std::vector<double> inv_mass;     // 1/t
  std::vector<double> radius;       // mm
  std::vector<std::uint8_t> plate;  // Plate
};

struct ColdParticles {
  std::vector<double> mass;        // t
  std::vector<double> ax, ay, az;  // mm: anchor on the plate = initial position
  std::vector<double> damped;      // mJ removed from each particle by viscous damping
};

struct ParticleStore {
  // Validates radii and the glued layers (InputError naming the sample).
  ParticleStore(const Sample& sample, const Params& params);

  std::size_t size() const { return hot.x.size(); }
  std::size_t bytes() const;  // capacity of every array

  HotParticles hot;
  ColdParticles cold;
  std::vector<std::uint32_t> storage_of_sample, sample_of_storage;
  std::vector<std::uint32_t> glued;  // storage indices of glued particles, ascending
  double max_radius = 0.0;           // mm
  double plate_separation0 = 0.0;    // mm: initial distance between the glued layers' mean y
};

}  // namespace rupture::dem
