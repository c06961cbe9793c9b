// What a collapse close to the force peak does to x_c, with the curve's own noise held fixed
// (docs/analysis.md, "x_c of a loading cut by a collapse"): each run-like bundle of the tuning set
// (10⁴ fibres, means over each row, calibration_set.hpp) that comes apart within MAX_CUT x_c is
// analysed as recorded and once more without its collapse, with the cut curve's filter (the rows
// before the cut are the same in both). Prints each pair's x_c error (% of the true x_c), uncut and
// cut, and their mean and rms over the pairs, with x_p's.
// Usage: cut_pairs [steps between rows = 200] [seeds per shape = 20] [MAX_CUT = 1.08]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "calibration_set.hpp"

using namespace rupture::analysis;
using namespace rupture::analysis::calibration;

namespace {

struct Summary {
  std::vector<double> values;
  void add(double v) { values.push_back(v); }
  void print(const char* what) const {
    double sum = 0.0, square = 0.0;
    for (double v : values) {
      sum += v;
      square += v * v;
    }
    if (values.empty()) return;
    const auto n = static_cast<double>(values.size());
    std::printf("%s: mean %+.2f %%, rms %.2f %%\n", what, sum / n, std::sqrt(square / n));
  }
};

}  // namespace

int main(int argc, char** argv) {
  const std::size_t every = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 200;
  const int seeds = argc > 2 ? std::atoi(argv[2]) : 20;
  const double max_cut = argc > 3 ? std::atof(argv[3]) : 1.08;
  Summary uncut_x_c, cut_x_c, moved_x_c, cut_x_p;
  int rejected = 0;
  std::printf("shape | seed | cut / x_c | x_c error uncut [%%] | cut [%%] | x_p error cut [%%]\n");
  for (const auto& s : calibration_set("tuning")) {
    const Truth t = truth(s);
    for (int seed = 1; seed <= seeds; ++seed) {
      const double b = run_like_cut(s, static_cast<std::uint64_t>(seed)) / t.x_c;
      if (b > max_cut) continue;
      const RunRows cut_rows{every, true, 0.008, true}, uncut_rows{every, true, 0.008, false};
      const auto cut =
          analyze_curve(run_like_curve(s, 10000, cut_rows, static_cast<std::uint64_t>(seed)), {});
      AnalysisOptions same_filter;
      same_filter.filter.cutoff = cut.filter.cutoff;
      const auto uncut =
          analyze_curve(run_like_curve(s, 10000, uncut_rows, static_cast<std::uint64_t>(seed)), same_filter);
      if (!cut.x_c || !cut.x_p || !uncut.x_c) {
        ++rejected;
        continue;
      }
      const double before = 100.0 * (uncut.x_c->value / t.x_c - 1.0),
                   after = 100.0 * (cut.x_c->value / t.x_c - 1.0);
      const double x_p = 100.0 * (cut.x_p->value / t.x_p - 1.0);
      std::printf("%s | %d | %.3f | %+.2f | %+.2f | %+.2f\n", s.name.c_str(), seed, b, before, after, x_p);
      uncut_x_c.add(before);
      cut_x_c.add(after);
      moved_x_c.add(after - before);
      cut_x_p.add(x_p);
    }
  }
  std::printf("%zu pairs, %d without x_c or x_p\n", cut_x_c.values.size(), rejected);
  uncut_x_c.print("x_c error, uncut");
  cut_x_c.print("x_c error, cut");
  moved_x_c.print("x_c moved by the cut");
  cut_x_p.print("x_p error, cut");
}
