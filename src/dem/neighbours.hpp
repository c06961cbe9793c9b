// dem/neighbours: the contact neighbour list (a Verlet list) and the cell grid that builds it. Per
// particle a slice of candidate partners (unbonded particles within r_a + r_b + skin at the last
// build) with room for the pairs its intact bonds may release before the next build; the positions
// of that build, which decide when the list must be rebuilt.
// Owns: the list, its build and its growth by released pairs. Not: contact forces (dem/forces).
#pragma once

#include <cstdint>
#include <vector>

#include "dem/bonds.hpp"
#include "dem/particles.hpp"

namespace rupture::dem {

struct NeighbourList {
  // Builds the list from scratch. Every particle's list comes out in a fixed cell order, so the list
  // (and every force sum over it) is the same for any thread count. A non-finite position leaves the
  // list as it was: the caller's stability check reports the state.
  void build(const HotParticles& particles, const BondStore& bonds, double max_radius, double skin,
             bool parallel);
  // A bond between a and b broke: each becomes a contact candidate of the other.
  void add_pair(std::uint32_t a, std::uint32_t b);
  std::size_t bytes() const;

  std::vector<std::uint32_t> start, count, list;  // slices [start[a], start[a] + count[a]) of list
  std::vector<double> xb, yb, zb;                 // mm: positions at the last build
  std::size_t builds = 0;

 private:
  std::vector<std::uint32_t> cell_start_, cell_particles_, capacity_;
};

}  // namespace rupture::dem
