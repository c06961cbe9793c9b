#include "dem/neighbours.hpp"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace rupture::dem {

// Cells no smaller than the largest cutoff (2 r_max + skin); particles binned by a counting sort in
// storage order; each particle's candidates visited in a fixed cell order. One pass over the
// particles on purpose (93 lines): after failure it runs hundreds of times per run, and the binning
// and the candidate sweep share its buffers.
void NeighbourList::build(const HotParticles& p, const BondStore& bonds, double max_radius, bool parallel) {
  const std::uint32_t n = static_cast<std::uint32_t>(p.x.size());
  const auto& x = p.x;
  const auto& y = p.y;
  const auto& z = p.z;
  for (auto* v : {&xb, &yb, &zb}) v->resize(n);  // sized even when the build gives up below
  double lo[3] = {x[0], y[0], z[0]}, hi[3] = {x[0], y[0], z[0]};
  for (std::uint32_t a = 0; a < n; ++a) {
    if (!std::isfinite(x[a] + y[a] + z[a])) return;
    lo[0] = std::min(lo[0], x[a]);
    hi[0] = std::max(hi[0], x[a]);
    lo[1] = std::min(lo[1], y[a]);
    hi[1] = std::max(hi[1], y[a]);
    lo[2] = std::min(lo[2], z[a]);
    hi[2] = std::max(hi[2], z[a]);
  }
  const double cell = 2.0 * max_radius + skin;
  std::int64_t dims[3];
  for (int d = 0; d < 3; ++d)
    dims[d] =
        std::max<std::int64_t>(1, std::min<std::int64_t>(std::int64_t((hi[d] - lo[d]) / cell) + 1, 1 << 10));
  const std::size_t cells = std::size_t(dims[0] * dims[1] * dims[2]);
  // Cells may be larger than `cell` when clamped; that only adds candidates.
  double size[3];
  for (int d = 0; d < 3; ++d) size[d] = std::max(cell, (hi[d] - lo[d]) / double(dims[d]) * (1.0 + 1e-12));
  const auto coord = [&](double v, int d) {
    return std::min<std::int64_t>(dims[d] - 1,
                                  std::max<std::int64_t>(0, std::int64_t((v - lo[d]) / size[d])));
  };
  cell_start_.assign(cells + 1, 0);
  cell_particles_.resize(n);
  count.resize(n);
  start.resize(n + 1);
  // Cell index per particle kept in `count` meanwhile.
  for (std::uint32_t a = 0; a < n; ++a) {
    const auto c = std::uint32_t((coord(z[a], 2) * dims[1] + coord(y[a], 1)) * dims[0] + coord(x[a], 0));
    count[a] = c;
    ++cell_start_[c + 1];
  }
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::uint32_t a = 0; a < n; ++a) cell_particles_[fill[count[a]]++] = a;
  }

  // Visits the candidates of particle a in a fixed order.
  const auto visit = [&](std::uint32_t a, auto&& take) {
    const std::int64_t cx = coord(x[a], 0), cy = coord(y[a], 1), cz = coord(z[a], 2);
    for (std::int64_t iz = std::max<std::int64_t>(0, cz - 1); iz <= std::min(dims[2] - 1, cz + 1); ++iz)
      for (std::int64_t iy = std::max<std::int64_t>(0, cy - 1); iy <= std::min(dims[1] - 1, cy + 1); ++iy)
        for (std::int64_t ix = std::max<std::int64_t>(0, cx - 1); ix <= std::min(dims[0] - 1, cx + 1); ++ix) {
          const std::size_t c = std::size_t((iz * dims[1] + iy) * dims[0] + ix);
          for (std::uint32_t q = cell_start_[c]; q < cell_start_[c + 1]; ++q) {
            const std::uint32_t b = cell_particles_[q];
            if (b == a) continue;
            const double dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
            const double cut = p.radius[a] + p.radius[b] + skin;
            if (dx * dx + dy * dy + dz * dz < cut * cut && !bonds.linked(a, b)) take(b);
          }
        }
  };
  // One pass: each thread gathers its particles' candidates, each particle's sorted; then the slices
  // are laid out with room for the pairs their intact bonds may release, and filled.
  const int threads = parallel ? omp_get_max_threads() : 1;
  if (found_.size() < std::size_t(threads)) found_.resize(std::size_t(threads));
  found_thread_.resize(n);
  found_at_.resize(n);
#pragma omp parallel if (parallel)
  {
    const int thread = omp_get_thread_num();
    auto& found = found_[std::size_t(thread)];
    found.clear();
#pragma omp for schedule(static)
    for (std::uint32_t a = 0; a < n; ++a) {
      const std::size_t begin = found.size();
      visit(a, [&](std::uint32_t b) { found.push_back(b); });
      std::sort(found.begin() + std::ptrdiff_t(begin), found.end());
      found_thread_[a] = std::uint32_t(thread);
      found_at_[a] = std::uint32_t(begin);
      count[a] = std::uint32_t(found.size() - begin);
    }
  }
  start[0] = 0;
  for (std::uint32_t a = 0; a < n; ++a) start[a + 1] = start[a] + count[a] + bonds.link_count[a];
  list.resize(start[n]);
#pragma omp parallel for schedule(static) if (parallel)
  for (std::uint32_t a = 0; a < n; ++a)
    std::copy_n(found_[found_thread_[a]].begin() + found_at_[a], count[a], list.begin() + start[a]);
  xb = x;
  yb = y;
  zb = z;
  ++builds;
}

void NeighbourList::insert_sorted(std::uint32_t a, std::uint32_t b) {
  assert(count[a] < start[a + 1] - start[a] && "neighbour slice has room for every released bond");
  std::uint32_t q = start[a] + count[a]++;
  for (; q > start[a] && list[q - 1] > b; --q) list[q] = list[q - 1];
  list[q] = b;
}

void NeighbourList::add_pair(std::uint32_t a, std::uint32_t b) {
  insert_sorted(a, b);
  insert_sorted(b, a);
}

void NeighbourList::adapt_skin(std::uint64_t step, double narrowest, double widest) {
  // A rebuild costs ~15-30 steps of force work on the reduced tissue (docs/performance.md): lists
  // that last under 50 steps make rebuilds a large share, past 500 a wider skin only costs.
  constexpr std::uint64_t short_lived = 50, long_lived = 500;
  constexpr double factor = 1.5;
  const std::uint64_t lasted = step - built_at_step;
  built_at_step = step;
  if (lasted < short_lived)
    skin = std::min(widest, factor * skin);
  else if (lasted > long_lived)
    skin = std::max(narrowest, skin / factor);
}

std::size_t NeighbourList::bytes() const {
  std::size_t total = (xb.capacity() + yb.capacity() + zb.capacity()) * sizeof(double);
  for (const auto* v : {&start, &count, &list, &cell_start_, &cell_particles_, &found_thread_, &found_at_})
    total += v->capacity() * sizeof(std::uint32_t);
  for (const auto& found : found_) total += found.capacity() * sizeof(std::uint32_t);
  return total;
}

}  // namespace rupture::dem
