#include "sample/generator.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include "core/error.hpp"
#include "core/morton.hpp"
#include "core/progress.hpp"
#include "core/units.hpp"
#include "rupture/version.hpp"
#include "sample/cell_grid.hpp"
#include "sample/checks.hpp"

namespace rupture {

using sample_detail::CellGrid;

// ---------------------------------------------------------------------------------------------
// Radius distribution

namespace {
const boost::math::normal_distribution<double> standard_normal(0.0, 1.0);
}

TruncatedLogNormal::TruncatedLogNormal(double r_min, double r_max, double median, double sigma)
    : r_min_(r_min), r_max_(r_max), log_median_(0.0), sigma_(sigma) {
  if (!(r_min > 0.0) || !(r_max > r_min))
    throw InputError("--r-min/--r-max",
                     fmt::format("radii must satisfy 0 < r_min < r_max (got {} and {} mm)", r_min, r_max),
                     "give r_min below r_max, both positive, in mm");
  if (!(median > 0.0) || !std::isfinite(median))
    throw InputError("--r-median", fmt::format("median radius must be positive (got {} mm)", median));
  if (!(sigma > 0.0) || !std::isfinite(sigma))
    throw InputError("--r-sigma", fmt::format("log-normal spread must be positive (got {})", sigma),
                     "give the standard deviation of ln r, e.g. 0.35");
  log_median_ = std::log(median);
  cdf_low_ = boost::math::cdf(standard_normal, (std::log(r_min) - log_median_) / sigma_);
  cdf_high_ = boost::math::cdf(standard_normal, (std::log(r_max) - log_median_) / sigma_);
  if (!(cdf_high_ > cdf_low_))
    throw InputError("--r-median",
                     fmt::format("the log-normal (median {} mm, sigma {}) has no probability in [{}, {}] mm",
                                 median, sigma, r_min, r_max),
                     "move the median into the radius range or widen sigma");
}

double TruncatedLogNormal::cdf(double r) const {
  if (r <= r_min_) return 0.0;
  if (r >= r_max_) return 1.0;
  const double c = boost::math::cdf(standard_normal, (std::log(r) - log_median_) / sigma_);
  return std::clamp((c - cdf_low_) / (cdf_high_ - cdf_low_), 0.0, 1.0);
}

double TruncatedLogNormal::quantile(double u) const {
  const double p = cdf_low_ + std::clamp(u, 0.0, 1.0) * (cdf_high_ - cdf_low_);
  if (p <= 0.0) return r_min_;
  if (p >= 1.0) return r_max_;
  const double r = std::exp(log_median_ + sigma_ * boost::math::quantile(standard_normal, p));
  return std::clamp(r, r_min_, r_max_);  // rounding must never leave the promised bounds
}

void validate(const PackingParams& p) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(p.size.x) || !positive(p.size.y) || !positive(p.size.z))
    throw InputError("--width/--height/--depth",
                     fmt::format("box {} x {} x {} mm is not a box", p.size.x, p.size.y, p.size.z),
                     "give three positive sizes in mm");
  [[maybe_unused]] const TruncatedLogNormal radii(p.r_min, p.r_max, p.r_median,
                                                  p.r_sigma);  // checks the radii
  const double smallest_side = std::min({p.size.x, p.size.y, p.size.z});
  if (2.0 * p.r_max > smallest_side)
    throw InputError("--r-max",
                     fmt::format("largest diameter {} mm does not fit the box's smallest side {} mm",
                                 2.0 * p.r_max, smallest_side),
                     "lower r_max or enlarge the box");
  if (!(p.bond_tolerance >= 0.0) || !std::isfinite(p.bond_tolerance))
    throw InputError("--bond-tolerance", fmt::format("must be >= 0 (got {})", p.bond_tolerance),
                     "give the largest bonded surface gap relative to the pair's mean radius, e.g. 0.1");
  if (!(p.density >= min_plausible_density && p.density <= max_plausible_density))
    throw InputError("--density",
                     fmt::format("{:g} g/mm^3 is outside the plausible [{:g}, {:g}] g/mm^3", p.density,
                                 min_plausible_density, max_plausible_density),
                     "give the density in g/mm^3 (water is 1e-3)");
  // A dense random packing fills about 60 % of the box: the count, roughly, at the median radius.
  const double volume = p.size.x * p.size.y * p.size.z;
  const double particles = 0.6 * volume / (4.0 / 3.0 * std::numbers::pi * std::pow(p.r_median, 3));
  if (particles > max_particles)
    throw InputError(
        "--width/--height/--depth",
        fmt::format("a {:g} mm^3 box of particles of median radius {:g} mm holds about {:.3g} particles (a "
                    "run of them "
                    "needs about {:.3g} GB); at most {:g} are generated",
                    volume, p.r_median, particles, particles * run_bytes_per_particle / 1e9, max_particles),
        "use a smaller box or larger radii");
  if (p.attempts_per_draw == 0 || p.draw_block == 0 || p.fill_block == 0)
    throw InputError("packing budget", "attempt and block sizes must be at least 1");
  if (!(p.min_drawn_rate >= 0.0 && p.min_drawn_rate <= 1.0))
    throw InputError("--drawn-rate", fmt::format("must lie in [0, 1] (got {})", p.min_drawn_rate));
  if (!(p.min_fill_rate > 0.0 && p.min_fill_rate <= 1.0))
    throw InputError("--fill-rate", fmt::format("must lie in (0, 1] (got {})", p.min_fill_rate),
                     "a rate of 0 would never stop filling");
}

// ---------------------------------------------------------------------------------------------
// Packing

namespace {

// A neighbour of a trial position: a sphere (centre, radius) or a box face (inward normal n and
// offset d: the face is n.x = d).
struct Obstacle {
  bool is_plane = false;
  Vec3 v;          // sphere centre or plane normal (mm or unit)
  double s = 0.0;  // sphere radius or plane offset (mm)
  double distance = 0.0;
};

struct Sphere {
  Vec3 centre;
  double radius;
};

using Row = Eigen::Vector4d;  // coefficients of (x, y, z, r)

// The tangency conditions as linear equations in y = (x, y, z, r): each obstacle against the
// first sphere obstacle (the reference; |x - c_k|^2 - |x - c_0|^2 = (R_k + r)^2 - (R_0 + r)^2 is
// linear), each face as n.x - r = d, and a fixed radius as r = R.
struct TangencySystem {
  std::array<Row, 4> rows;
  std::array<double, 4> rhs{};
  int equations = 0;
  int reference = -1;  // index of the reference sphere; -1: faces only
  Vec3 c0{};
  double r0 = 0.0;
};

TangencySystem tangency_system(const std::array<Obstacle, 4>& obstacles, int count,
                               std::optional<double> fixed_radius) {
  TangencySystem t;
  for (int k = 0; k < count; ++k)
    if (!obstacles[k].is_plane) {
      t.reference = k;
      break;
    }
  t.c0 = t.reference >= 0 ? obstacles[t.reference].v : Vec3{};
  t.r0 = t.reference >= 0 ? obstacles[t.reference].s : 0.0;
  int& n = t.equations;
  for (int k = 0; k < count; ++k) {
    if (k == t.reference) continue;
    const Obstacle& o = obstacles[k];
    if (o.is_plane) {
      t.rows[n] = Row(o.v.x, o.v.y, o.v.z, -1.0);
      t.rhs[n] = o.s;
    } else {
      const Vec3 dc = o.v - t.c0;
      t.rows[n] = Row(dc.x, dc.y, dc.z, o.s - t.r0);
      t.rhs[n] = 0.5 * (norm2(o.v) - norm2(t.c0) - o.s * o.s + t.r0 * t.r0);
    }
    ++n;
  }
  if (fixed_radius) {
    t.rows[n] = Row(0.0, 0.0, 0.0, 1.0);
    t.rhs[n] = *fixed_radius;
    ++n;
  }
  return t;
}

// Faces only: four equations, one solution if they are independent.
int solve_faces_only(const TangencySystem& t, std::array<Sphere, 2>& out) {
  if (t.equations != 4) return 0;
  Eigen::Matrix4d a;
  Eigen::Vector4d b;
  for (int k = 0; k < 4; ++k) a.row(k) = t.rows[k].transpose(), b[k] = t.rhs[k];
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(a);
  if (!lu.isInvertible()) return 0;
  const Eigen::Vector4d y = lu.solve(b);
  out[0] = {{y[0], y[1], y[2]}, y[3]};
  return 1;
}

// Three equations leave a line y = y0 + t w; the reference sphere's quadratic picks up to two
// points on it.
int solve_on_the_line(const TangencySystem& t, std::optional<double> fixed_radius,
                      std::array<Sphere, 2>& out) {
  if (t.equations != 3) return 0;
  Eigen::Matrix<double, 3, 4> a;
  Eigen::Vector3d b;
  for (int k = 0; k < 3; ++k) a.row(k) = t.rows[k].transpose(), b[k] = t.rhs[k];
  // Null direction w of a (generalised cross product) and the least-norm particular solution.
  Eigen::Vector4d w;
  for (int col = 0; col < 4; ++col) {
    Eigen::Matrix3d minor;
    for (int c = 0, m = 0; c < 4; ++c)
      if (c != col) minor.col(m++) = a.col(c);
    w[col] = ((col % 2) ? -1.0 : 1.0) * minor.determinant();
  }
  const Eigen::Matrix3d gram = a * a.transpose();
  Eigen::Matrix3d gram_inverse;
  bool invertible = false;
  gram.computeInverseWithCheck(gram_inverse, invertible, 1e-24);
  if (!invertible || w.norm() < 1e-14) return 0;
  const Eigen::Vector4d y0 = a.transpose() * (gram_inverse * b);

  // Quadratic in t for y = y0 + t w: |x - c0|^2 = (R0 + r)^2.
  const Vec3 wx{w[0], w[1], w[2]}, dx = Vec3{y0[0], y0[1], y0[2]} - t.c0;
  const double wr = w[3], rr = t.r0 + y0[3];
  const double qa = norm2(wx) - wr * wr, qb = 2.0 * (dot(wx, dx) - wr * rr), qc = norm2(dx) - rr * rr;
  std::array<double, 2> roots{};
  int found = 0;
  if (std::abs(qa) < 1e-14 * (norm2(wx) + wr * wr)) {
    if (std::abs(qb) < 1e-300) return 0;
    roots[found++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) return 0;
    const double sq = std::sqrt(disc);
    // Numerically stable pair of roots.
    const double q = -0.5 * (qb + std::copysign(sq, qb));
    roots[found++] = q / qa;
    if (q != 0.0) roots[found++] = qc / q;
  }
  int solutions = 0;
  for (int k = 0; k < found; ++k) {
    const Eigen::Vector4d y = y0 + roots[k] * w;
    if (!(t.r0 + y[3] > 0.0)) continue;
    out[solutions++] = {{y[0], y[1], y[2]}, fixed_radius ? *fixed_radius : y[3]};
  }
  return solutions;
}

// Spheres (centre x, radius r) touching every obstacle: externally for spheres (|x - c| = R + r),
// from the inside for faces (n.x - d = r). Coordinates are relative to the trial point, so the
// numbers stay small and the tangency is exact to ~1e-15 mm. Either all of the obstacles plus a
// fixed radius, or 4 obstacles and a free radius, give 3 linear equations plus one quadratic: up to
// two solutions.
int tangent_spheres(const std::array<Obstacle, 4>& obstacles, int count, std::optional<double> fixed_radius,
                    std::array<Sphere, 2>& out) {
  const TangencySystem t = tangency_system(obstacles, count, fixed_radius);
  return t.reference < 0 ? solve_faces_only(t, out) : solve_on_the_line(t, fixed_radius, out);
}

class Packer {
 public:
  Packer(const PackingParams& params, std::uint64_t seed)
      : params_(params),
        box_{{0.0, 0.0, 0.0}, params.size},
        grid_(box_, 2.0 * params.r_max),
        positions_rng_(seed, RandomStream::sample_packing),
        tolerance_(1e-9 * params.r_max) {
    // Faces as inward-facing planes n.x = d.
    faces_ = {{{true, {1, 0, 0}, box_.lower.x},
               {true, {-1, 0, 0}, -box_.upper.x},
               {true, {0, 1, 0}, box_.lower.y},
               {true, {0, -1, 0}, -box_.upper.y},
               {true, {0, 0, 1}, box_.lower.z},
               {true, {0, 0, -1}, -box_.upper.z}}};
  }

  // Tries one random position for a sphere of the given radius (phase 1) or of whatever radius the
  // gap allows (phase 2). Returns whether a sphere was placed.
  bool try_place(std::optional<double> radius) {
    ++positions_tried_;
    const Vec3 p{positions_rng_.uniform(box_.lower.x, box_.upper.x),
                 positions_rng_.uniform(box_.lower.y, box_.upper.y),
                 positions_rng_.uniform(box_.lower.z, box_.upper.z)};
    const int wanted = radius ? 3 : 4;
    std::array<Obstacle, 4> nearest;
    const int count = nearest_obstacles(p, wanted, nearest);
    if (count < wanted) return false;
    // Work relative to p (small numbers, exact tangency).
    for (int k = 0; k < count; ++k) {
      if (nearest[k].is_plane)
        nearest[k].s -= dot(nearest[k].v, p);
      else
        nearest[k].v -= p;
    }
    std::array<Sphere, 2> candidates;
    const int solutions = tangent_spheres(nearest, count, radius, candidates);
    // Prefer the solution nearer the trial point.
    if (solutions == 2 && norm2(candidates[1].centre) < norm2(candidates[0].centre))
      std::swap(candidates[0], candidates[1]);
    for (int k = 0; k < solutions; ++k) {
      Sphere s{candidates[k].centre + p, candidates[k].radius};
      if (fits(s)) return add(s);
    }
    // Phase 1 also seeds: a drawn sphere that fits where it was dropped stays there (this is what
    // starts the packing in an empty box, before any gap exists).
    if (radius && fits({p, *radius})) return add({p, *radius});
    return false;
  }

  const std::vector<Sphere>& spheres() const { return spheres_; }
  std::uint64_t positions_tried() const { return positions_tried_; }

 private:
  int nearest_obstacles(const Vec3& p, int wanted, std::array<Obstacle, 4>& nearest) const {
    int count = 0;
    const auto consider = [&](const Obstacle& o) {
      if (count == wanted && o.distance >= nearest[count - 1].distance) return;
      int k = count < wanted ? count++ : count - 1;
      while (k > 0 && nearest[k - 1].distance > o.distance) {
        nearest[k] = nearest[k - 1];
        --k;
      }
      nearest[k] = o;
    };
    for (Obstacle face : faces_) {
      face.distance = dot(face.v, p) - face.s;
      consider(face);
    }
    grid_.for_each_near(p, [&](std::uint32_t j) {
      const Sphere& s = spheres_[j];
      consider({false, s.centre, s.radius, norm(p - s.centre) - s.radius});
    });
    return count;
  }

  bool fits(const Sphere& s) const {
    if (!(s.radius >= params_.r_min - tolerance_ && s.radius <= params_.r_max + tolerance_)) return false;
    const Vec3 lo = box_.lower, hi = box_.upper;
    const double r = s.radius - tolerance_;
    if (s.centre.x - r < lo.x || s.centre.y - r < lo.y || s.centre.z - r < lo.z || s.centre.x + r > hi.x ||
        s.centre.y + r > hi.y || s.centre.z + r > hi.z)
      return false;
    bool free = true;
    grid_.for_each_near(s.centre, [&](std::uint32_t j) {
      const double reach = s.radius + spheres_[j].radius - tolerance_;
      if (free && norm2(s.centre - spheres_[j].centre) < reach * reach) free = false;
    });
    return free;
  }

  bool add(Sphere s) {
    // A fitted radius may exceed its bounds by the round-off tolerance; clamp it back inside.
    s.radius = std::clamp(s.radius, params_.r_min, params_.r_max);
    grid_.insert(static_cast<std::uint32_t>(spheres_.size()), s.centre);
    spheres_.push_back(s);
    return true;
  }

  PackingParams params_;
  Box box_;
  CellGrid grid_;
  Rng positions_rng_;
  double tolerance_;  // mm: round-off allowance for exact tangency
  std::array<Obstacle, 6> faces_;
  std::vector<Sphere> spheres_;
  std::uint64_t positions_tried_ = 0;
};

// Phase 1: radii drawn from the log-normal, each placed touching three neighbours (or dropped
// where it falls while the box is still empty); a draw that finds no place is discarded. Stops when
// a block of draws places too few.
template <class Show>
void place_drawn_radii(Packer& packer, const TruncatedLogNormal& radii, Rng& radius_rng,
                       const PackingParams& params, GenerationReport& rep, double& solid_volume,
                       const Show& show) {
  bool discarded_any = false;
  for (std::uint32_t placed_in_block = params.draw_block;
       placed_in_block >= params.min_drawn_rate * params.draw_block;) {
    placed_in_block = 0;
    for (std::uint32_t d = 0; d < params.draw_block; ++d) {
      const double r = radii.draw(radius_rng);
      ++rep.draws;
      bool placed = false;
      for (std::uint32_t attempt = 0; attempt < params.attempts_per_draw && !placed; ++attempt)
        placed = packer.try_place(r);
      if (placed) {
        ++placed_in_block;
        ++rep.drawn_placed;
        solid_volume += units::sphere_volume(r);
        if (!discarded_any) rep.radii_before_first_discard.push_back(r);
      } else {
        discarded_any = true;
      }
      show("drawn radii");
    }
  }
}

// Phase 2: fill the remaining gaps with spheres touching four neighbours (radius set by the gap,
// kept only inside [r_min, r_max]) until gaps have become too rare to find.
template <class Show>
void fill_gaps(Packer& packer, const PackingParams& params, GenerationReport& rep, double& solid_volume,
               const Show& show) {
  for (std::uint32_t filled_in_block = params.fill_block;
       filled_in_block >= params.min_fill_rate * params.fill_block;) {
    filled_in_block = 0;
    for (std::uint32_t t = 0; t < params.fill_block; ++t) {
      if (packer.try_place(std::nullopt)) {
        ++filled_in_block;
        ++rep.gap_filled;
        solid_volume += units::sphere_volume(packer.spheres().back().radius);
      }
      show("gap filling");
    }
  }
}

// The packed spheres as a sample: stored in spatial order (ids follow), bonded, with glued layers
// and the generator's settings as provenance.
Sample sample_of(const std::vector<Sphere>& spheres, const PackingParams& params, std::uint64_t seed) {
  Sample sample;
  sample.box = {{0.0, 0.0, 0.0}, params.size};
  sample.density = params.density;
  sample.id.resize(spheres.size());
  sample.position.reserve(spheres.size());
  sample.radius.reserve(spheres.size());
  for (const Sphere& s : spheres) {
    sample.position.push_back(s.centre);
    sample.radius.push_back(s.radius);
  }
  sample.group.assign(spheres.size(), ParticleGroup::free);
  sort_spatially(sample, 2.0 * params.r_max);
  std::iota(sample.id.begin(), sample.id.end(), std::int64_t{0});  // id = storage index after sorting
  make_bonds(sample, params.bond_tolerance);
  assign_glued_layers(sample);
  sample.provenance = {
      fmt::format("generated by rupture {}", version_string),
      fmt::format(
          "generator: insertion packing, seed {}, box {} x {} x {} mm, radii log-normal median {} mm sigma "
          "{} "
          "truncated to [{}, {}] mm, bond tolerance {}, attempts per draw {}, drawn rate {} per {} draws, "
          "fill rate {} per {} positions",
          seed, params.size.x, params.size.y, params.size.z, params.r_median, params.r_sigma, params.r_min,
          params.r_max, params.bond_tolerance, params.attempts_per_draw, params.min_drawn_rate,
          params.draw_block, params.min_fill_rate, params.fill_block)};
  return sample;
}

}  // namespace

Sample generate_sample(const PackingParams& params, std::uint64_t seed, GenerationReport* report) {
  validate(params);
  const TruncatedLogNormal radii(params.r_min, params.r_max, params.r_median, params.r_sigma);
  Rng radius_rng(seed, RandomStream::sample_radii);
  Packer packer(params, seed);
  GenerationReport local;
  GenerationReport& rep = report ? *report : local;
  rep = {};

  const double box_volume = params.size.x * params.size.y * params.size.z;
  Progress progress("sample: positions tried");  // total unknown: the packing decides when it is full
  double solid_volume = 0.0;                     // mm^3
  const auto show = [&](const char* phase) {
    progress.update_with(static_cast<double>(packer.positions_tried()), [&] {
      return fmt::format("{}: {} particles, solid fraction {:.3f}", phase, packer.spheres().size(),
                         solid_volume / box_volume);
    });
  };
  place_drawn_radii(packer, radii, radius_rng, params, rep, solid_volume, show);
  rep.solid_fraction_drawn = solid_volume / box_volume;
  fill_gaps(packer, params, rep, solid_volume, show);
  progress.finish();
  rep.positions_tried = packer.positions_tried();
  return sample_of(packer.spheres(), params, seed);
}

void make_bonds(Sample& sample, double tolerance) {
  sample.bonds.clear();
  const std::size_t n = sample.size();
  if (n == 0) return;
  const double r_max = *std::max_element(sample.radius.begin(), sample.radius.end());
  CellGrid grid(sample.box, 2.0 * r_max * (1.0 + 0.5 * tolerance));
  for (std::uint32_t i = 0; i < n; ++i) grid.insert(i, sample.position[i]);
  // Bonds of particle i with every j > i in reach. Two passes (count, then fill into each particle's
  // own slice), each parallel over i: the result does not depend on the number of threads.
  const auto for_each_partner = [&](std::uint32_t i, auto&& use) {
    const Vec3 pi = sample.position[i];
    const double ri = sample.radius[i];
    grid.for_each_near(pi, [&](std::uint32_t j) {
      if (j <= i) return;
      const double reach = (ri + sample.radius[j]) * (1.0 + 0.5 * tolerance);
      const Vec3 d = sample.position[j] - pi;
      if (norm2(d) < reach * reach) use(j, norm(d));
    });
  };
  std::vector<std::size_t> start(n + 1, 0);
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i)
    for_each_partner(static_cast<std::uint32_t>(i),
                     [&](std::uint32_t, double) { ++start[static_cast<std::size_t>(i) + 1]; });
  std::partial_sum(start.begin(), start.end(), start.begin());
  sample.bonds.resize(start[n]);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    const auto first = start[static_cast<std::size_t>(i)];
    auto slot = first;
    const auto u = static_cast<std::uint32_t>(i);
    for_each_partner(u, [&](std::uint32_t j, double distance) { sample.bonds[slot++] = {u, j, distance}; });
    std::sort(sample.bonds.begin() + static_cast<std::ptrdiff_t>(first),
              sample.bonds.begin() + static_cast<std::ptrdiff_t>(slot),
              [](const Bond& a, const Bond& b) { return a.j < b.j; });
  }
}

double default_glue_depth(const Sample& sample) {
  return sample.radius.empty() ? 0.0 : *std::min_element(sample.radius.begin(), sample.radius.end());
}

void assign_glued_layers(Sample& sample, double depth) {
  sample.group.assign(sample.size(), ParticleGroup::free);
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const double below = sample.position[k].y - sample.radius[k] - sample.box.lower.y;
    const double above = sample.box.upper.y - sample.position[k].y - sample.radius[k];
    if (below <= depth && below <= above)
      sample.group[k] = ParticleGroup::bottom;
    else if (above <= depth)
      sample.group[k] = ParticleGroup::top;
  }
}

void assign_glued_layers(Sample& sample) { assign_glued_layers(sample, default_glue_depth(sample)); }

void sort_spatially(Sample& sample, double cell_size) {
  const std::size_t n = sample.size();
  const CellGrid grid(sample.box, cell_size);
  std::vector<std::uint64_t> key(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto c = grid.coords(sample.position[k]);
    key[k] = morton_key(static_cast<std::uint64_t>(c[0]), static_cast<std::uint64_t>(c[1]),
                        static_cast<std::uint64_t>(c[2]));
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
  std::vector<std::uint32_t> new_index(n);
  for (std::uint32_t k = 0; k < n; ++k) new_index[order[k]] = k;
  const auto permute = [&](auto& values) {
    if (values.size() != n) return;
    auto old = values;
    for (std::size_t k = 0; k < n; ++k) values[k] = old[order[k]];
  };
  permute(sample.id);
  permute(sample.position);
  permute(sample.radius);
  permute(sample.group);
  for (Bond& b : sample.bonds) {
    auto i = new_index[b.i], j = new_index[b.j];
    b.i = std::min(i, j);
    b.j = std::max(i, j);
  }
  std::sort(sample.bonds.begin(), sample.bonds.end(),
            [](const Bond& a, const Bond& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
}

}  // namespace rupture
