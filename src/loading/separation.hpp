// loading/separation: has the sample come apart? Two rules. Connectivity: a union-find over intact
// bonds and touching contacts asks whether any particle glued to the top plate is still connected to
// one glued to the bottom plate. Load-free: after bonds have broken, the mean top-plate force has
// stayed below a fraction of its peak over a strain window; it ends runs where a few slack bond
// chains keep the halves connected while they carry no load. Not: when to ask (the run loop asks
// every stop.separation_check_interval steps).
#pragma once

#include <algorithm>
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

// The load-free rule. Fed the top-plate force every step; asked at every check, it compares the
// mean force over the interval since the last check with the largest such mean so far (interval
// means, so that one ringing step neither triggers nor resets it).
class LoadFreeWatch {
 public:
  // Everything that carries over between checks (a checkpoint stores it to resume exactly).
  struct State {
    double sum = 0.0;  // N, top-plate force summed over the current interval
    std::uint64_t count = 0;
    double last_strain = 0.0;  // %, end of the previous interval
    double peak = 0.0;         // N, largest interval mean so far
    bool load_free = false;    // in a load-free stretch
    double free_since = 0.0;   // %, where it began
  };

  LoadFreeWatch(double fraction, double window_strain) : fraction_(fraction), window_(window_strain) {}
  LoadFreeWatch(double fraction, double window_strain, const State& state)
      : fraction_(fraction), window_(window_strain), s_(state) {}
  const State& state() const { return s_; }
  void add(double force) {
    s_.sum += force;
    ++s_.count;
  }
  // `strain` (%) at the end of the interval; `broken` tells whether any bond has broken yet.
  bool check(double strain, bool broken) {
    const double mean = s_.count > 0 ? s_.sum / double(s_.count) : 0.0;
    s_.sum = 0.0;
    s_.count = 0;
    const double interval_start = s_.last_strain;
    s_.last_strain = strain;
    s_.peak = std::max(s_.peak, mean);
    if (fraction_ <= 0.0 || !broken || s_.peak <= 0.0 || mean >= fraction_ * s_.peak) {
      s_.load_free = false;
      return false;
    }
    if (!s_.load_free) s_.free_since = interval_start;
    s_.load_free = true;
    return strain - s_.free_since >= window_;
  }

 private:
  double fraction_, window_;
  State s_;
};

}  // namespace rupture::loading
