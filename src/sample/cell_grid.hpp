// sample/cell_grid: a uniform grid of cells over a box, each cell a linked list of particle indices.
// Used by the packing generator (particles added one at a time), bond detection and the sample
// statistics. Cells are at least `min_cell_size` wide, so every pair closer than that lies in the same
// or an adjacent cell. Iteration order is fixed (cells in x-fastest order, newest particle first in
// each cell), so everything built on it is deterministic.
// Not dem/neighbours' grid, on purpose: that one is rebuilt in bulk from moving positions (a
// counting sort, hundreds of times per run); this one grows by one particle at a time inside a
// fixed box, which a counting sort cannot do without re-sorting on every insertion.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sample/sample.hpp"

namespace rupture::sample_detail {

class CellGrid {
 public:
  CellGrid(const Box& box, double min_cell_size) : lower_(box.lower) {
    const Vec3 size = box.size();
    const std::array<double, 3> extent{size.x, size.y, size.z};
    for (int a = 0; a < 3; ++a) {
      // At least one cell; a cell never narrower than min_cell_size.
      dims_[a] = std::max(1, static_cast<int>(std::floor(extent[a] / min_cell_size)));
      inverse_width_[a] = extent[a] > 0.0 ? dims_[a] / extent[a] : 0.0;
    }
    head_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2], -1);
  }

  void insert(std::uint32_t index, const Vec3& p) {
    if (next_.size() <= index) next_.resize(index + 1, -1);
    const auto cell = flat(coords(p));
    next_[index] = head_[cell];
    head_[cell] = static_cast<std::int32_t>(index);
  }

  // Calls fn(index) for every particle in the 3x3x3 block of cells around p.
  template <class Fn>
  void for_each_near(const Vec3& p, Fn&& fn) const {
    const auto c = coords(p);
    for (int z = std::max(0, c[2] - 1); z <= std::min(dims_[2] - 1, c[2] + 1); ++z)
      for (int y = std::max(0, c[1] - 1); y <= std::min(dims_[1] - 1, c[1] + 1); ++y)
        for (int x = std::max(0, c[0] - 1); x <= std::min(dims_[0] - 1, c[0] + 1); ++x)
          for (auto k = head_[flat({x, y, z})]; k >= 0; k = next_[static_cast<std::size_t>(k)])
            fn(static_cast<std::uint32_t>(k));
  }

  // Integer cell coordinates of p, clamped into the grid (particles may sit slightly outside the box).
  std::array<int, 3> coords(const Vec3& p) const {
    const std::array<double, 3> rel{p.x - lower_.x, p.y - lower_.y, p.z - lower_.z};
    std::array<int, 3> c{};
    for (int a = 0; a < 3; ++a)
      // Clamp before converting: a far-away (imported) particle must not overflow the int.
      c[a] = static_cast<int>(std::clamp(std::floor(rel[a] * inverse_width_[a]), 0.0, dims_[a] - 1.0));
    return c;
  }

 private:
  std::size_t flat(const std::array<int, 3>& c) const {
    return (static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  }

  Vec3 lower_;
  std::array<int, 3> dims_{};
  std::array<double, 3> inverse_width_{};
  std::vector<std::int32_t> head_, next_;
};

}  // namespace rupture::sample_detail
