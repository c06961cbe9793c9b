#include "analysis/bootstrap.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>

#include "analysis/filters.hpp"
#include "core/random.hpp"

namespace rupture::analysis {

namespace {

constexpr int scales[] = {1, 2, 3, 4, 6, 8};  // lags L of the structure function
// The shortest span whose structure function is read: the longest lag on both sides of 17 samples.
constexpr std::size_t shortest_span = 4 * static_cast<std::size_t>(scales[std::size(scales) - 1]) + 1;
static_assert(shortest_span == shortest_noise_span);

// S(L) = mean((y[i+L] − 2y[i] + y[i−L])²) over [low, high] for each L in `scales`, leaving out
// values above 10 robust sd (a sudden drop at failure is no noise). Also keeps the L = 1 values,
// for the correlation of F with E_e.
struct StructureFunction {
  std::vector<double> s;   // one per scale
  std::vector<double> d1;  // second differences at L = 1 (NaN where left out)
};

constexpr std::size_t outlier_neighbourhood = 32;  // OutlierScale::local

// Marks the second differences beyond 10 robust sd as left out (NaN), the sd read as `outliers` says.
void leave_out_outliers(std::span<double> d, OutlierScale outliers) {
  if (outliers == OutlierScale::span) {
    const double limit = d.empty() ? 0.0 : 10.0 * robust_scale(d);
    for (auto& v : d)
      if (limit > 0.0 && std::abs(v) > limit) v = std::nan("");
    return;
  }
  const std::vector<double> values(d.begin(), d.end());
  std::vector<double> neighbours;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const std::size_t first = i > outlier_neighbourhood ? i - outlier_neighbourhood : 0;
    const std::size_t last = std::min(d.size(), i + outlier_neighbourhood + 1);
    neighbours.assign(values.begin() + static_cast<std::ptrdiff_t>(first),
                      values.begin() + static_cast<std::ptrdiff_t>(last));
    const double limit = 10.0 * robust_scale(neighbours);
    if (limit > 0.0 && std::abs(values[i]) > limit) d[i] = std::nan("");
  }
}

StructureFunction structure_function(std::span<const double> y, std::size_t low, std::size_t high,
                                     OutlierScale outliers) {
  StructureFunction f;
  for (int L : scales) {
    const auto l = static_cast<std::size_t>(L);
    std::vector<double> d;
    for (std::size_t i = low + l; i + l <= high; ++i) d.push_back(y[i + l] - 2.0 * y[i] + y[i - l]);
    leave_out_outliers(d, outliers);
    double sum = 0.0;
    std::size_t kept = 0;
    for (double v : d) {
      if (std::isnan(v)) continue;
      sum += v * v;
      ++kept;
    }
    f.s.push_back(kept > 0 ? sum / static_cast<double>(kept) : 0.0);
    if (L == 1) f.d1 = std::move(d);
  }
  return f;
}

// Fits S(L) ≈ 6σ_w² + 2L σ_r² + L⁴ c (white noise, random walk, the curve's own curvature) by
// least squares relative to S(L), over every subset of the three terms with non-negative
// coefficients; the best such fit wins. On interval means the walk's term is (2L − 1) σ_r² (RowKind).
NoiseComponents fit_components(const std::vector<double>& s, RowKind rows) {
  const double shared_walk = rows == RowKind::interval_means ? 1.0 : 0.0;
  NoiseComponents best;
  double best_misfit = std::numeric_limits<double>::infinity();
  for (int subset = 1; subset < 8; ++subset) {
    Eigen::MatrixXd design(static_cast<Eigen::Index>(s.size()), 3);
    Eigen::VectorXd target(static_cast<Eigen::Index>(s.size()));
    for (std::size_t k = 0; k < s.size(); ++k) {
      const double L = scales[k], weight = s[k] > 0.0 ? 1.0 / s[k] : 0.0;
      const auto r = static_cast<Eigen::Index>(k);
      design(r, 0) = (subset & 1) ? 6.0 * weight : 0.0;
      design(r, 1) = (subset & 2) ? (2.0 * L - shared_walk) * weight : 0.0;
      design(r, 2) = (subset & 4) ? L * L * L * L * weight : 0.0;
      target(r) = s[k] * weight;
    }
    const Eigen::Vector3d c = design.colPivHouseholderQr().solve(target);
    if ((c.array() < 0.0).any()) continue;
    const double misfit = (design * c - target).squaredNorm();
    if (misfit < best_misfit) {
      best_misfit = misfit;
      best.white = std::sqrt(c(0));
      best.walk = std::sqrt(c(1));
    }
  }
  return best;
}

// Under the model S(L) never falls as L grows (each term is constant or rising). A ringing's second
// differences do: a period of P samples cancels at lags near P and adds up near P/2. A fall below
// half the largest value at a shorter lag marks one (white noise's estimates stay within ~20 %).
constexpr double ringing_fall = 0.5;

bool rings(const std::vector<double>& s) {
  double highest = 0.0;
  for (double v : s) {
    if (v < ringing_fall * highest) return true;
    highest = std::max(highest, v);
  }
  return false;
}

// The components of one curve. Where its structure function rings (a DEM run's F, sampled faster
// than its slowest mode: docs/analysis.md, "What F's ringing does to the noise model"), the fit
// reads the ringing as a walk or hides the walk under it. The walk is then read on means over
// blocks of k samples, the shortest k (2 to 8) whose structure function no longer rings: a block
// of about one period damps the ringing, and a walk's step over a block is √k times its step per
// sample. The ringing itself enters as white noise of its own variance (the mean of S(L)/6 over the
// lags, where its correlations average out), which the filter removes as it removes the ringing.
// Block means of interval means are interval means; block means of instants are read as instants
// (their exact term, (2L − 1 + 1/k²)σ², is not used: F's walk there is mostly taken from E_e's,
// add_hidden_force_walk, and the change would need its own check).
NoiseComponents fit_curve(std::span<const double> y, std::size_t low, std::size_t high,
                          const std::vector<double>& s, OutlierScale outliers, RowKind rows) {
  if (!rings(s)) return fit_components(s, rows);
  for (std::size_t k = 2; k <= 8; ++k) {
    const std::size_t blocks = (high + 1 - low) / k;
    if (blocks < shortest_span) break;
    std::vector<double> means(blocks);
    for (std::size_t b = 0; b < blocks; ++b) {
      const auto first = y.begin() + static_cast<std::ptrdiff_t>(low + b * k);
      means[b] = std::accumulate(first, first + static_cast<std::ptrdiff_t>(k), 0.0) / static_cast<double>(k);
    }
    const auto block = structure_function(means, 0, blocks - 1, outliers);
    if (rings(block.s)) continue;
    NoiseComponents c;
    c.ringing_block = k;
    c.walk = fit_components(block.s, rows).walk / std::sqrt(static_cast<double>(k));
    c.white = std::sqrt(std::accumulate(s.begin(), s.end(), 0.0) / (6.0 * static_cast<double>(s.size())));
    return c;
  }
  return fit_components(s, rows);
}

double quantile_sorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double position = p * static_cast<double>(sorted.size() - 1);
  const auto k = static_cast<std::size_t>(std::floor(position));
  if (k + 1 >= sorted.size()) return sorted.back();
  const double t = position - static_cast<double>(k);
  return sorted[k] + t * (sorted[k + 1] - sorted[k]);
}

}  // namespace

NoiseModel estimate_noise(std::span<const double> force, std::span<const double> energy, std::size_t low,
                          std::size_t high, OutlierScale outliers, RowKind rows) {
  assert(force.size() == energy.size());
  high = std::min(high, force.size() - 1);
  NoiseModel model;
  const auto f = structure_function(force, low, high, outliers);
  const auto e = structure_function(energy, low, high, outliers);
  model.force = fit_curve(force, low, high, f.s, outliers, rows);
  model.energy = fit_curve(energy, low, high, e.s, outliers, rows);
  double cross = 0.0, ff = 0.0, ee = 0.0;
  for (std::size_t i = 0; i < f.d1.size(); ++i) {
    if (std::isnan(f.d1[i]) || std::isnan(e.d1[i])) continue;
    cross += f.d1[i] * e.d1[i];
    ff += f.d1[i] * f.d1[i];
    ee += e.d1[i] * e.d1[i];
  }
  if (ff > 0.0 && ee > 0.0) model.correlation = std::clamp(cross / std::sqrt(ff * ee), -1.0, 1.0);
  return model;
}

bool random_walk_dominates(const NoiseComponents& curve) {
  return 2.0 * curve.walk * curve.walk > 6.0 * curve.white * curve.white;
}

bool random_walk_dominates(const NoiseModel& model) {
  return random_walk_dominates(model.force) || random_walk_dominates(model.energy);
}

int walk_dominated_quarters(std::span<const double> force, std::span<const double> energy, std::size_t low,
                            std::size_t high) {
  high = std::min(high, force.size() - 1);
  if (high < low || high - low + 1 < 4 * shortest_span) return 0;
  const std::size_t n = high + 1 - low;
  int quarters = 0;
  for (std::size_t q = 0; q < 4; ++q)
    if (random_walk_dominates(estimate_noise(force, energy, low + q * n / 4, low + (q + 1) * n / 4 - 1)))
      ++quarters;
  return quarters;
}

namespace {

// Relative walk step along [low, high] of a curve whose noise comes from breaks: step² ∝ x^(2
// power) · s(x), s = −d(F/x)/dx the rate at which the secant stiffness falls (power 1 for F, 2 for
// E_e); empty where the stiffness never falls. F/x is averaged over `half` samples on each side
// before the difference: the counts of breaks are themselves the noise. The noise model floors each
// step at 1 % of the mean square (no sample without noise); the weights that carry E_e's steps to F's
// take it unfloored (add_hidden_force_walk).
enum class Floor { one_percent, none };
std::vector<double> damage_profile(std::span<const double> strain, std::span<const double> force,
                                   std::size_t low, std::size_t high, int power,
                                   Floor floor = Floor::one_percent) {
  const std::size_t n = high - low + 1, size = strain.size();
  const std::size_t half =
      static_cast<std::size_t>(std::clamp<double>(static_cast<double>(n) / 16.0, 3.0, 200.0));
  // Running sums of the secant stiffness F/x (at x <= 0, the first defined value).
  std::vector<double> sum(size + 1, 0.0);
  double first = std::nan("");
  for (std::size_t i = 0; i < size && std::isnan(first); ++i)
    if (strain[i] > 0.0) first = force[i] / strain[i];
  for (std::size_t i = 0; i < size; ++i)
    sum[i + 1] = sum[i] + (strain[i] > 0.0 ? force[i] / strain[i] : first);
  const auto mean_over = [&](std::size_t from, std::size_t to) {  // [from, to], clamped to the curve
    to = std::min(to, size - 1);
    from = std::min(from, to);
    return (sum[to + 1] - sum[from]) / static_cast<double>(to + 1 - from);
  };
  const double step = strain[1] - strain[0];
  std::vector<double> profile(n);
  double mean = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = low + j;
    const double before = mean_over(i > half ? i - half : 0, i > 0 ? i - 1 : 0),
                 after = mean_over(i + 1, i + half);
    const double softening = (before - after) / (step * static_cast<double>(half + 1));
    profile[j] = std::pow(strain[i], 2 * power) * std::max(softening, 0.0);
    mean += profile[j] / static_cast<double>(n);
  }
  if (!(mean > 0.0) || !std::isfinite(mean)) return {};
  const double least = floor == Floor::one_percent ? 0.01 * mean : 0.0;
  double mean_square = 0.0;
  for (auto& p : profile) {
    p = std::max(p, least);
    mean_square += p / static_cast<double>(n);
  }
  for (auto& p : profile) p = std::sqrt(p / mean_square);
  return profile;
}

}  // namespace

void add_walk_profiles(NoiseModel& model, std::span<const double> strain, std::span<const double> force,
                       std::size_t low, std::size_t high) {
  assert(strain.size() == force.size() && strain.size() >= 2);
  high = std::min(high, force.size() - 1);
  model.force.walk_profile = random_walk_dominates(model.force) ? damage_profile(strain, force, low, high, 1)
                                                                : std::vector<double>{};
  model.energy.walk_profile = random_walk_dominates(model.energy)
                                  ? damage_profile(strain, force, low, high, 2)
                                  : std::vector<double>{};
}

void add_hidden_force_walk(NoiseModel& model, std::span<const double> strain, std::span<const double> force,
                           std::span<const double> energy, std::size_t low, std::size_t high) {
  assert(strain.size() == force.size() && force.size() == energy.size() && strain.size() >= 2);
  high = std::min(high, force.size() - 1);
  const bool force_reading_lost = model.force.ringing_block != 0 || !(model.force.walk > 0.0);
  if (!force_reading_lost || model.energy.ringing_block != 0 || !random_walk_dominates(model.energy)) return;
  // E_e's step at each sample relative to its rms over the span, from the breaks' physics, unfloored:
  // with the noise model's floor, the samples near zero strain, where F/E_e = 2/x has no bound, set
  // the rms (1.7-5.5 times F's own walk on finite bundles, 5000 rows the worst; 1.00 unfloored).
  const auto energy_steps = damage_profile(strain, force, low, high, 2, Floor::none);
  if (energy_steps.empty()) return;
  double squares = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = low; i <= high; ++i) {
    if (!(energy[i] > 0.0)) continue;
    const double step = energy_steps[i - low] * force[i] / energy[i];
    squares += step * step;
    ++counted;
  }
  if (counted == 0) return;
  model.force.walk = model.energy.walk * std::sqrt(squares / static_cast<double>(counted));
  model.force.walk_from_energy = true;
  model.force.walk_read_as_zero = model.force.ringing_block == 0;
  model.force.walk_profile =
      model.energy.walk_profile.empty() ? std::vector<double>{} : damage_profile(strain, force, low, high, 1);
}

void add_model_noise(const NoiseModel& model, std::span<double> force, std::span<double> energy,
                     std::uint64_t seed, std::uint64_t replicate) {
  assert(force.size() == energy.size());
  Rng rng(seed, RandomStream::analysis_bootstrap, replicate);
  const double rho = model.correlation, rest = std::sqrt(std::max(0.0, 1.0 - rho * rho));
  const auto step = [](const NoiseComponents& c, std::size_t i) {
    return i < c.walk_profile.size() ? c.walk * c.walk_profile[i] : c.walk;
  };
  double walk_force = 0.0, walk_energy = 0.0;
  for (std::size_t i = 0; i < force.size(); ++i) {
    const double a = rng.normal(), b = rng.normal(), c = rng.normal(), d = rng.normal();
    if (i > 0) {
      walk_force += step(model.force, i) * c;
      walk_energy += step(model.energy, i) * (rho * c + rest * d);
    }
    force[i] += model.force.white * a + walk_force;
    energy[i] += model.energy.white * (rho * a + rest * b) + walk_energy;
  }
}

BootstrapResult bootstrap_peaks(std::span<const double> force, std::span<const double> energy,
                                const NoiseModel& model, const PeakMeasure& measure,
                                const BootstrapOptions& options) {
  BootstrapResult result;
  result.attempted = std::max(0, options.replicates);
  std::vector<std::optional<PeakValues>> values(static_cast<std::size_t>(result.attempted));
#pragma omp parallel
  {
    std::vector<double> f(force.size()), e(energy.size());
#pragma omp for schedule(dynamic)
    for (int b = 0; b < result.attempted; ++b) {
      std::copy(force.begin(), force.end(), f.begin());
      std::copy(energy.begin(), energy.end(), e.begin());
      add_model_noise(model, f, e, options.seed, static_cast<std::uint64_t>(b));
      values[static_cast<std::size_t>(b)] = measure(f, e);
    }
  }
  for (const auto& v : values) {
    if (v)
      result.replicates.push_back(*v);
    else
      ++result.failed;
  }
  return result;
}

BootstrapInterval bootstrap_interval(double estimate, std::vector<double> replicates, double kept_bias) {
  BootstrapInterval s;
  s.estimate = estimate;
  if (replicates.size() < 2) {
    s.ci68_low = s.ci68_high = s.ci95_low = s.ci95_high = estimate;
    return s;
  }
  std::sort(replicates.begin(), replicates.end());
  const double n = static_cast<double>(replicates.size());
  const double mean = std::accumulate(replicates.begin(), replicates.end(), 0.0) / n;
  double squares = 0.0;
  for (double v : replicates) squares += (v - mean) * (v - mean);
  const double spread = std::sqrt(squares / (n - 1.0));
  s.spread = spread;
  s.bias = mean - estimate;
  // Half the bootstrap's bias estimate is subtracted and the other half counted as error: the
  // replicates are smoothed twice (the data once, then again with their noise), so their shift
  // over-states the smoothing bias of the data, and how much is not known (docs/analysis.md). On
  // finite bundles the bias has the wrong sign, yet leaving it in failed its check (held-out 17).
  s.estimate = estimate - 0.5 * (s.bias - kept_bias);
  s.sd = std::hypot(spread, 0.5 * s.bias);
  // Replicates that all agree (a window the noise model reads as noise-free) carry no shape: the
  // interval is then the normal one of the bias's half, not zero wide.
  const double widen = spread > 0.0 ? s.sd / spread : 1.0;
  const double median = quantile_sorted(replicates, 0.5);
  const bool agree = quantile_sorted(replicates, 0.975) - quantile_sorted(replicates, 0.025) <= 1e-9 * s.sd;
  const auto at = [&](double p) {
    if (agree) return s.estimate + s.sd * boost::math::quantile(boost::math::normal(), p);
    return s.estimate + widen * (quantile_sorted(replicates, p) - median);
  };
  s.ci68_low = at(0.15865525393145707);
  s.ci68_high = at(0.8413447460685429);
  s.ci95_low = at(0.025);
  s.ci95_high = at(0.975);
  return s;
}

BootstrapInterval add_systematic(BootstrapInterval interval, double shift) {
  const double sd = std::hypot(interval.sd, shift);
  const double widen = interval.sd > 0.0 ? sd / interval.sd : 1.0;
  const auto stretch = [&](double bound) { return interval.estimate + widen * (bound - interval.estimate); };
  interval.ci68_low = stretch(interval.ci68_low);
  interval.ci68_high = stretch(interval.ci68_high);
  interval.ci95_low = stretch(interval.ci95_low);
  interval.ci95_high = stretch(interval.ci95_high);
  if (interval.sd == 0.0) {
    interval.ci68_low -= std::abs(shift), interval.ci68_high += std::abs(shift);
    interval.ci95_low -= 1.96 * std::abs(shift), interval.ci95_high += 1.96 * std::abs(shift);
  }
  interval.sd = sd;
  return interval;
}

}  // namespace rupture::analysis
