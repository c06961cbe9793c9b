#include "fbm/bundle.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

#include "core/random.hpp"

namespace rupture::fbm {

namespace {

constexpr std::size_t draw_block = std::size_t{1} << 16;
// Load-controlled states kept per output point before resampling.
constexpr std::size_t states_kept = 8;

// Keeps an evenly spaced subset (in state index) of a sequence of unknown length: every
// stride-th state, the stride doubling whenever more than `limit` are held. Memory stays
// O(limit) even for 10^7 load steps.
class Thinner {
 public:
  explicit Thinner(std::size_t limit) : limit_(std::max<std::size_t>(limit, 3)) {}
  void add(const CurvePoint& point) {
    if (count_++ % stride_ == 0) {
      kept_.push_back(point);
      if (kept_.size() > limit_) {
        std::size_t out = 0;
        for (std::size_t i = 0; i < kept_.size(); i += 2) kept_[out++] = kept_[i];
        kept_.resize(out);
        stride_ *= 2;
      }
    }
    last_ = point;
  }
  // The kept states plus the last one.
  std::vector<CurvePoint> finish() {
    if (count_ > 0 && (count_ - 1) % stride_ != 0) kept_.push_back(last_);
    return std::move(kept_);
  }

 private:
  std::size_t limit_, stride_ = 1, count_ = 0;
  std::vector<CurvePoint> kept_;
  CurvePoint last_{};
};

// Running force maximum over the states of a load-controlled run. E_e is not tracked: the
// bundle collapses at x_c, before its elastic-energy maximum.
struct RunningMaxima {
  Characteristics c;
  void add(const CurvePoint& p) {
    if (p.F > c.F_c) {
      c.F_c = p.F;
      c.x_c = p.x;
      c.E_d_at_x_c = p.E_d;
    }
  }
};

// A load-controlled run's stable states resampled onto `points` equally spaced strains from 0 to
// the last state by linear interpolation (the origin added as the unloaded state), so that the
// curve has the same shape as every other curve and a difference quotient sees no uneven steps.
std::vector<CurvePoint> resample_uniform(std::vector<CurvePoint> states, std::size_t points) {
  states.insert(states.begin(), CurvePoint{0, 0, 0, 0, 0, 0});
  points = std::max<std::size_t>(points, 3);
  std::vector<CurvePoint> curve;
  curve.reserve(points);
  const double x_end = states.back().x;
  std::size_t j = 0;
  for (std::size_t i = 0; i < points; ++i) {
    const double x =
        i + 1 == points ? x_end : x_end * static_cast<double>(i) / static_cast<double>(points - 1);
    while (j + 2 < states.size() && states[j + 1].x < x) ++j;
    const CurvePoint& a = states[j];
    const CurvePoint& b = states[j + 1];
    const double w = b.x > a.x ? std::clamp((x - a.x) / (b.x - a.x), 0.0, 1.0) : 1.0;
    const auto mix = [w](double u, double v) { return u + w * (v - u); };
    curve.push_back({x, mix(a.F, b.F), mix(a.E_e, b.E_e), mix(a.E_d, b.E_d), 0.0,
                     mix(a.broken_fraction, b.broken_fraction)});
  }
  return curve;
}

// x_p and ℰ_max of a sampled curve: vertex of the least-squares parabola through the samples
// within ±10 % of the strain of the largest sample, which averages away the counting noise of the
// difference quotient; falls back to the largest sample when the fit has no maximum inside.
void measure_precursor(const std::vector<CurvePoint>& curve, Characteristics& c) {
  if (curve.empty()) return;
  const auto top = std::max_element(
      curve.begin(), curve.end(), [](const CurvePoint& a, const CurvePoint& b) { return a.Erate < b.Erate; });
  c.x_p = top->x;
  c.Erate_max = top->Erate;
  const double lo = 0.9 * top->x, hi = 1.1 * top->x, x0 = top->x;
  // Normal equations of y = a + b u + q u², u = x - x0, summed in curve order.
  double s[5] = {0, 0, 0, 0, 0}, t[3] = {0, 0, 0};
  std::size_t n = 0;
  for (const auto& p : curve) {
    if (p.x < lo || p.x > hi) continue;
    const double u = p.x - x0;
    double power = 1.0;
    for (int k = 0; k < 5; ++k) {
      s[k] += power;
      if (k < 3) t[k] += power * p.Erate;
      power *= u;
    }
    ++n;
  }
  if (n < 5) return;
  // Solve the 3x3 system by Cramer's rule.
  const auto det3 = [](double a, double b, double cc, double d, double e, double f, double g, double h,
                       double i) { return a * (e * i - f * h) - b * (d * i - f * g) + cc * (d * h - e * g); };
  const double d = det3(s[0], s[1], s[2], s[1], s[2], s[3], s[2], s[3], s[4]);
  if (d == 0.0) return;
  const double a = det3(t[0], s[1], s[2], t[1], s[2], s[3], t[2], s[3], s[4]) / d;
  const double b = det3(s[0], t[0], s[2], s[1], t[1], s[3], s[2], t[2], s[4]) / d;
  const double q = det3(s[0], s[1], t[0], s[1], s[2], t[1], s[2], s[3], t[2]) / d;
  if (!(q < 0.0)) return;
  const double u = -b / (2.0 * q);
  if (x0 + u < lo || x0 + u > hi) return;
  c.x_p = x0 + u;
  c.Erate_max = a + b * u + q * u * u;
}

BundleCurve finish_curve(std::vector<CurvePoint> curve, Characteristics measured) {
  fill_energy_rate(curve);
  measure_precursor(curve, measured);
  derive_ratios(measured);
  return {std::move(curve), measured};
}

}  // namespace

std::vector<double> draw_thresholds(const StrengthDistribution& distribution, std::size_t fibers,
                                    std::uint64_t seed) {
  std::vector<double> thresholds(fibers);
  const std::size_t blocks = (fibers + draw_block - 1) / draw_block;
  // Each block has its own random stream, so the result does not depend on the thread count.
#pragma omp parallel for schedule(static)
  for (std::size_t block = 0; block < blocks; ++block) {
    Rng rng(seed, RandomStream::fbm_thresholds, block);
    const std::size_t end = std::min(fibers, (block + 1) * draw_block);
    for (std::size_t i = block * draw_block; i < end; ++i)
      thresholds[i] = distribution.quantile(rng.uniform01());
  }
  return thresholds;
}

void fill_energy_rate(std::vector<CurvePoint>& curve) {
  const std::size_t n = curve.size();
  if (n < 2) {
    for (auto& p : curve) p.Erate = 0.0;
    return;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
    const double dx = curve[b].x - curve[a].x;
    curve[i].Erate = dx != 0.0 ? (curve[b].E_e - curve[a].E_e) / dx : 0.0;
  }
}

BundleCurve strain_controlled(std::vector<double> thresholds, std::size_t points) {
  std::sort(thresholds.begin(), thresholds.end());
  const std::size_t n = thresholds.size();
  const double inv_n = 1.0 / static_cast<double>(n);
  // Exact maxima: F and E_e peak just before a fiber breaks, at x = t_k with N - k fibers intact
  // (the first of equal thresholds gives the right count, later ones lower values).
  Characteristics c;
  double damage = 0.0;  // Σ t_i² over broken fibers
  for (std::size_t k = 0; k < n; ++k) {
    const double x = thresholds[k], intact = static_cast<double>(n - k) * inv_n;
    if (x * intact > c.F_c) {
      c.F_c = x * intact;
      c.x_c = x;
      c.E_d_at_x_c = 0.5 * damage * inv_n;
    }
    if (0.5 * x * x * intact > c.E_max.value_or(0.0)) {
      c.E_max = 0.5 * x * x * intact;
      c.x_m = x;
    }
    damage += x * x;
  }
  // The sampled curve: fibers with t < x are broken.
  points = std::max<std::size_t>(points, 3);
  std::vector<CurvePoint> curve;
  curve.reserve(points);
  const double x_end = thresholds.back();
  std::size_t broken = 0;
  damage = 0.0;
  for (std::size_t i = 0; i < points; ++i) {
    const double x = x_end * static_cast<double>(i) / static_cast<double>(points - 1);
    while (broken < n && thresholds[broken] < x) {
      damage += thresholds[broken] * thresholds[broken];
      ++broken;
    }
    const double intact = static_cast<double>(n - broken) * inv_n;
    curve.push_back({x, x * intact, 0.5 * x * x * intact, 0.5 * damage * inv_n, 0.0,
                     static_cast<double>(broken) * inv_n});
  }
  return finish_curve(std::move(curve), c);
}

LoadControlled load_controlled_els(std::vector<double> thresholds, std::size_t points) {
  std::sort(thresholds.begin(), thresholds.end());
  const std::size_t n = thresholds.size();
  const double inv_n = 1.0 / static_cast<double>(n);
  LoadControlled run;
  Thinner thinner(states_kept * points);
  RunningMaxima maxima;
  double damage = 0.0;  // Σ (strain at breaking)² over broken fibers
  std::size_t k = 0;    // fibers broken so far: always the k weakest
  while (k < n) {
    // Raise the load until the weakest survivor breaks: total force F = t_k (N - k).
    const double force = thresholds[k] * static_cast<double>(n - k);
    const CurvePoint state{thresholds[k],        force * inv_n, 0.5 * thresholds[k] * force * inv_n,
                           0.5 * damage * inv_n, 0.0,           static_cast<double>(k) * inv_n};
    thinner.add(state);
    maxima.add(state);
    // Hold the load: fiber j breaks while its threshold is below the strain F / (N - j).
    damage += thresholds[k] * thresholds[k];
    std::size_t j = k + 1;
    while (j < n && thresholds[j] * static_cast<double>(n - j) < force) {
      const double strain = force / static_cast<double>(n - j);
      damage += strain * strain;
      ++j;
    }
    ++run.load_steps;
    if (j == n)
      run.final_burst = j - k;
    else
      ++run.burst_counts[j - k];
    k = j;
  }
  run.result = finish_curve(resample_uniform(thinner.finish(), points), maxima.c);
  return run;
}

LoadControlled load_controlled_lls(const std::vector<double>& thresholds, std::size_t points) {
  const std::size_t n = thresholds.size();
  const double inv_n = 1.0 / static_cast<double>(n);
  std::vector<std::size_t> left(n), right(n);
  std::vector<double> multiplier(n, 1.0);  // load of fiber i = multiplier[i] * σ
  std::vector<char> intact(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    left[i] = (i + n - 1) % n;
    right[i] = (i + 1) % n;
  }
  std::size_t survivors = n;
  // Σ multiplier² over survivors, for E_e = σ² Σ m² / 2. The multipliers are multiples of 1/2,
  // so this sum is exact in double arithmetic for N < 2^25.
  double sum_m2 = static_cast<double>(n);
  const auto load_multiplier = [&](std::size_t i) {
    if (survivors == 1) return static_cast<double>(n);
    const std::size_t gap_left = (i + n - left[i] - 1) % n, gap_right = (right[i] + n - i - 1) % n;
    return 1.0 + 0.5 * static_cast<double>(gap_left + gap_right);
  };
  // Min-heap of (breaking load per fiber σ = t_i / m_i, i); entries made stale by a later change
  // of m_i are skipped when popped.
  using Entry = std::pair<double, std::size_t>;
  std::vector<Entry> entries(n);
  for (std::size_t i = 0; i < n; ++i) entries[i] = {thresholds[i], i};
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap(std::greater<>{}, std::move(entries));

  LoadControlled run;
  Thinner thinner(states_kept * points);
  RunningMaxima maxima;
  double sigma = 0.0, damage = 0.0;
  std::vector<std::size_t> cascade;
  while (survivors > 0) {
    auto [key, first] = heap.top();
    heap.pop();
    if (!intact[first] || key != thresholds[first] / multiplier[first]) continue;
    sigma = std::max(sigma, key);
    const CurvePoint state{sigma * static_cast<double>(n) / static_cast<double>(survivors),
                           sigma,
                           0.5 * sigma * sigma * sum_m2 * inv_n,
                           0.5 * damage * inv_n,
                           0.0,
                           static_cast<double>(n - survivors) * inv_n};
    thinner.add(state);
    maxima.add(state);
    std::size_t burst = 0;
    cascade.assign(1, first);
    while (!cascade.empty()) {
      const std::size_t b = cascade.back();
      cascade.pop_back();
      if (!intact[b]) continue;
      intact[b] = 0;
      ++burst;
      const double load = multiplier[b] * sigma;
      damage += load * load;
      sum_m2 -= multiplier[b] * multiplier[b];
      if (--survivors == 0) break;
      const std::size_t l = left[b], r = right[b];
      right[l] = r;
      left[r] = l;
      // The two survivors bounding the grown broken run take its load (one if only one is left).
      const auto reload = [&](std::size_t s) {
        sum_m2 -= multiplier[s] * multiplier[s];
        multiplier[s] = load_multiplier(s);
        sum_m2 += multiplier[s] * multiplier[s];
        heap.emplace(thresholds[s] / multiplier[s], s);
        if (thresholds[s] < multiplier[s] * sigma) cascade.push_back(s);
      };
      reload(l);
      if (r != l) reload(r);
    }
    ++run.load_steps;
    if (survivors == 0)
      run.final_burst = burst;
    else
      ++run.burst_counts[burst];
  }
  run.result = finish_curve(resample_uniform(thinner.finish(), points), maxima.c);
  return run;
}

}  // namespace rupture::fbm
