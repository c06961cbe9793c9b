#include "dem/particles.hpp"

#include <algorithm>
#include <numeric>

#include "core/error.hpp"
#include "core/morton.hpp"
#include "dem/physics.hpp"

namespace rupture::dem {

namespace {

// Storage order: particles sorted along a Z-order curve of their initial positions (ties broken by
// sample index: deterministic).
std::vector<std::uint32_t> morton_order(const Sample& sample) {
  const std::size_t n = sample.size();
  Vec3 lo = sample.position.empty() ? Vec3{} : sample.position[0], hi = lo;
  for (const auto& p : sample.position) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-300});
  const double scale = double((1u << 21) - 1) / extent;
  std::vector<std::uint64_t> key(n);
  for (std::size_t a = 0; a < n; ++a) {
    const auto& p = sample.position[a];
    key[a] = morton_key(std::uint64_t((p.x - lo.x) * scale), std::uint64_t((p.y - lo.y) * scale),
                        std::uint64_t((p.z - lo.z) * scale));
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  return order;
}

}  // namespace

ParticleStore::ParticleStore(const Sample& sample, const Params& params) {
  const std::size_t n = sample.size();
  sample_of_storage = morton_order(sample);
  storage_of_sample.resize(n);
  for (std::uint32_t a = 0; a < n; ++a) storage_of_sample[sample_of_storage[a]] = a;

  for (auto* v : {&hot.x, &hot.y, &hot.z, &hot.vx, &hot.vy, &hot.vz, &hot.fx, &hot.fy, &hot.fz, &hot.inv_mass,
                  &hot.radius, &cold.mass, &cold.ax, &cold.ay, &cold.az, &cold.damped})
    v->assign(n, 0.0);
  hot.plate.assign(n, plate_none);
  double bottom_y = 0.0, top_y = 0.0;
  std::size_t bottom_n = 0, top_n = 0;
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint32_t s = sample_of_storage[a];
    const Vec3 p = sample.position[s];
    hot.x[a] = cold.ax[a] = p.x;
    hot.y[a] = cold.ay[a] = p.y;
    hot.z[a] = cold.az[a] = p.z;
    hot.radius[a] = sample.radius[s];
    if (!(hot.radius[a] > 0.0))
      throw InputError("sample", "particle " + std::to_string(sample.id[s]) + " has radius <= 0",
                       "fix the sample");
    cold.mass[a] = particle_mass(hot.radius[a], params.density);
    hot.inv_mass[a] = 1.0 / cold.mass[a];
    max_radius = std::max(max_radius, hot.radius[a]);
    switch (sample.group[s]) {
      case ParticleGroup::bottom:
        hot.plate[a] = plate_bottom;
        bottom_y += p.y;
        ++bottom_n;
        break;
      case ParticleGroup::top:
        hot.plate[a] = plate_top;
        top_y += p.y;
        ++top_n;
        break;
      case ParticleGroup::free:
        break;
    }
    if (hot.plate[a] != plate_none) glued.push_back(a);
  }
  if (bottom_n == 0 || top_n == 0)
    throw InputError("sample", "needs particles glued to both the bottom and the top plate",
                     "mark the bottom and top layers (groups) in the sample");
  plate_separation0 = top_y / double(top_n) - bottom_y / double(bottom_n);
}

std::size_t ParticleStore::bytes() const {
  std::size_t total = 0;
  for (const auto* v : {&hot.x, &hot.y, &hot.z, &hot.vx, &hot.vy, &hot.vz, &hot.fx, &hot.fy, &hot.fz,
                        &hot.inv_mass, &hot.radius, &cold.mass, &cold.ax, &cold.ay, &cold.az, &cold.damped})
    total += v->capacity() * sizeof(double);
  for (const auto* v : {&storage_of_sample, &sample_of_storage, &glued})
    total += v->capacity() * sizeof(std::uint32_t);
  return total + hot.plate.capacity();
}

}  // namespace rupture::dem
