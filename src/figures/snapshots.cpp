#include "figures/snapshots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string_view>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/vtk.hpp"

namespace rupture::figures {

namespace fs = std::filesystem;

namespace {

// The share of bonds whose |extension| sets the ends of the colour scale; the few most stretched bonds
// (at a crack tip) would otherwise wash every other bond out to the middle colour.
constexpr double colour_quantile = 0.995;

double quantile_of_magnitude(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  for (auto& v : values) v = std::abs(v);
  const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

SnapshotBonds read_snapshot_bonds(const fs::path& vtp) {
  const io::VtkPolyData data = io::read_vtp(vtp);
  const io::VtkArray* relative = data.line_array("relative_extension");
  if (relative == nullptr || relative->components != 1)
    throw InputError(vtp.string(), "no line array relative_extension",
                     "give a snapshot written by `rupture run` (output.snapshot_interval)");
  const std::vector<double> extension = io::as_doubles(*relative);
  SnapshotBonds bonds;
  for (std::size_t b = 0; b < data.lines.size(); ++b) {
    const Vec3& a = data.points[data.lines[b][0]];
    const Vec3& c = data.points[data.lines[b][1]];
    bonds.x_a.push_back(a.x);
    bonds.y_a.push_back(a.y);
    bonds.x_b.push_back(c.x);
    bonds.y_b.push_back(c.y);
    bonds.relative_extension.push_back(extension[b]);
  }
  return bonds;
}

std::vector<SnapshotFile> list_snapshots(const fs::path& run_folder, const io::CsvTable& curves) {
  std::vector<SnapshotFile> found;
  const fs::path collection = run_folder / "snapshots.pvd";
  if (!fs::is_regular_file(collection)) return found;
  // The collection names each snapshot as file="snapshots/step_N.vtp" (io/vtk write_pvd).
  const std::string text = io::read_text_file(collection);
  constexpr std::string_view attribute = "file=\"";
  for (auto at = text.find(attribute); at != std::string::npos; at = text.find(attribute, at)) {
    at += attribute.size();
    const auto end = text.find('"', at);
    if (end == std::string::npos) break;
    const fs::path file = run_folder / text.substr(at, end - at);
    const std::string stem = file.stem().string();
    if (stem.rfind("step_", 0) != 0 || file.extension() != ".vtp") continue;
    std::uint64_t step = 0;
    const auto [next, error] = std::from_chars(stem.data() + 5, stem.data() + stem.size(), step);
    if (error != std::errc() || next != stem.data() + stem.size()) continue;
    if (!fs::is_regular_file(file))
      throw InputError(collection.string(), fmt::format("lists {}, which is missing", file.string()),
                       "rerun the run, or remove snapshots.pvd to plot without snapshots");
    found.push_back({file, step, 0.0});
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.step < b.step; });
  // Snapshots and curve rows need not share steps: interpolate the strain linearly in step.
  const auto& steps = curves.column("step");
  const auto& strain = curves.column("strain");
  for (auto& s : found) {
    const double step = static_cast<double>(s.step);
    const auto hi = std::lower_bound(steps.begin(), steps.end(), step);
    if (hi == steps.begin())
      s.strain = strain.front();
    else if (hi == steps.end())
      s.strain = strain.back();
    else {
      const auto i = static_cast<std::size_t>(hi - steps.begin());
      const double t = (step - steps[i - 1]) / (steps[i] - steps[i - 1]);
      s.strain = strain[i - 1] + t * (strain[i] - strain[i - 1]);
    }
  }
  return found;
}

std::vector<SnapshotFile> nearest_snapshots(const std::vector<SnapshotFile>& all,
                                            const std::vector<double>& strains) {
  std::vector<SnapshotFile> chosen;
  if (all.empty()) return chosen;
  for (double wanted : strains) {
    const auto best = std::min_element(all.begin(), all.end(), [wanted](const auto& a, const auto& b) {
      return std::abs(a.strain - wanted) < std::abs(b.strain - wanted);
    });
    if (std::none_of(chosen.begin(), chosen.end(), [&](const auto& c) { return c.step == best->step; }))
      chosen.push_back(*best);
  }
  std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.step < b.step; });
  return chosen;
}

namespace {

// The extent of every bond end drawn, for one shared set of axes.
struct Extent {
  double x_low = INFINITY, x_high = -INFINITY, y_low = INFINITY, y_high = -INFINITY;
};

// One snapshot's intact bonds as segments (x, y, dx, dy, extension in %), widening `extent`.
DataBlock intact_bonds_block(const SnapshotBonds& bonds, const SnapshotFile& snapshot,
                             const std::string& strain_unit, Extent& extent) {
  DataBlock block;
  block.title =
      fmt::format("intact bonds at step {}, strain {:.4g} {}", snapshot.step, snapshot.strain, strain_unit);
  block.header = {"x[mm]", "y[mm]", "dx[mm]", "dy[mm]", "extension[%]"};
  block.columns.resize(5);
  for (std::size_t b = 0; b < bonds.x_a.size(); ++b) {
    block.columns[0].push_back(bonds.x_a[b]);
    block.columns[1].push_back(bonds.y_a[b]);
    block.columns[2].push_back(bonds.x_b[b] - bonds.x_a[b]);
    block.columns[3].push_back(bonds.y_b[b] - bonds.y_a[b]);
    block.columns[4].push_back(100.0 * bonds.relative_extension[b]);
    extent.x_low = std::min({extent.x_low, bonds.x_a[b], bonds.x_b[b]});
    extent.x_high = std::max({extent.x_high, bonds.x_a[b], bonds.x_b[b]});
    extent.y_low = std::min({extent.y_low, bonds.y_a[b], bonds.y_b[b]});
    extent.y_high = std::max({extent.y_high, bonds.y_a[b], bonds.y_b[b]});
  }
  return block;
}

// The bonds broken up to a snapshot, where they broke: the crack, which the intact bonds through
// the sample's depth would otherwise hide.
DataBlock broken_bonds_block(const io::CsvTable& breaks, std::uint64_t up_to_step) {
  DataBlock broken;
  broken.title = fmt::format("bonds broken up to step {}", up_to_step);
  broken.header = {"x[mm]", "y[mm]"};
  broken.columns.resize(2);
  const auto& step = breaks.column("step");
  const auto& x = breaks.column("x");
  const auto& y = breaks.column("y");
  for (std::size_t r = 0; r < step.size() && step[r] <= double(up_to_step); ++r) {
    broken.columns[0].push_back(x[r]);
    broken.columns[1].push_back(y[r]);
  }
  return broken;
}

// One colour scale for every panel, symmetric so an unstretched bond is the middle colour; the same
// axes for all; each panel the sample's aspect at 1000 px width, plus room for title and labels.
void share_scales(Figure& figure, std::vector<double> all_extensions, const Extent& e, std::size_t panels) {
  double scale = quantile_of_magnitude(std::move(all_extensions), colour_quantile);
  if (!(scale > 0.0)) scale = 1e-6;
  const double pad_x = 0.02 * (e.x_high - e.x_low), pad_y = 0.05 * (e.y_high - e.y_low);
  for (auto& panel : figure.panels) {
    panel.cbrange = fmt::format("[{}:{}]", -scale, scale);
    panel.xrange = fmt::format("[{}:{}]", e.x_low - pad_x, e.x_high + pad_x);
    panel.yrange = fmt::format("[{}:{}]", e.y_low - pad_y, e.y_high + pad_y);
  }
  const double aspect = (e.y_high - e.y_low + 2 * pad_y) / std::max(e.x_high - e.x_low + 2 * pad_x, 1e-12);
  figure.height = static_cast<int>(panels) * std::clamp(static_cast<int>(160 + 760 * aspect), 300, 900);
}

}  // namespace

Figure snapshots_figure(const std::vector<SnapshotFile>& chosen, const std::string& strain_unit,
                        std::vector<std::string> provenance, const io::CsvTable* breaks) {
  Figure figure;
  figure.name = "snapshots";
  std::vector<double> all_extensions;
  Extent extent;
  for (const auto& snapshot : chosen) {
    provenance.push_back("read: " + snapshot.file.string());
    const SnapshotBonds bonds = read_snapshot_bonds(snapshot.file);
    DataBlock block = intact_bonds_block(bonds, snapshot, strain_unit, extent);
    all_extensions.insert(all_extensions.end(), block.columns[4].begin(), block.columns[4].end());
    Panel panel;
    panel.title = fmt::format("strain x = {:.3g} {} (step {}, {} intact bonds)", snapshot.strain, strain_unit,
                              snapshot.step, bonds.x_a.size());
    panel.xlabel = "x across the width [mm]";
    panel.ylabel = "y, loading direction [mm]";
    panel.equal_axes = true;
    panel.cblabel = "bond extension (r - r_0)/r_0 [%]";
    panel.series = {{.block = figure.blocks.size(), .style = Style::segments, .extra_columns = {2, 3, 4}}};
    figure.blocks.push_back(std::move(block));
    if (breaks != nullptr) {
      DataBlock broken = broken_bonds_block(*breaks, snapshot.step);
      panel.title += fmt::format(", {} broken", broken.columns[0].size());
      if (!broken.columns[0].empty()) {
        panel.series.push_back({.block = figure.blocks.size(),
                                .title = "broken bond",
                                .style = Style::points,
                                .color = "#000000",
                                .point_type = 7,
                                .point_size = 0.45});
        figure.blocks.push_back(std::move(broken));
      }
    }
    figure.panels.push_back(std::move(panel));
  }
  share_scales(figure, std::move(all_extensions), extent, chosen.size());
  figure.provenance = std::move(provenance);
  figure.caption = fmt::format(
      "Intact bonds at {} strains, coloured by their extension (r - r0)/r0 in % on one scale for all panels "
      "(ends of the scale: the {:.1f} % quantile of |extension|){}.",
      chosen.size(), 100.0 * colour_quantile,
      breaks != nullptr
          ? "; black dots: the bonds broken so far, where they broke (from breaks.csv), which trace the crack"
          : "; broken bonds are gone");
  return figure;
}

}  // namespace rupture::figures
