#include "dem/bonds.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace rupture::dem {

BondStore::BondStore(const Sample& sample, std::span<const std::uint32_t> storage_of_sample) {
  const std::size_t n = sample.size(), nb = sample.bonds.size();
  i.resize(nb);
  j.resize(nb);
  r0.resize(nb);
  intact.assign(nb, 1);
  intact_count = nb;
  link_start.assign(n + 1, 0);
  for (std::size_t b = 0; b < nb; ++b) {
    const auto& bond = sample.bonds[b];
    if (bond.i >= bond.j || bond.j >= n || !(bond.rest_length > 0.0))
      throw InputError(
          "sample", "bond " + std::to_string(b) + " is invalid (needs i < j < particles and rest length > 0)",
          "regenerate or re-export the sample");
    i[b] = storage_of_sample[bond.i];
    j[b] = storage_of_sample[bond.j];
    r0[b] = bond.rest_length;
    ++link_start[i[b] + 1];
    ++link_start[j[b] + 1];
  }
  std::partial_sum(link_start.begin(), link_start.end(), link_start.begin());
  for (auto* v : {&link_other, &link_bond}) v->resize(2 * nb);
  link_r0.resize(2 * nb);
  // Per particle, links in order of the other particle (a fixed summation order).
  std::vector<std::vector<std::uint32_t>> bonds_of(n);
  for (std::uint32_t b = 0; b < nb; ++b) {
    bonds_of[i[b]].push_back(b);
    bonds_of[j[b]].push_back(b);
  }
  link_count.resize(n);
  for (std::uint32_t a = 0; a < n; ++a) {
    auto& list = bonds_of[a];
    const auto other = [&](std::uint32_t b) { return i[b] == a ? j[b] : i[b]; };
    std::sort(list.begin(), list.end(),
              [&](std::uint32_t l, std::uint32_t r) { return other(l) < other(r); });
    link_count[a] = static_cast<std::uint32_t>(list.size());
    std::uint32_t slot = link_start[a];
    for (const std::uint32_t b : list) set_link(slot++, a, b);
  }
}

void BondStore::set_link(std::uint32_t slot, std::uint32_t a, std::uint32_t bond) {
  link_bond[slot] = bond;
  link_other[slot] = i[bond] == a ? j[bond] : i[bond];
  link_r0[slot] = r0[bond];
}

bool BondStore::linked(std::uint32_t a, std::uint32_t b) const {
  for (std::uint32_t l = link_start[a]; l < link_start[a] + link_count[a]; ++l)
    if (link_other[l] == b) return true;
  return false;
}

void BondStore::unlink(std::uint32_t bond) {
  intact[bond] = 0;
  --intact_count;
  // Swap the link with the particle's last intact one and shrink the intact range.
  for (const std::uint32_t from : {i[bond], j[bond]}) {
    const std::uint32_t last = link_start[from] + link_count[from] - 1;
    for (std::uint32_t l = link_start[from]; l <= last; ++l)
      if (link_bond[l] == bond) {
        std::swap(link_other[l], link_other[last]);
        std::swap(link_bond[l], link_bond[last]);
        std::swap(link_r0[l], link_r0[last]);
        --link_count[from];
        break;
      }
  }
}

void BondStore::restore(std::span<const std::uint8_t> intact_flags, std::span<const std::uint32_t> counts,
                        std::span<const std::uint32_t> bond_of_link) {
  intact.assign(intact_flags.begin(), intact_flags.end());
  intact_count = std::size_t(std::count(intact.begin(), intact.end(), std::uint8_t{1}));
  link_count.assign(counts.begin(), counts.end());
  for (std::uint32_t a = 0; a + 1 < link_start.size(); ++a)
    for (std::uint32_t l = link_start[a]; l < link_start[a + 1]; ++l) set_link(l, a, bond_of_link[l]);
}

std::size_t BondStore::bytes() const {
  std::size_t total = 0;
  for (const auto* v : {&r0, &link_r0}) total += v->capacity() * sizeof(double);
  for (const auto* v : {&i, &j, &link_start, &link_count, &link_other, &link_bond})
    total += v->capacity() * sizeof(std::uint32_t);
  return total + intact.capacity();
}

}  // namespace rupture::dem
