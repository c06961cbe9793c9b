// The sweep that chose AnalysisOptions::random_walk_smoothing_share (docs/analysis.md, "The smoothing
// cap"): finite-bundle curves of the 14 shapes used before the choice (the tuning set, the first
// held-out set, the fourth held-out set without its uniform law, which is the tuning's scaled) at
// N = 10^4, 10^5, 10^6 fibers, each at 300, 1000 and 5000 rows with `seeds` seeds, analysed once per
// share with 100 bootstrap replicates and the bootstrap's own (unscaled) intervals. Prints per share and
// fiber count: curves, those with a δ_x, accepted, δ_x's mean and rms relative error and the unscaled
// intervals' coverage; then δ_x's mean and rms error per shape. Each curve is drawn once and analysed
// at every share, so the shares see the same curves.
// Usage: smoothing_share_sweep [seeds = 4] [share ... = 0 0.35 0.5 0.7]   (0: no cap)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "calibration_set.hpp"

using namespace rupture::analysis;
using namespace rupture::analysis::calibration;

namespace {

std::vector<Shape> swept_shapes() {
  std::vector<Shape> chosen;
  for (auto& s : shapes()) chosen.push_back(s);  // the tuning set and the first held-out set
  for (auto& s : calibration_set("held-out-4"))
    if (s.name.rfind("uniform", 0) != 0) chosen.push_back(s);
  return chosen;
}

struct Outcome {
  bool estimated = false, accepted = false, in68 = false, in95 = false;
  double relative_error = 0.0;
};

struct Tally {
  int curves = 0, estimated = 0, accepted = 0, in68 = 0, in95 = 0;
  double sum = 0.0, squares = 0.0;
  void add(const Outcome& o) {
    ++curves;
    if (!o.estimated) return;
    ++estimated;
    accepted += o.accepted;
    in68 += o.in68;
    in95 += o.in95;
    sum += o.relative_error;
    squares += o.relative_error * o.relative_error;
  }
  double mean() const { return estimated ? sum / estimated : NAN; }
  double rms() const { return estimated ? std::sqrt(squares / estimated) : NAN; }
};

const std::size_t fibers_choice[] = {10000, 100000, 1000000};
const std::size_t rows_choice[] = {300, 1000, 5000};

struct Case {
  std::size_t shape, fibers, rows;
  std::uint64_t seed;
};

std::vector<Case> make_cases(std::size_t shapes, int seeds) {
  std::vector<Case> cases;
  for (const std::size_t fibers : fibers_choice)
    for (std::size_t s = 0; s < shapes; ++s)
      for (const std::size_t rows : rows_choice)
        for (int k = 0; k < seeds; ++k)
          cases.push_back({s, fibers, rows, static_cast<std::uint64_t>(7919 * cases.size() + 31)});
  return cases;
}

// outcomes[share][case]; each case's curve is drawn once. Cases run in parallel, each analysis on one
// thread (the bootstrap's replicates have their own generators: the numbers do not depend on it).
std::vector<std::vector<Outcome>> analyse(const std::vector<Shape>& swept, const std::vector<Case>& cases,
                                          const std::vector<double>& shares) {
  std::vector<std::vector<Outcome>> outcomes(shares.size(), std::vector<Outcome>(cases.size()));
#pragma omp parallel for schedule(dynamic)
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const Case& k = cases[c];
    const Shape& s = swept[k.shape];
    const Curve curve = finite_bundle_curve(s, k.rows, k.fibers, k.seed);
    const double truth_delta = truth(s).delta();
    for (std::size_t i = 0; i < shares.size(); ++i) {
      AnalysisOptions options;
      options.calibrated_intervals = false;
      options.uncertainty.replicates = 100;
      options.random_walk_smoothing_share = shares[i];
      const auto r = analyze_curve(curve, options);
      if (!r.delay) continue;
      const auto& d = *r.delay;
      outcomes[i][c] = {.estimated = true,
                        .accepted = r.accepted,
                        .in68 = d.ci68_low <= truth_delta && truth_delta <= d.ci68_high,
                        .in95 = d.ci95_low <= truth_delta && truth_delta <= d.ci95_high,
                        .relative_error = (d.mean - truth_delta) / truth_delta};
    }
  }
  return outcomes;
}

// The tally of one share over the cases `keep` selects.
template <class Keep>
Tally tally(const std::vector<Case>& cases, const std::vector<Outcome>& outcomes, Keep keep) {
  Tally t;
  for (std::size_t c = 0; c < cases.size(); ++c)
    if (keep(cases[c])) t.add(outcomes[c]);
  return t;
}

void print_by_fibers(const std::vector<Case>& cases, const std::vector<double>& shares,
                     const std::vector<std::vector<Outcome>>& outcomes) {
  std::printf(
      "| share | fibers | curves | with δ_x | accepted | δ_x mean error | δ_x rms error | 68 %% coverage "
      "(unscaled) | 95 %% coverage (unscaled) |\n|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < shares.size(); ++i)
    for (const std::size_t fibers : fibers_choice) {
      const Tally t = tally(cases, outcomes[i], [&](const Case& c) { return c.fibers == fibers; });
      std::printf("| %g | %zu | %d | %d | %d | %+.1f %% | %.1f %% | %.0f %% | %.0f %% |\n", shares[i], fibers,
                  t.curves, t.estimated, t.accepted, 100 * t.mean(), 100 * t.rms(),
                  100.0 * t.in68 / t.estimated, 100.0 * t.in95 / t.estimated);
    }
}

void print_by_shape(const std::vector<Shape>& swept, const std::vector<Case>& cases,
                    const std::vector<double>& shares, const std::vector<std::vector<Outcome>>& outcomes) {
  std::printf("\nδ_x mean / rms relative error per shape and fiber count\n\n| shape | fibers |");
  for (const double share : shares) std::printf(" share %g |", share);
  std::printf("\n|---|---|");
  for (std::size_t i = 0; i < shares.size(); ++i) std::printf("---|");
  std::printf("\n");
  for (std::size_t s = 0; s < swept.size(); ++s)
    for (const std::size_t fibers : fibers_choice) {
      std::printf("| %s | %zu |", swept[s].name.c_str(), fibers);
      for (std::size_t i = 0; i < shares.size(); ++i) {
        const Tally t =
            tally(cases, outcomes[i], [&](const Case& c) { return c.shape == s && c.fibers == fibers; });
        std::printf(" %+.1f / %.1f %% |", 100 * t.mean(), 100 * t.rms());
      }
      std::printf("\n");
    }
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 4;
  std::vector<double> shares;
  for (int i = 2; i < argc; ++i) {
    char* end = nullptr;
    shares.push_back(std::strtod(argv[i], &end));
    if (end == argv[i] || *end != '\0' || shares.back() < 0.0 || shares.back() > 1.0) {
      std::fprintf(stderr, "smoothing_share_sweep: share '%s' is not a number in [0, 1] (0: no cap)\n",
                   argv[i]);
      return 2;
    }
  }
  if (shares.empty()) shares = {0.0, 0.35, 0.5, 0.7};
  if (seeds < 1) {
    std::fprintf(stderr, "smoothing_share_sweep: seeds must be a whole number of at least 1\n");
    return 2;
  }
  const std::vector<Shape> swept = swept_shapes();
  const std::vector<Case> cases = make_cases(swept.size(), seeds);
  const auto outcomes = analyse(swept, cases, shares);
  std::printf("%zu shapes x 3 row counts x %d seeds = %zu curves per fiber count\n\n", swept.size(), seeds,
              swept.size() * 3 * static_cast<std::size_t>(seeds));
  print_by_fibers(cases, shares, outcomes);
  print_by_shape(swept, cases, shares, outcomes);
  return 0;
}
