// dem/neighbours: the contact neighbour list (a Verlet list) and the cell grid that builds it. Per
// particle a slice of candidate partners (unbonded particles within r_a + r_b + skin at the last
// build), sorted by storage index, with room for the pairs its intact bonds may release before the
// next build; the positions of that build, which decide when the list must be rebuilt; the skin,
// which adapts to how often that happens.
// Because every slice is sorted and the force pass adds only touching pairs, forces do not depend on
// the skin or on when the list was rebuilt: the skin is a pure speed setting.
// Owns: the list, its build, its growth by released pairs and the skin. Not: contact forces
// (dem/forces), nor the packing generator's incremental grid (sample/cell_grid: one particle added
// at a time, where this grid is rebuilt in bulk by a counting sort).
#pragma once

#include <cstdint>
#include <vector>

#include "dem/bonds.hpp"
#include "dem/particles.hpp"

namespace rupture::dem {

struct NeighbourList {
  // Builds the list from scratch at the current skin. A non-finite position leaves the list as it
  // was: the caller's stability check reports the state.
  void build(const HotParticles& particles, const BondStore& bonds, double max_radius, bool parallel);
  // Whether the list may miss a touching pair: two particles each moved since the build, by at most
  // the largest and second-largest displacement (mm), may have closed the skin between them.
  bool stale(double largest_move, double second_move) const { return largest_move + second_move > skin; }
  // After a build at `step`: widens the skin (up to `widest`, mm) when the list lasted few steps since
  // the last build and narrows it back towards `narrowest` when it lasts long. Rebuilds then stay a
  // small share of the work whatever the particles' speeds (fragments after failure fly fast).
  void adapt_skin(std::uint64_t step, double narrowest, double widest);
  // A bond between a and b broke: each becomes a contact candidate of the other, in sorted place.
  void add_pair(std::uint32_t a, std::uint32_t b);
  std::size_t bytes() const;

  // A particle's position and radius (mm), as the build reads them in bucket order.
  struct Binned {
    double x, y, z, radius;
  };

  std::vector<std::uint32_t> start, count, list;  // slices [start[a], start[a] + count[a]) of list
  std::vector<double> xb, yb, zb;                 // mm: positions at the last build
  double skin = 0.0;                              // mm
  std::uint64_t built_at_step = 0;
  std::size_t builds = 0;

 private:
  void insert_sorted(std::uint32_t a, std::uint32_t b);

  std::vector<std::uint32_t> cell_start_, cell_particles_;
  std::vector<Binned> binned_;  // cell_particles_' positions and radii, in the same (bucket) order
  // Per thread, the candidates of its particles found in one pass; per particle, where they lie.
  std::vector<std::vector<std::uint32_t>> found_;
  std::vector<std::uint32_t> found_thread_, found_at_;
};

}  // namespace rupture::dem
