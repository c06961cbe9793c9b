// dem/neighbours: the Verlet list's invariants, which the skin-independence of the forces rests on:
// every slice sorted, holding exactly the unbonded pairs within r_a + r_b + skin, released pairs
// inserted in sorted place, the rebuild test and the skin's adaptation.
#include "dem/neighbours.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sample/lattice.hpp"

namespace rupture::dem {
namespace {

struct Block {
  Sample sample = make_cubic_block(4, 4, 3, 0.5);
  Params params;
  ParticleStore particles{sample, params};
  BondStore bonds{sample, particles.storage_of_sample};
};

std::vector<std::uint32_t> slice(const NeighbourList& list, std::uint32_t a) {
  return {list.list.begin() + list.start[a], list.list.begin() + list.start[a] + list.count[a]};
}

// Every slice sorted, holding exactly the unbonded pairs within the cutoff (against all pairs), with
// room for the pairs its bonds may release; returns the number of candidates.
std::size_t expect_exact_slices(const Block& block, const NeighbourList& list) {
  const auto& p = block.particles.hot;
  std::size_t pairs = 0;
  for (std::uint32_t a = 0; a < block.particles.size(); ++a) {
    const auto mine = slice(list, a);
    EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end())) << "slot " << a;
    std::vector<std::uint32_t> expected;
    for (std::uint32_t b = 0; b < block.particles.size(); ++b) {
      if (b == a || block.bonds.linked(a, b)) continue;
      const double d = std::hypot(p.x[b] - p.x[a], p.y[b] - p.y[a], p.z[b] - p.z[a]);
      if (d < p.radius[a] + p.radius[b] + list.skin) expected.push_back(b);
    }
    EXPECT_EQ(mine, expected) << "slot " << a;
    pairs += mine.size();
    EXPECT_EQ(list.start[a + 1] - list.start[a], mine.size() + block.bonds.link_count[a])
        << "room for every pair its bonds may release";
  }
  return pairs;
}

TEST(NeighbourList, SlicesAreSortedAndHoldExactlyTheUnbondedPairsWithinTheCutoff) {
  Block block;
  NeighbourList list;
  list.skin = 0.5;  // mm: reaches the face diagonals (1.414 mm apart, cutoff 1.5 mm), not the body ones
  list.build(block.particles.hot, block.bonds, block.particles.max_radius, false);
  EXPECT_GT(expect_exact_slices(block, list), 0u) << "the face diagonals are candidates";
}

// After failure fragments fly far apart: the grid must stay O(particles) (a dense grid over their box
// was 10^9 cells, 4 GB cleared at every rebuild) and still find exactly the pairs within the cutoff,
// also where far cells share a bucket and where one lies further out than any integer cell index.
TEST(NeighbourList, FragmentsFlownFarApartKeepTheGridSmallAndTheSlicesExact) {
  Block block;
  auto& p = block.particles.hot;
  const double far[][3] = {{1e5, 2e5, -3e20}, {-4e5, 1e5, 2e5}, {3e5, -2e5, 1e5}, {3e5 + 0.9, -2e5, 1e5}};
  for (std::uint32_t a = 0; a < 4; ++a) {  // the last two close to each other: a pair far from the rest
    p.x[a] = far[a][0];
    p.y[a] = far[a][1];
    p.z[a] = far[a][2];
  }
  NeighbourList list;
  list.skin = 0.5;
  list.build(p, block.bonds, block.particles.max_radius, false);
  EXPECT_GT(expect_exact_slices(block, list), 0u);
  EXPECT_LT(list.bytes(), std::size_t{64} << 10) << "bytes for 48 particles over a box of 10^6 mm";
}

TEST(NeighbourList, ReleasedPairsGoInSortedPlaceAtBothEnds) {
  Block block;
  NeighbourList list;
  list.skin = 0.5;
  list.build(block.particles.hot, block.bonds, block.particles.max_radius, false);
  const std::uint32_t bond = 7, i = block.bonds.i[bond], j = block.bonds.j[bond];
  block.bonds.unlink(bond);
  list.add_pair(i, j);
  for (const auto& [self, other] : {std::pair{i, j}, std::pair{j, i}}) {
    const auto mine = slice(list, self);
    EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
    EXPECT_EQ(std::count(mine.begin(), mine.end(), other), 1);
  }
}

TEST(NeighbourList, RebuildIsDueWhenTwoMovesTogetherCouldCloseTheSkin) {
  NeighbourList list;
  list.skin = 0.1;
  EXPECT_FALSE(list.stale(0.06, 0.04)) << "two particles closing by at most 0.1 mm cannot touch";
  EXPECT_TRUE(list.stale(0.06, 0.0401));
  EXPECT_FALSE(list.stale(0.09, 0.0)) << "one particle alone may move almost the whole skin";
  EXPECT_TRUE(list.stale(INFINITY, 0.0)) << "a non-finite move forces a rebuild";
}

TEST(NeighbourList, SkinWidensForShortLivedListsAndNarrowsBack) {
  NeighbourList list;
  list.skin = 0.05;
  list.adapt_skin(10, 0.05, 0.2);  // the list lasted 10 steps
  EXPECT_DOUBLE_EQ(list.skin, 0.075);
  for (std::uint64_t step = 20; step < 200; step += 10) list.adapt_skin(step, 0.05, 0.2);
  EXPECT_DOUBLE_EQ(list.skin, 0.2) << "capped at the widest";
  list.adapt_skin(300, 0.05, 0.2);  // lasted 110 steps: kept
  EXPECT_DOUBLE_EQ(list.skin, 0.2);
  for (std::uint64_t step = 1000; step < 10000; step += 1000) list.adapt_skin(step, 0.05, 0.2);
  EXPECT_DOUBLE_EQ(list.skin, 0.05) << "back to the narrowest when lists last long";
}

}  // namespace
}  // namespace rupture::dem
