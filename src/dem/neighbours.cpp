#include "dem/neighbours.hpp"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>
#include <span>

namespace rupture::dem {

namespace {

// The cells of the grid: cubes of side `side` (no smaller than the largest cutoff) addressed by their
// integer coordinates from the particles' lower corner. While the particles' box holds at most
// `buckets` cells they are numbered densely; a larger box (fragments flown far apart after failure)
// is hashed into that many buckets, so memory and time stay O(particles) however far they fly (a
// dense grid there reached 10^9 cells, 4 GB cleared at every rebuild, ~8 steps/s on 2,708 particles).
// Cells that share a bucket only add candidates the distance test rejects.
struct CellTable {
  double lo[3], side;
  std::int64_t dims[3];  // cells along each axis
  std::size_t buckets;
  bool hashed;

  CellTable(const double (&low)[3], const double (&high)[3], double cell_side, std::size_t particles)
      : lo{low[0], low[1], low[2]}, side(cell_side), buckets(std::max<std::size_t>(64, 2 * particles)) {
    double cells = 1.0;
    for (int d = 0; d < 3; ++d) {
      const double along = std::floor((high[d] - low[d]) / side) + 1.0;
      cells *= along;
      dims[d] = along < 1e9 ? std::int64_t(along) : std::int64_t(1e9);
    }
    hashed = cells > double(buckets);
    if (!hashed) buckets = std::size_t(dims[0] * dims[1] * dims[2]);
  }
  // Clamped before the cast: a fragment may lie 1e20 cells out, past any integer.
  std::int64_t coord(double v, int d) const {
    return std::int64_t(std::min(double(dims[d] - 1), std::max(0.0, std::floor((v - lo[d]) / side))));
  }
  // The bucket of cell (ix, iy, iz), or -1 for a cell outside the dense grid.
  std::int64_t bucket(std::int64_t ix, std::int64_t iy, std::int64_t iz) const {
    if (!hashed) {
      if (ix < 0 || iy < 0 || iz < 0 || ix >= dims[0] || iy >= dims[1] || iz >= dims[2]) return -1;
      return (iz * dims[1] + iy) * dims[0] + ix;
    }
    const auto h =
        std::uint64_t(ix) * 73856093u ^ std::uint64_t(iy) * 19349663u ^ std::uint64_t(iz) * 83492791u;
    return std::int64_t(h % buckets);
  }
};

// The particles' bounding box (mm); false where a position is not finite.
bool bounding_box(const HotParticles& p, double (&lo)[3], double (&hi)[3]) {
  lo[0] = hi[0] = p.x[0], lo[1] = hi[1] = p.y[0], lo[2] = hi[2] = p.z[0];
  for (std::size_t a = 0; a < p.x.size(); ++a) {
    if (!std::isfinite(p.x[a] + p.y[a] + p.z[a])) return false;
    lo[0] = std::min(lo[0], p.x[a]);
    hi[0] = std::max(hi[0], p.x[a]);
    lo[1] = std::min(lo[1], p.y[a]);
    hi[1] = std::max(hi[1], p.y[a]);
    lo[2] = std::min(lo[2], p.z[a]);
    hi[2] = std::max(hi[2], p.z[a]);
  }
  return true;
}

// What the candidate sweep reads: the table, each bucket's slice [start[b], start[b + 1]) of the
// particles in bucket order, their storage indices and their positions and radii.
struct Bins {
  const CellTable& table;
  std::span<const std::uint32_t> start, particles;
  std::span<const NeighbourList::Binned> binned;
};

// Appends the candidates of storage particle a, at `at`, to `found`: the unbonded particles of its 27
// cells within r_a + r_b + margin, each once and unsorted. In a dense grid the three cells of a row
// along x are consecutive buckets, so each row is one sweep over consecutive memory; hashed, distinct
// cells may share a bucket, and each bucket is swept once.
void gather_candidates(std::uint32_t a, const NeighbourList::Binned at, const Bins& bins,
                       const BondStore& bonds, double margin, std::vector<std::uint32_t>& found) {
  // Local copies of the views: `found` grows in memory, through which they would otherwise be reread.
  const auto binned = bins.binned;
  const auto particles = bins.particles;
  const auto sweep = [&](std::uint32_t from, std::uint32_t to) {
    for (std::uint32_t q = from; q < to; ++q) {
      const NeighbourList::Binned& c = binned[q];
      const double dx = c.x - at.x, dy = c.y - at.y, dz = c.z - at.z;
      const double cut = at.radius + c.radius + margin;
      if (dx * dx + dy * dy + dz * dz < cut * cut) {
        const std::uint32_t b = particles[q];
        if (b != a && !bonds.linked(a, b)) found.push_back(b);
      }
    }
  };
  const CellTable& table = bins.table;
  const std::int64_t cx = table.coord(at.x, 0), cy = table.coord(at.y, 1), cz = table.coord(at.z, 2);
  if (!table.hashed) {
    const std::int64_t x0 = std::max<std::int64_t>(cx - 1, 0), x1 = std::min(cx + 1, table.dims[0] - 1);
    for (std::int64_t iz = std::max<std::int64_t>(cz - 1, 0); iz <= std::min(cz + 1, table.dims[2] - 1); ++iz)
      for (std::int64_t iy = std::max<std::int64_t>(cy - 1, 0); iy <= std::min(cy + 1, table.dims[1] - 1);
           ++iy)
        sweep(bins.start[std::size_t(table.bucket(x0, iy, iz))],
              bins.start[std::size_t(table.bucket(x1, iy, iz)) + 1]);
    return;
  }
  std::int64_t seen[27];
  int distinct = 0;
  for (std::int64_t iz = cz - 1; iz <= cz + 1; ++iz)
    for (std::int64_t iy = cy - 1; iy <= cy + 1; ++iy)
      for (std::int64_t ix = cx - 1; ix <= cx + 1; ++ix) {
        const std::int64_t c = table.bucket(ix, iy, iz);
        if (std::find(seen, seen + distinct, c) != seen + distinct) continue;
        seen[distinct++] = c;
        sweep(bins.start[std::size_t(c)], bins.start[std::size_t(c) + 1]);
      }
}

}  // namespace

// Particles binned by a counting sort in storage order into the cell table's buckets, with their
// positions copied in that order; each particle's candidates gathered from its 27 cells (in a dense
// grid nine runs of three consecutive buckets; hashed, each bucket once) and sorted. One
// pass over the particles on purpose: after failure it runs hundreds of times per run, and the
// binning and the candidate sweep share its buffers.
void NeighbourList::build(const HotParticles& p, const BondStore& bonds, double max_radius, bool parallel) {
  const std::uint32_t n = static_cast<std::uint32_t>(p.x.size());
  const auto& x = p.x;
  const auto& y = p.y;
  const auto& z = p.z;
  for (auto* v : {&xb, &yb, &zb}) v->resize(n);  // sized even when the build gives up below
  double lo[3], hi[3];
  if (!bounding_box(p, lo, hi)) return;
  const CellTable table(lo, hi, 2.0 * max_radius + skin, n);
  const auto bucket_of = [&](std::uint32_t a) {
    return std::uint32_t(table.bucket(table.coord(x[a], 0), table.coord(y[a], 1), table.coord(z[a], 2)));
  };
  cell_start_.assign(table.buckets + 1, 0);
  cell_particles_.resize(n);
  count.resize(n);
  start.resize(n + 1);
  // Bucket per particle kept in `count` meanwhile.
  for (std::uint32_t a = 0; a < n; ++a) {
    count[a] = bucket_of(a);
    ++cell_start_[count[a] + 1];
  }
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::uint32_t a = 0; a < n; ++a) cell_particles_[fill[count[a]]++] = a;
  }
  // The particles' positions and radii copied into bucket order, so that the sweep below reads each
  // bucket's particles from consecutive memory rather than gathering them from storage order.
  binned_.resize(n);
  for (std::uint32_t q = 0; q < n; ++q) {
    const std::uint32_t b = cell_particles_[q];
    binned_[q] = {x[b], y[b], z[b], p.radius[b]};
  }

  const Bins bins{table, cell_start_, cell_particles_, binned_};
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
      gather_candidates(a, {x[a], y[a], z[a], p.radius[a]}, bins, bonds, skin, found);
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
  total += binned_.capacity() * sizeof(Binned);
  for (const auto& found : found_) total += found.capacity() * sizeof(std::uint32_t);
  return total;
}

}  // namespace rupture::dem
