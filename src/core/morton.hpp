// core/morton: Z-order (Morton) keys of integer cell coordinates, the space-filling curve along
// which samples are stored and the DEM engine orders its particles, so neighbours in space are
// neighbours in memory.
#pragma once

#include <cstdint>

namespace rupture {

// Spreads the low 21 bits of v over every third bit of a 63-bit word.
constexpr std::uint64_t spread_bits_3d(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

// The Morton key of cell (ix, iy, iz), each coordinate below 2^21.
constexpr std::uint64_t morton_key(std::uint64_t ix, std::uint64_t iy, std::uint64_t iz) {
  return spread_bits_3d(ix) | spread_bits_3d(iy) << 1 | spread_bits_3d(iz) << 2;
}

}  // namespace rupture
