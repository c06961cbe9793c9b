#include "dem/system.hpp"

#include "core/hash.hpp"
#include "core/morton.hpp"

#include <omp.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "core/units.hpp"
#include "dem/force_laws.hpp"

namespace rupture::dem {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Storage order: particles sorted along a Z-order curve of their initial positions, so that
// neighbours in space are neighbours in memory (ties broken by sample index: deterministic).
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

void validate(const Sample& sample, const Params& p) {
  const std::size_t n = sample.size();
  if (sample.radius.size() != n || sample.group.size() != n || sample.id.size() != n)
    throw InputError("sample", "particle arrays differ in length", "regenerate or re-export the sample");
  for (std::size_t b = 0; b < sample.bonds.size(); ++b) {
    const auto& bond = sample.bonds[b];
    if (bond.i >= bond.j || bond.j >= n || !(bond.rest_length > 0.0))
      throw InputError(
          "sample", "bond " + std::to_string(b) + " is invalid (needs i < j < particles and rest length > 0)",
          "regenerate or re-export the sample");
  }
  if (!(p.bond_stiffness > 0.0))
    throw InputError("bonds.stiffness", "must be > 0 (N/mm)", "give a positive k_n");
  if (!(p.break_distance > 0.0))
    throw InputError("bonds.break_distance", "must be > 0", "give a positive b_d");
  if (!(p.density > 0.0))
    throw InputError("sample.density", "must be > 0 (g/mm^3)", "give a positive density");
}

}  // namespace

System::System(const Sample& sample, const Params& params) : params_(params) {
  validate(sample, params);
  const std::size_t n = sample.size();
  parallel_ = n >= 2048;
  sample_of_storage_ = morton_order(sample);
  storage_of_sample_.resize(n);
  for (std::uint32_t a = 0; a < n; ++a) storage_of_sample_[sample_of_storage_[a]] = a;

  for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &fx_, &fy_, &fz_, &inv_mass_, &radius_, &mass_, &ax_, &ay_,
                  &az_, &xb_, &yb_, &zb_, &damped_per_particle_})
    v->assign(n, 0.0);
  plate_.assign(n, plate_none);
  const double rho = units::density_from_g_per_mm3(params.density);
  double bottom_y = 0.0, top_y = 0.0;
  std::size_t bottom_n = 0, top_n = 0;
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint32_t s = sample_of_storage_[a];
    const Vec3 p = sample.position[s];
    x_[a] = ax_[a] = p.x;
    y_[a] = ay_[a] = p.y;
    z_[a] = az_[a] = p.z;
    radius_[a] = sample.radius[s];
    if (!(radius_[a] > 0.0))
      throw InputError("sample", "particle " + std::to_string(sample.id[s]) + " has radius <= 0",
                       "fix the sample");
    mass_[a] = rho * units::sphere_volume(radius_[a]);
    inv_mass_[a] = 1.0 / mass_[a];
    max_radius_ = std::max(max_radius_, radius_[a]);
    switch (sample.group[s]) {
      case ParticleGroup::bottom:
        plate_[a] = plate_bottom;
        bottom_y += p.y;
        ++bottom_n;
        break;
      case ParticleGroup::top:
        plate_[a] = plate_top;
        top_y += p.y;
        ++top_n;
        break;
      case ParticleGroup::free:
        break;
    }
    if (plate_[a] != plate_none) glued_.push_back(a);
  }
  if (bottom_n == 0 || top_n == 0)
    throw InputError("sample", "needs particles glued to both the bottom and the top plate",
                     "mark the bottom and top layers (groups) in the sample");
  plate_separation0_ = top_y / double(top_n) - bottom_y / double(bottom_n);

  // Bonds: constants per bond, then links grouped by particle in order of the other particle.
  const std::size_t nb = sample.bonds.size();
  bond_i_.resize(nb);
  bond_j_.resize(nb);
  bond_r0_.resize(nb);
  bond_k_.resize(nb);
  intact_.assign(nb, 1);
  intact_count_ = nb;
  link_start_.assign(n + 1, 0);
  for (std::size_t b = 0; b < nb; ++b) {
    const auto& bond = sample.bonds[b];
    bond_i_[b] = storage_of_sample_[bond.i];
    bond_j_[b] = storage_of_sample_[bond.j];
    bond_r0_[b] = bond.rest_length;
    bond_k_[b] =
        params.scale_stiffness ? params.bond_stiffness * bond.rest_length / 4.0 : params.bond_stiffness;
    ++link_start_[bond_i_[b] + 1];
    ++link_start_[bond_j_[b] + 1];
  }
  std::partial_sum(link_start_.begin(), link_start_.end(), link_start_.begin());
  for (auto* v : {&link_other_, &link_bond_}) v->resize(2 * nb);
  for (auto* v : {&link_r0_, &link_k_, &link_limit_}) v->resize(2 * nb);
  {
    // Per particle, links in order of the other particle (a fixed summation order).
    std::vector<std::vector<std::uint32_t>> bonds_of(n);
    for (std::uint32_t b = 0; b < nb; ++b) {
      bonds_of[bond_i_[b]].push_back(b);
      bonds_of[bond_j_[b]].push_back(b);
    }
    link_count_.resize(n);
    for (std::uint32_t a = 0; a < n; ++a) {
      auto& list = bonds_of[a];
      const auto other = [&](std::uint32_t b) { return bond_i_[b] == a ? bond_j_[b] : bond_i_[b]; };
      std::sort(list.begin(), list.end(),
                [&](std::uint32_t l, std::uint32_t r) { return other(l) < other(r); });
      link_count_[a] = static_cast<std::uint32_t>(list.size());
      std::uint32_t l = link_start_[a];
      for (const std::uint32_t b : list) set_link(l++, a, b);
    }
  }

  // Stability bound (Gershgorin on the mass-weighted stiffness matrix): for particle a,
  // lambda_a = sum_b k_ab (1/m_a + 1/sqrt(m_a m_b)) + k_glue/m_a.
  double lambda_max = 0.0;
  for (std::uint32_t a = 0; a < n; ++a) {
    double lambda = 0.0, spring_sum = 0.0;
    for (std::uint32_t l = link_start_[a]; l < link_start_[a + 1]; ++l) {
      lambda += link_k_[l] * (inv_mass_[a] + 1.0 / std::sqrt(mass_[a] * mass_[link_other_[l]]));
      spring_sum += link_k_[l];
    }
    if (plate_[a] != plate_none && params.glue_mode == GlueMode::spring) {
      lambda += params.glue_stiffness * inv_mass_[a];
      spring_sum += params.glue_stiffness;
    }
    if (lambda > lambda_max) {
      lambda_max = lambda;
      stiffest_spring_sum_ = spring_sum;
      stiffest_mass_ = mass_[a];
    }
  }
  critical_dt_ = lambda_max > 0.0 ? 2.0 / std::sqrt(lambda_max) : std::numeric_limits<double>::infinity();

  rebuild_neighbours();
  compute_forces(0.0);
  update_plate_forces();
}

std::size_t System::state_bytes() const {
  const std::size_t n = x_.size();
  return n * (13 * sizeof(double) + 3 * sizeof(std::uint32_t)) + (n + 1) * sizeof(std::uint32_t) +
         intact_.size() + (link_bond_.size() + nb_.size()) * sizeof(std::uint32_t);
}

std::size_t System::memory_bytes() const {
  std::size_t bytes = 0;
  for (const auto* v : {&x_,
                        &y_,
                        &z_,
                        &vx_,
                        &vy_,
                        &vz_,
                        &fx_,
                        &fy_,
                        &fz_,
                        &inv_mass_,
                        &radius_,
                        &mass_,
                        &ax_,
                        &ay_,
                        &az_,
                        &xb_,
                        &yb_,
                        &zb_,
                        &damped_per_particle_,
                        &bond_r0_,
                        &bond_k_})
    bytes += v->capacity() * sizeof(double);
  for (const auto* v : {&storage_of_sample_, &sample_of_storage_, &glued_, &bond_i_, &bond_j_, &link_start_,
                        &nb_start_, &nb_count_, &nb_, &cell_start_, &cell_particles_, &flagged_merged_})
    bytes += v->capacity() * sizeof(std::uint32_t);
  for (const auto* v : {&link_count_, &link_other_, &link_bond_})
    bytes += v->capacity() * sizeof(std::uint32_t);
  for (const auto* v : {&link_r0_, &link_k_, &link_limit_}) bytes += v->capacity() * sizeof(double);
  bytes += plate_.capacity() + intact_.capacity();
  return bytes;
}

// Link slot l of particle a holds bond b: the other end and the bond's constants.
void System::set_link(std::uint32_t l, std::uint32_t a, std::uint32_t b) {
  link_bond_[l] = b;
  link_other_[l] = bond_i_[b] == a ? bond_j_[b] : bond_i_[b];
  link_r0_[l] = bond_r0_[b];
  link_k_[l] = bond_k_[b];
  link_limit_[l] = params_.break_rule == BreakRule::absolute ? params_.break_distance
                                                             : params_.break_distance * bond_r0_[b];
}

bool System::bonded_intact(std::uint32_t a, std::uint32_t b) const {
  for (std::uint32_t l = link_start_[a]; l < link_start_[a] + link_count_[a]; ++l)
    if (link_other_[l] == b) return true;
  return false;
}

// Cell grid with cells no smaller than the largest cutoff (2 r_max + skin), particles binned by a
// counting sort in storage order; each particle's list is then filled in a fixed cell order, so
// the list (and every force sum over it) is the same for any thread count.
void System::rebuild_neighbours() {
  const auto start = Clock::now();
  const std::uint32_t n = static_cast<std::uint32_t>(x_.size());
  const double skin = params_.skin;
  double lo[3] = {x_[0], y_[0], z_[0]}, hi[3] = {x_[0], y_[0], z_[0]};
  for (std::uint32_t a = 0; a < n; ++a) {
    if (!std::isfinite(x_[a] + y_[a] + z_[a])) return;  // unstable state: the caller's check reports it
    lo[0] = std::min(lo[0], x_[a]);
    hi[0] = std::max(hi[0], x_[a]);
    lo[1] = std::min(lo[1], y_[a]);
    hi[1] = std::max(hi[1], y_[a]);
    lo[2] = std::min(lo[2], z_[a]);
    hi[2] = std::max(hi[2], z_[a]);
  }
  const double cell = 2.0 * max_radius_ + skin;
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
  nb_count_.resize(n);
  nb_start_.resize(n + 1);
  // Cell index per particle kept in nb_count_ temporarily.
  for (std::uint32_t a = 0; a < n; ++a) {
    const auto c = std::uint32_t((coord(z_[a], 2) * dims[1] + coord(y_[a], 1)) * dims[0] + coord(x_[a], 0));
    nb_count_[a] = c;
    ++cell_start_[c + 1];
  }
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  {
    std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::uint32_t a = 0; a < n; ++a) cell_particles_[fill[nb_count_[a]]++] = a;
  }

  // Visits the candidates of particle a in a fixed order.
  const auto visit = [&](std::uint32_t a, auto&& take) {
    const std::int64_t cx = coord(x_[a], 0), cy = coord(y_[a], 1), cz = coord(z_[a], 2);
    for (std::int64_t iz = std::max<std::int64_t>(0, cz - 1); iz <= std::min(dims[2] - 1, cz + 1); ++iz)
      for (std::int64_t iy = std::max<std::int64_t>(0, cy - 1); iy <= std::min(dims[1] - 1, cy + 1); ++iy)
        for (std::int64_t ix = std::max<std::int64_t>(0, cx - 1); ix <= std::min(dims[0] - 1, cx + 1); ++ix) {
          const std::size_t c = std::size_t((iz * dims[1] + iy) * dims[0] + ix);
          for (std::uint32_t p = cell_start_[c]; p < cell_start_[c + 1]; ++p) {
            const std::uint32_t b = cell_particles_[p];
            if (b == a) continue;
            const double dx = x_[b] - x_[a], dy = y_[b] - y_[a], dz = z_[b] - z_[a];
            const double cut = radius_[a] + radius_[b] + skin;
            if (dx * dx + dy * dy + dz * dz < cut * cut && !bonded_intact(a, b)) take(b);
          }
        }
  };
  // Pass 1: capacity per particle = candidates + intact bonds (room for pairs released by breaks).
  std::vector<std::uint32_t> capacity(n);
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::uint32_t a = 0; a < n; ++a) {
    std::uint32_t count = 0;
    visit(a, [&](std::uint32_t) { ++count; });
    capacity[a] = count + link_count_[a];
  }
  nb_start_[0] = 0;
  for (std::uint32_t a = 0; a < n; ++a) nb_start_[a + 1] = nb_start_[a] + capacity[a];
  nb_.resize(nb_start_[n]);
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::uint32_t a = 0; a < n; ++a) {
    std::uint32_t count = 0;
    visit(a, [&](std::uint32_t b) { nb_[nb_start_[a] + count++] = b; });
    nb_count_[a] = count;
  }
  std::copy(x_.begin(), x_.end(), xb_.begin());
  std::copy(y_.begin(), y_.end(), yb_.begin());
  std::copy(z_.begin(), z_.end(), zb_.begin());
  ++rebuilds_;
  times_.neighbours += seconds_since(start);
}

void System::add_neighbour(std::uint32_t a, std::uint32_t b) {
  assert(nb_count_[a] < nb_start_[a + 1] - nb_start_[a] &&
         "neighbour slice has room for every released bond");
  nb_[nb_start_[a] + nb_count_[a]++] = b;
}

void System::compute_forces(double half_dt) {
  if (params_.damping > 0.0)
    compute_forces_impl<true>(half_dt);
  else
    compute_forces_impl<false>(half_dt);
}

// Force pass: each particle gathers its bond, contact and glue forces in a fixed order, flags its
// bonds that exceed their limit (from the lower-index end only, so each bond is flagged once) and
// finishes its velocity half-kick. A bond over its limit contributes no force in the pass that
// finds it: it breaks at this configuration.
template <bool damped>
void System::compute_forces_impl(double half_dt) {
  const auto start = Clock::now();
  const std::uint32_t n = static_cast<std::uint32_t>(x_.size());
  const int threads = omp_get_max_threads();
  if (flagged_.size() < std::size_t(threads)) flagged_.resize(std::size_t(threads));
  const double kc = params_.contact_stiffness;
  const double kg = params_.glue_mode == GlueMode::spring ? params_.glue_stiffness : 0.0;
  const double plate_u[3] = {0.0, 0.0, top_.displacement};
  const double damping = params_.damping;
  const double* __restrict x = x_.data();
  const double* __restrict y = y_.data();
  const double* __restrict z = z_.data();
  const double* __restrict rad = radius_.data();
  const std::uint32_t* __restrict link_other = link_other_.data();
  const double* __restrict link_r0 = link_r0_.data();
  const double* __restrict link_k = link_k_.data();
  const double* __restrict link_limit = link_limit_.data();
  const std::uint32_t* __restrict link_start = link_start_.data();
  const std::uint32_t* __restrict link_count = link_count_.data();
  const std::uint32_t* __restrict nb = nb_.data();
#pragma omp parallel if (parallel_)
  {
    auto& flags = flagged_[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(static)
    for (std::uint32_t a = 0; a < n; ++a) {
      const double xa = x[a], ya = y[a], za = z[a];
      double fx = 0.0, fy = 0.0, fz = 0.0;
      const std::uint32_t begin = link_start[a], end = begin + link_count[a];
      int over = 0;
      // Branch-free so that it vectorises; a bond over its limit gives no force and is flagged below.
#pragma omp simd reduction(+ : fx, fy, fz) reduction(| : over)
      for (std::uint32_t l = begin; l < end; ++l) {
        const std::uint32_t j = link_other[l];
        const double dx = x[j] - xa, dy = y[j] - ya, dz = z[j] - za;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double s = r - link_r0[l];
        const bool holds = s <= link_limit[l];
        const double c = holds ? link_k[l] * s / r : 0.0;
        fx += c * dx;
        fy += c * dy;
        fz += c * dz;
        over |= int(!holds);
      }
      if (over) [[unlikely]] {
        for (std::uint32_t l = begin; l < end; ++l) {
          const std::uint32_t j = link_other[l];
          const double dx = x[j] - xa, dy = y[j] - ya, dz = z[j] - za;
          if (j > a && std::sqrt(dx * dx + dy * dy + dz * dz) - link_r0[l] > link_limit[l])
            flags.push_back(link_bond_[l]);
        }
      }
      const double ra = rad[a];
#pragma omp simd reduction(+ : fx, fy, fz)
      for (std::uint32_t p = nb_start_[a]; p < nb_start_[a] + nb_count_[a]; ++p) {
        const std::uint32_t b = nb[p];
        const double dx = x[b] - xa, dy = y[b] - ya, dz = z[b] - za;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        const double touch = ra + rad[b];
        const double c = r < touch ? -kc * (touch - r) / r : 0.0;
        fx += c * dx;
        fy += c * dy;
        fz += c * dz;
      }
      const std::uint8_t plate = plate_[a];
      if (plate != plate_none) {
        fx -= kg * (xa - ax_[a]);
        fy -= kg * (ya - ay_[a] - plate_u[plate]);
        fz -= kg * (za - az_[a]);
      }
      fx_[a] = fx;
      fy_[a] = fy;
      fz_[a] = fz;
      if (plate != plate_none && params_.glue_mode == GlueMode::rigid) continue;
      const double h = half_dt * inv_mass_[a];
      if constexpr (damped) {
        const double keep = 1.0 - damping * half_dt;
        const double vx0 = vx_[a], vy0 = vy_[a], vz0 = vz_[a];
        vx_[a] = vx0 * keep + h * fx;
        vy_[a] = vy0 * keep + h * fy;
        vz_[a] = vz0 * keep + h * fz;
        // Work of -c m v over the half step, with the mean of the old and new velocity.
        damped_per_particle_[a] +=
            damping * half_dt * mass_[a] * 0.5 *
            (vx0 * vx0 + vy0 * vy0 + vz0 * vz0 + vx_[a] * vx0 + vy_[a] * vy0 + vz_[a] * vz0);
      } else {
        vx_[a] += h * fx;
        vy_[a] += h * fy;
        vz_[a] += h * fz;
      }
    }
  }
  times_.forces += seconds_since(start);
}

namespace {

// The farthest mover of a step: larger (|dt v| / r)^2 wins, ties go to the lower storage index, so
// the result is the same for any split of the loop over threads.
struct MoveMax {
  double move2;
  std::uint32_t index;
};
inline MoveMax farther(const MoveMax& a, const MoveMax& b) {
  return (a.move2 > b.move2 || (a.move2 == b.move2 && a.index < b.index)) ? a : b;
}
#pragma omp declare reduction(farther : MoveMax : omp_out = farther(omp_out, omp_in)) \
    initializer(omp_priv = MoveMax{-1.0, 0xffffffffu})

}  // namespace

// First half-kick and drift; glued particles in rigid mode follow their plate. Returns the largest
// squared displacement since the last neighbour-list build (mm^2) and this step's farthest mover.
template <bool damped>
System::DriftResult System::kick_drift(double dt) {
  const std::uint32_t n = static_cast<std::uint32_t>(x_.size());
  const double half = 0.5 * dt, damping = params_.damping;
  const bool rigid = params_.glue_mode == GlueMode::rigid;
  const double plate_u[3] = {0.0, 0.0, top_.displacement};
  const double plate_v[3] = {0.0, 0.0, top_.velocity};
  double max_d2 = 0.0;
  MoveMax mover{-1.0, 0xffffffffu};
#pragma omp parallel for schedule(static) reduction(max : max_d2) reduction(farther : mover) if (parallel_)
  for (std::uint32_t a = 0; a < n; ++a) {
    const std::uint8_t plate = plate_[a];
    if (rigid && plate != plate_none) {
      x_[a] = ax_[a];
      y_[a] = ay_[a] + plate_u[plate];
      z_[a] = az_[a];
      vx_[a] = 0.0;
      vy_[a] = plate_v[plate];
      vz_[a] = 0.0;
    } else {
      const double h = half * inv_mass_[a];
      if constexpr (damped) {
        const double keep = 1.0 - damping * half;
        const double vx0 = vx_[a], vy0 = vy_[a], vz0 = vz_[a];
        vx_[a] = vx0 * keep + h * fx_[a];
        vy_[a] = vy0 * keep + h * fy_[a];
        vz_[a] = vz0 * keep + h * fz_[a];
        damped_per_particle_[a] +=
            damping * half * mass_[a] * 0.5 *
            (vx0 * vx0 + vy0 * vy0 + vz0 * vz0 + vx_[a] * vx0 + vy_[a] * vy0 + vz_[a] * vz0);
      } else {
        vx_[a] += h * fx_[a];
        vy_[a] += h * fy_[a];
        vz_[a] += h * fz_[a];
      }
      x_[a] += dt * vx_[a];
      y_[a] += dt * vy_[a];
      z_[a] += dt * vz_[a];
      const double v2 = vx_[a] * vx_[a] + vy_[a] * vy_[a] + vz_[a] * vz_[a];
      double move2 = dt * dt * v2 / (radius_[a] * radius_[a]);
      if (!(move2 <= std::numeric_limits<double>::max())) move2 = std::numeric_limits<double>::infinity();
      mover = farther(mover, MoveMax{move2, a});
    }
    const double dx = x_[a] - xb_[a], dy = y_[a] - yb_[a], dz = z_[a] - zb_[a];
    max_d2 = std::max(max_d2, dx * dx + dy * dy + dz * dz);
  }
  return {max_d2, std::max(mover.move2, 0.0), mover.index == 0xffffffffu ? 0u : mover.index};
}

// Force of each plate on the sample along y: the glue springs' pull, or in rigid mode what the
// plate must supply so that its particles follow it (m a - internal force).
void System::update_plate_forces() {
  const auto start = Clock::now();
  std::array<double, 3> force{};
  const double plate_u[3] = {0.0, 0.0, top_.displacement};
  const double plate_a[3] = {0.0, 0.0, top_.acceleration};
  for (const std::uint32_t a : glued_) {
    const std::uint8_t plate = plate_[a];
    if (params_.glue_mode == GlueMode::spring)
      force[plate] += params_.glue_stiffness * (ay_[a] + plate_u[plate] - y_[a]);
    else
      force[plate] += mass_[a] * plate_a[plate] - fy_[a];
  }
  plate_force_ = force;
  times_.plates += seconds_since(start);
}

// Applies the flagged breaks in bond order: the bond stops acting, its energy at this
// configuration leaves the ledger as released energy (less any contact energy the pair gains),
// and the pair becomes a contact candidate.
void System::apply_breaks() {
  const auto start = Clock::now();
  flagged_merged_.clear();
  for (auto& flags : flagged_) {
    flagged_merged_.insert(flagged_merged_.end(), flags.begin(), flags.end());
    flags.clear();
  }
  std::sort(flagged_merged_.begin(), flagged_merged_.end());
  for (const std::uint32_t b : flagged_merged_) break_one(b);
  times_.breaks += seconds_since(start);
}

void System::break_one(std::uint32_t b) {
  const std::uint32_t i = bond_i_[b], j = bond_j_[b];
  const double dx = x_[j] - x_[i], dy = y_[j] - y_[i], dz = z_[j] - z_[i];
  const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
  const HookeBond bond{bond_k_[b], bond_r0_[b]};
  const LinearContact contact{params_.contact_stiffness, radius_[i] + radius_[j]};
  // The bond acted in the previous kick and not in this one, so for the integrator it vanished
  // half a step ago: its energy there (r moved back by half a step of the pair's relative
  // velocity) is what leaves the ledger. Using the energy at r instead would leave an O(dt) gap.
  const double closing = ((vx_[j] - vx_[i]) * dx + (vy_[j] - vy_[i]) * dy + (vz_[j] - vz_[i]) * dz) / r;
  const double r_break = r - last_half_dt_ * closing;
  const double energy = bond.energy(r_break) - contact.energy(r);
  intact_[b] = 0;
  --intact_count_;
  // Swap the link with the particle's last intact one and shrink the intact range.
  for (const std::uint32_t from : {i, j}) {
    const std::uint32_t last = link_start_[from] + link_count_[from] - 1;
    for (std::uint32_t l = link_start_[from]; l <= last; ++l)
      if (link_bond_[l] == b) {
        std::swap(link_other_[l], link_other_[last]);
        std::swap(link_bond_[l], link_bond_[last]);
        std::swap(link_r0_[l], link_r0_[last]);
        std::swap(link_k_[l], link_k_[last]);
        std::swap(link_limit_[l], link_limit_[last]);
        --link_count_[from];
        break;
      }
  }
  add_neighbour(i, j);
  add_neighbour(j, i);
  released_ += energy;
  const std::uint32_t si = sample_of_storage_[i], sj = sample_of_storage_[j];
  events_.push_back({step_,
                     b,
                     std::min(si, sj),
                     std::max(si, sj),
                     {0.5 * (x_[i] + x_[j]), 0.5 * (y_[i] + y_[j]), 0.5 * (z_[i] + z_[j])},
                     bond_r0_[b],
                     bond.stretch(r),
                     energy});
}

void System::break_bond(std::size_t bond) {
  if (!intact_[bond]) return;
  break_one(static_cast<std::uint32_t>(bond));
  forces_stale_ = true;
}

void System::step(double dt, const PlateMotion& top) {
  if (forces_stale_) {  // bonds were broken by hand since the last force pass
    compute_forces(0.0);
    update_plate_forces();
    apply_breaks();
    forces_stale_ = false;
  }
  const double force_before = plate_force_[plate_top];
  const double u_before = top_.displacement;
  auto start = Clock::now();
  top_ = top;
  const DriftResult drift = params_.damping > 0.0 ? kick_drift<true>(dt) : kick_drift<false>(dt);
  last_move_ = {std::sqrt(drift.move2), sample_of_storage_[drift.mover]};
  times_.integrate += seconds_since(start);
  time_ += dt;
  ++step_;
  if (!(drift.max_d2 <= 0.25 * params_.skin * params_.skin)) rebuild_neighbours();
  compute_forces(0.5 * dt);
  update_plate_forces();
  last_half_dt_ = 0.5 * dt;
  apply_breaks();
  last_half_dt_ = 0.0;
  // Trapezoid rule for the plate work, consistent with the velocity-Verlet energy to O(dt^2).
  plate_work_ += 0.5 * (force_before + plate_force_[plate_top]) * (top_.displacement - u_before);
  if (params_.damping > 0.0)
    damped_ = std::accumulate(damped_per_particle_.begin(), damped_per_particle_.end(), 0.0);
}

Energies System::energies() const {
  const std::uint32_t n = static_cast<std::uint32_t>(x_.size());
  const double kg = params_.glue_mode == GlueMode::spring ? params_.glue_stiffness : 0.0;
  const double plate_u[3] = {0.0, 0.0, top_.displacement};
  // Per-particle values, then a serial sum in storage order: independent of the thread count.
  std::vector<std::array<double, 4>> per(n);
  std::vector<std::uint32_t> contacts(n);
#pragma omp parallel for schedule(static) if (parallel_)
  for (std::uint32_t a = 0; a < n; ++a) {
    double elastic = 0.0, contact = 0.0;
    std::uint32_t count = 0;
    for (std::uint32_t l = link_start_[a]; l < link_start_[a] + link_count_[a]; ++l) {
      const std::uint32_t b = link_other_[l];
      if (b < a) continue;
      const double dx = x_[b] - x_[a], dy = y_[b] - y_[a], dz = z_[b] - z_[a];
      elastic += HookeBond{link_k_[l], link_r0_[l]}.energy(std::sqrt(dx * dx + dy * dy + dz * dz));
    }
    for (std::uint32_t p = nb_start_[a]; p < nb_start_[a] + nb_count_[a]; ++p) {
      const std::uint32_t b = nb_[p];
      if (b < a) continue;
      const double dx = x_[b] - x_[a], dy = y_[b] - y_[a], dz = z_[b] - z_[a];
      const LinearContact law{params_.contact_stiffness, radius_[a] + radius_[b]};
      const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
      if (r < law.touch) {
        contact += law.energy(r);
        ++count;
      }
    }
    double glue = 0.0;
    if (plate_[a] != plate_none)
      glue = GlueSpring{kg}.energy(x_[a] - ax_[a], y_[a] - ay_[a] - plate_u[plate_[a]], z_[a] - az_[a]);
    const double kinetic = 0.5 * mass_[a] * (vx_[a] * vx_[a] + vy_[a] * vy_[a] + vz_[a] * vz_[a]);
    per[a] = {elastic, kinetic, contact, glue};
    contacts[a] = count;
  }
  Energies e;
  for (std::uint32_t a = 0; a < n; ++a) {
    e.elastic += per[a][0];
    e.kinetic += per[a][1];
    e.contact += per[a][2];
    e.glue += per[a][3];
    e.contacts += contacts[a];
  }
  return e;
}

EngineState System::save_state() const {
  EngineState s;
  s.step = step_;
  s.time = time_;
  s.top = top_;
  s.plate_force = plate_force_;
  s.plate_work = plate_work_;
  s.released = released_;
  s.damped = damped_;
  s.neighbour_rebuilds = rebuilds_;
  s.forces_stale = forces_stale_;
  s.stage_times = times_;
  s.sample_of_storage = sample_of_storage_;
  s.x = x_, s.y = y_, s.z = z_;
  s.vx = vx_, s.vy = vy_, s.vz = vz_;
  s.fx = fx_, s.fy = fy_, s.fz = fz_;
  s.xb = xb_, s.yb = yb_, s.zb = zb_;
  s.damped_per_particle = damped_per_particle_;
  s.intact = intact_;
  s.link_count = link_count_;
  s.link_bond = link_bond_;
  s.nb_start = nb_start_;
  s.nb_count = nb_count_;
  // Slots past each slice's used part hold leftovers of older lists that are never read: zero
  // them so that equal states give equal checkpoint bytes.
  s.nb.assign(nb_.size(), 0);
  for (std::size_t a = 0; a < x_.size(); ++a)
    std::copy_n(nb_.begin() + nb_start_[a], nb_count_[a], s.nb.begin() + nb_start_[a]);
  return s;
}

void System::restore_state(const EngineState& s, const std::string& source) {
  const std::size_t n = x_.size(), bonds = bond_i_.size();
  const auto fail = [&](const std::string& field, const std::string& problem) {
    throw InputError(source + ": " + field, problem,
                     "resume with the sample and config the checkpoint was written with, or use an older "
                     "checkpoint");
  };
  const auto require_size = [&](const std::string& field, std::size_t size, std::size_t expected) {
    if (size != expected)
      fail(field, "holds " + std::to_string(size) + " values where this run has " + std::to_string(expected));
  };
  if (s.sample_of_storage != sample_of_storage_)
    fail("sample_of_storage", "the particle order differs from this sample's (another sample?)");
  const std::pair<const char*, const std::vector<double>*> particle_fields[] = {
      {"x", &s.x},   {"y", &s.y},   {"z", &s.z},   {"vx", &s.vx}, {"vy", &s.vy},
      {"vz", &s.vz}, {"fx", &s.fx}, {"fy", &s.fy}, {"fz", &s.fz}, {"xb", &s.xb},
      {"yb", &s.yb}, {"zb", &s.zb}, {"damped_per_particle", &s.damped_per_particle}};
  for (const auto& [name, values] : particle_fields) require_size(name, values->size(), n);
  require_size("intact", s.intact.size(), bonds);
  require_size("link_count", s.link_count.size(), n);
  require_size("link_bond", s.link_bond.size(), link_bond_.size());
  require_size("nb_start", s.nb_start.size(), n + 1);
  require_size("nb_count", s.nb_count.size(), n);

  std::size_t intact = 0;
  for (std::size_t b = 0; b < bonds; ++b) {
    if (s.intact[b] > 1) fail("intact", "bond " + std::to_string(b) + " has flag " + std::to_string(s.intact[b]));
    intact += s.intact[b];
  }
  // Each particle's slice must hold its own bonds (in any order), the intact ones first.
  std::vector<std::uint32_t> mine, theirs;
  for (std::size_t a = 0; a < n; ++a) {
    const std::uint32_t begin = link_start_[a], end = link_start_[a + 1];
    if (s.link_count[a] > end - begin)
      fail("link_count", "particle slot " + std::to_string(a) + " counts more links than it has");
    mine.assign(link_bond_.begin() + begin, link_bond_.begin() + end);
    theirs.assign(s.link_bond.begin() + begin, s.link_bond.begin() + end);
    std::sort(mine.begin(), mine.end());
    std::sort(theirs.begin(), theirs.end());
    if (mine != theirs) fail("link_bond", "particle slot " + std::to_string(a) + " lists bonds it does not have");
    for (std::uint32_t l = begin; l < end; ++l)
      if ((l < begin + s.link_count[a]) != (s.intact[s.link_bond[l]] != 0))
        fail("link_count", "particle slot " + std::to_string(a) + " disagrees with the intact flags");
  }
  if (s.nb_start[0] != 0) fail("nb_start", "does not start at 0");
  for (std::size_t a = 0; a < n; ++a) {
    if (s.nb_start[a + 1] < s.nb_start[a]) fail("nb_start", "decreases at particle slot " + std::to_string(a));
    if (s.nb_count[a] > s.nb_start[a + 1] - s.nb_start[a])
      fail("nb_count", "particle slot " + std::to_string(a) + " overflows its neighbour slice");
  }
  require_size("nb", s.nb.size(), s.nb_start[n]);
  for (std::size_t a = 0; a < n; ++a)
    for (std::uint32_t p = s.nb_start[a]; p < s.nb_start[a] + s.nb_count[a]; ++p)
      if (s.nb[p] >= n || s.nb[p] == a)
        fail("nb", "particle slot " + std::to_string(a) + " has an invalid neighbour");

  step_ = s.step;
  time_ = s.time;
  top_ = s.top;
  plate_force_ = s.plate_force;
  plate_work_ = s.plate_work;
  released_ = s.released;
  damped_ = s.damped;
  rebuilds_ = s.neighbour_rebuilds;
  forces_stale_ = s.forces_stale;
  times_ = s.stage_times;
  x_ = s.x, y_ = s.y, z_ = s.z;
  vx_ = s.vx, vy_ = s.vy, vz_ = s.vz;
  fx_ = s.fx, fy_ = s.fy, fz_ = s.fz;
  xb_ = s.xb, yb_ = s.yb, zb_ = s.zb;
  damped_per_particle_ = s.damped_per_particle;
  intact_ = s.intact;
  intact_count_ = intact;
  link_count_ = s.link_count;
  for (std::uint32_t a = 0; a < n; ++a)
    for (std::uint32_t l = link_start_[a]; l < link_start_[a + 1]; ++l) set_link(l, a, s.link_bond[l]);
  nb_start_ = s.nb_start;
  nb_count_ = s.nb_count;
  nb_ = s.nb;
  events_.clear();
  last_move_ = {};
}

Vec3 System::position(std::size_t sample_index) const {
  const auto a = storage_of_sample_[sample_index];
  return {x_[a], y_[a], z_[a]};
}

Vec3 System::velocity(std::size_t sample_index) const {
  const auto a = storage_of_sample_[sample_index];
  return {vx_[a], vy_[a], vz_[a]};
}

void System::set_velocity(std::size_t sample_index, const Vec3& v) {
  const auto a = storage_of_sample_[sample_index];
  vx_[a] = v.x;
  vy_[a] = v.y;
  vz_[a] = v.z;
}

double System::bond_extension(std::size_t bond) const {
  if (!intact_[bond]) return std::numeric_limits<double>::quiet_NaN();
  const auto i = bond_i_[bond], j = bond_j_[bond];
  const double dx = x_[j] - x_[i], dy = y_[j] - y_[i], dz = z_[j] - z_[i];
  return std::sqrt(dx * dx + dy * dy + dz * dz) - bond_r0_[bond];
}

std::uint64_t System::state_hash() const {
  Fnv1a h;
  for (const std::uint32_t a : storage_of_sample_)
    for (double v : {x_[a], y_[a], z_[a], vx_[a], vy_[a], vz_[a]}) h.add_value(v);
  return h.hash;
}

std::size_t System::sample_index_of_largest_speed() const {
  std::size_t best = 0;
  double best_v2 = -1.0;
  for (std::size_t a = 0; a < x_.size(); ++a) {
    const double v2 = vx_[a] * vx_[a] + vy_[a] * vy_[a] + vz_[a] * vz_[a];
    if (!(v2 <= best_v2)) {  // NaN wins: it is the particle to report
      best = a;
      best_v2 = v2;
      if (std::isnan(v2)) break;
    }
  }
  return sample_of_storage_[best];
}

}  // namespace rupture::dem
