// loading/separation: has the sample come apart? A union-find over intact bonds and touching
// contacts asks whether any particle glued to the top plate is still connected to one glued to the
// bottom plate. Not: when to ask (the run loop asks every stop.separation_check_interval steps).
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

#include "dem/system.hpp"

namespace rupture::loading {

// Disjoint sets with path halving and union by size; buffers are kept between checks.
class UnionFind {
 public:
  void reset(std::size_t n) {
    parent_.resize(n);
    size_.assign(n, 1);
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  std::uint32_t find(std::uint32_t a) {
    while (parent_[a] != a) {
      parent_[a] = parent_[parent_[a]];
      a = parent_[a];
    }
    return a;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<std::uint32_t> parent_, size_;
};

// True when no path of intact bonds and contacts joins the top glued layer to the bottom one.
inline bool separated(const dem::System& system, UnionFind& sets) {
  sets.reset(system.size());
  system.for_each_connection([&](std::uint32_t a, std::uint32_t b) { sets.unite(a, b); });
  std::vector<std::uint8_t> bottom_roots(system.size(), 0);
  for (std::uint32_t a = 0; a < system.size(); ++a)
    if (system.plate_of_storage(a) == dem::plate_bottom) bottom_roots[sets.find(a)] = 1;
  for (std::uint32_t a = 0; a < system.size(); ++a)
    if (system.plate_of_storage(a) == dem::plate_top && bottom_roots[sets.find(a)]) return false;
  return true;
}

}  // namespace rupture::loading
