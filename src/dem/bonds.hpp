// dem/bonds: the bond store. Bonds in sample order (storage indices of their ends, rest length,
// intact flag) and, per particle, its links (CSR): each bond seen from both ends with the rest
// length the force pass reads, so that pass streams through them (stiffness and break limit follow
// from the rest length and the Params: dem/physics). A particle's intact links
// occupy [link_start[a], link_start[a] + link_count[a]) in a fixed order (its summation order); a
// break moves the link past that range, so broken bonds cost the force pass nothing.
// Owns: the bond arrays and their invariants. Not: deciding that a bond breaks (dem/breaks).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sample/sample.hpp"

namespace rupture::dem {

struct BondStore {
  // Validates the bonds (InputError naming the sample); links ordered by the other particle.
  BondStore(const Sample& sample, std::span<const std::uint32_t> storage_of_sample);

  std::size_t size() const { return i.size(); }
  std::size_t bytes() const;
  // Whether a and b (storage indices) share an intact bond.
  bool linked(std::uint32_t a, std::uint32_t b) const;
  // Marks `bond` broken and moves its link out of both ends' intact ranges.
  void unlink(std::uint32_t bond);
  // Restores broken flags and link order (a checkpoint's), rebuilding the link constants.
  void restore(std::span<const std::uint8_t> intact_flags, std::span<const std::uint32_t> counts,
               std::span<const std::uint32_t> bond_of_link);

  // Per bond, sample order.
  std::vector<std::uint32_t> i, j;  // storage indices, ends
  std::vector<double> r0;           // mm (stiffness and break limit: dem::bond_stiffness, break_limit)
  std::vector<std::uint8_t> intact;
  std::size_t intact_count = 0;
  // Per particle link slices and per link slot.
  std::vector<std::uint32_t> link_start, link_count;
  std::vector<std::uint32_t> link_other, link_bond;
  // The rest length (mm) per link; stiffness and break limit follow from it and the Params
  // (bond_stiffness, break_limit), so they are not stored twice per bond.
  std::vector<double> link_r0;

 private:
  void set_link(std::uint32_t slot, std::uint32_t a, std::uint32_t bond);
};

}  // namespace rupture::dem
