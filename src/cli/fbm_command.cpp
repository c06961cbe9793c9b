// cli/fbm_command: `rupture fbm theory | curves | simulate`, the fiber bundle model from the
// command line. Owns option parsing, tables, CSV and JSON output; the physics is in src/fbm.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "fbm/bundle.hpp"
#include "fbm/distribution.hpp"
#include "fbm/els_theory.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "rupture/version.hpp"

namespace rupture::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* units_note =
    "per N kappa = 1: strain dimensionless, force F/(N kappa), energies E/(N kappa), energy rate dE_e/dx / "
    "(N kappa)";

std::unique_ptr<fbm::StrengthDistribution> load_distribution(const std::string& spec) {
  return fbm::parse_distribution_spec(spec, [](const std::string& path) { return io::read_text_file(path); });
}

std::string format_optional(const std::optional<double>& value) {
  return value ? fmt::format("{:.12g}", *value) : "not defined";
}

std::string characteristics_table(const fbm::Characteristics& c) {
  std::string table;
  const auto row = [&](const char* name, const std::string& value, const char* meaning) {
    table += fmt::format("  {:<11} {:<20} {}\n", name, value, meaning);
  };
  const auto num = [](double v) { return fmt::format("{:.12g}", v); };
  row("x_c", num(c.x_c), "critical strain (force maximum)");
  row("F_c", num(c.F_c), "force maximum F/(N kappa)");
  row("x_m", format_optional(c.x_m), "strain of the elastic-energy maximum");
  row("E_max", format_optional(c.E_max), "elastic-energy maximum E_e/(N kappa)");
  row("x_p", num(c.x_p),
      c.Erate_max_at_cutoff ? "precursor strain: at the lower cut-off (see note)"
                            : "precursor strain (energy-rate maximum)");
  row("Erate_max", num(c.Erate_max),
      c.Erate_max_at_cutoff ? "energy-rate supremum: left limit at the cut-off"
                            : "energy-rate maximum dE_e/dx / (N kappa)");
  row("delta_x", num(c.delta_x), "x_c - x_p");
  row("Gamma", format_optional(c.Gamma), "(x_m - x_c) / delta_x");
  row("A_r", format_optional(c.A_r), "E_max / (x_p Erate_max)");
  row("E_d(x_c)", num(c.E_d_at_x_c), "damage energy at x_c, E_d/(N kappa)");
  if (c.Erate_max_at_cutoff)
    table +=
        "  note: the energy rate jumps down at the lower cut-off of the thresholds and is largest just below "
        "it;\n"
        "        x_p is the cut-off and Erate_max the supremum there (not attained).\n";
  return table;
}

std::string csv_text(const std::vector<fbm::CurvePoint>& curve, const std::vector<std::string>& comments) {
  std::string text;
  for (const auto& line : comments) text += "# " + line + "\n";
  text += io::format_csv_header({"strain[1]", "force[1]", "elastic_energy[1]", "damage_energy[1]",
                                 "energy_rate[1]", "broken_fraction[1]"});
  for (const auto& p : curve)
    text += io::format_csv_row({p.x, p.F, p.E_e, p.E_d, p.Erate, p.broken_fraction});
  return text;
}

void add_theory(CLI::App& fbm_app) {
  auto* app = fbm_app.add_subcommand("theory", "Characteristic points of the ELS bundle (N -> infinity)");
  auto spec = std::make_shared<std::string>("uniform");
  auto as_json = std::make_shared<bool>(false);
  app->add_option(
         "--dist", *spec,
         "Threshold distribution: uniform[:a=A,b=B], powerlaw:alpha=A, weibull:k=K[,lambda=L], file:PATH")
      ->capture_default_str();
  app->add_flag("--json", *as_json, "Print JSON instead of a table");
  app->callback([spec, as_json] {
    const auto dist = load_distribution(*spec);
    // Strains on which a file's exact step curve is differentiated for x_p.
    constexpr std::size_t empirical_points = 2001;
    const auto c = fbm::theory_characteristics(*dist, empirical_points);
    const auto* empirical = dynamic_cast<const fbm::Empirical*>(dist.get());
    const std::string method =
        empirical ? fmt::format(
                        "exact ELS curve of the {} fibers in the file; x_p, Erate_max from central "
                        "differences of E_e on 2001 strains",
                        empirical->sorted_thresholds().size())
                  : "ELS theory, N -> infinity: maxima by root finding (TOMS 748), E_d by Gauss-Kronrod";
    if (*as_json) {
      json doc{{"version", version_string},
               {"command", "fbm theory"},
               {"dist", dist->spec()},
               {"method", method},
               {"normalisation", units_note}};
      doc.update(fbm::to_json(c));
      fmt::print("{}\n", doc.dump(2));
    } else {
      fmt::print("fiber bundle, dist {}\n{}\n{}\n{}", dist->spec(), method, units_note,
                 characteristics_table(c));
    }
  });
}

void add_curves(CLI::App& fbm_app) {
  auto* app = fbm_app.add_subcommand(
      "curves", "Analytic ELS curves x, F, E_e, E_d, energy rate on a strain grid (CSV)");
  struct Options {
    std::string spec = "uniform", out;
    std::size_t points = 1001;
  };
  auto o = std::make_shared<Options>();
  app->add_option("--dist", o->spec, "Threshold distribution (see `fbm theory --help`)")
      ->capture_default_str();
  app->add_option("-o,--out", o->out, "CSV file to write (- for stdout)")->required();
  app->add_option("--points", o->points, "Number of strains, equally spaced from 0 to the end of the support")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{3}, std::size_t{100000000}));
  app->callback([o] {
    const auto dist = load_distribution(o->spec);
    const auto curve = fbm::theory_curve(*dist, o->points);
    io::write_output(
        o->out, csv_text(curve, {fmt::format("rupture {}", version_string),
                                 fmt::format("fbm curves --dist {} --points {}", dist->spec(), o->points),
                                 std::string("ELS theory, ") + units_note}));
  });
}

struct SimulateOptions {
  std::string spec = "uniform", sharing = "els", control, out, bursts;
  bool json = false;
  std::size_t fibers = 1000000, points = 2001;
  std::uint64_t seed = 1;
};

// Draws the bundle, runs it under strain or load control, writes the curve (and bursts) and prints
// the summary.
void run_simulate(const SimulateOptions& o) {
  const auto dist = load_distribution(o.spec);
  const std::string control = o.control.empty() ? (o.sharing == "lls" ? "load" : "strain") : o.control;
  if (o.sharing == "lls" && control == "strain")
    throw InputError("--control", "LLS is defined under load control only (a rigid clamp makes it ELS)",
                     "use --control load with --sharing lls");
  if (control == "strain" && !o.bursts.empty())
    throw InputError("--bursts", "bursts exist only under load control", "add --control load");
  const auto thresholds = fbm::draw_thresholds(*dist, o.fibers, o.seed);
  fbm::BundleCurve result;
  std::optional<fbm::LoadControlled> load;
  if (control == "strain") {
    result = fbm::strain_controlled(thresholds, o.points);
  } else {
    load = o.sharing == "els" ? fbm::load_controlled_els(thresholds, o.points)
                              : fbm::load_controlled_lls(thresholds, o.points);
    result = load->result;
  }
  const std::string command =
      fmt::format("fbm simulate --dist {} --fibers {} --seed {} --sharing {} --control {} --points {}",
                  dist->spec(), o.fibers, o.seed, o.sharing, control, o.points);
  const std::string units = std::string(units_note) + " (force per fiber F/N)";
  if (!o.out.empty()) {
    std::vector<std::string> comments{fmt::format("rupture {}", version_string), command,
                                      "finite bundle, " + units};
    if (control == "load")
      comments.push_back(
          "rows: the stable states before each burst, interpolated onto equally spaced strains up to x_c");
    if (o.sharing == "lls") comments.push_back("LLS: strain = mean strain of the intact fibers");
    io::write_file_atomically(o.out, csv_text(result.curve, comments));
  }
  std::string bursts_path = o.bursts;
  if (load && bursts_path.empty() && !o.out.empty()) {
    const fs::path out(o.out);
    bursts_path = (out.parent_path() / (out.stem().string() + "_bursts.csv")).string();
  }
  if (load && !bursts_path.empty()) {
    std::string text = fmt::format(
        "# rupture {}\n# {}\n# bursts (avalanches) of the quasi-static load-controlled run; "
        "the final burst ({} fibers) that breaks the rest is not counted\n",
        version_string, command, load->final_burst);
    text += io::format_csv_header({"size[fibers]", "count[1]"});
    for (const auto& [size, count] : load->burst_counts)
      text += io::format_csv_row({static_cast<double>(size), static_cast<double>(count)});
    io::write_file_atomically(bursts_path, text);
  }
  json summary{{"version", version_string},
               {"command", "fbm simulate"},
               {"inputs",
                {{"dist", dist->spec()},
                 {"fibers", o.fibers},
                 {"seed", o.seed},
                 {"sharing", o.sharing},
                 {"control", control},
                 {"points", o.points}}},
               {"normalisation", units},
               {"curve_file", o.out.empty() ? json(nullptr) : json(o.out)}};
  summary.update(fbm::to_json(result.measured));
  // The N -> infinity ELS values, for comparison with the measured ones.
  if (const auto* continuous = dynamic_cast<const fbm::ContinuousDistribution*>(dist.get()))
    summary["els_theory"] = fbm::to_json(fbm::ElsTheory(*continuous).characteristics());
  if (load) {
    std::size_t bursts = 0;
    for (const auto& [size, count] : load->burst_counts) bursts += count;
    summary["bursts"] = bursts;
    summary["final_burst"] = load->final_burst;
    summary["bursts_file"] = bursts_path.empty() ? json(nullptr) : json(bursts_path);
  }
  if (o.json) {
    fmt::print("{}\n", summary.dump(2));
  } else {
    fmt::print("finite bundle, N = {}, seed {}, {} sharing, {} control, dist {}\n{}\n{}", o.fibers, o.seed,
               o.sharing, control, dist->spec(), units, characteristics_table(result.measured));
    if (load)
      fmt::print("  {} bursts before the final one, which broke {} fibers\n",
                 summary["bursts"].get<std::size_t>(), load->final_burst);
  }
}

void add_simulate(CLI::App& fbm_app) {
  auto* app =
      fbm_app.add_subcommand("simulate", "Simulate a finite bundle (strain- or load-controlled, ELS or LLS)");
  auto o = std::make_shared<SimulateOptions>();
  app->add_option("--dist", o->spec, "Threshold distribution (see `fbm theory --help`)")
      ->capture_default_str();
  app->add_option("--fibers", o->fibers, "Number of fibers N")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{2}, std::size_t{1} << 31));
  app->add_option("--seed", o->seed, "Random seed (same seed, same bundle on every platform)")
      ->capture_default_str();
  app->add_option("--sharing", o->sharing, "Load sharing: els (equal) or lls (nearest survivors on a ring)")
      ->capture_default_str()
      ->check(CLI::IsMember({"els", "lls"}));
  app->add_option("--control", o->control,
                  "strain (default for els) or load (default, and the only choice, for lls)")
      ->check(CLI::IsMember({"strain", "load"}));
  app->add_option("-o,--out", o->out, "CSV curve to write");
  app->add_option("--bursts", o->bursts,
                  "CSV of burst sizes (load control; default: beside --out as NAME_bursts.csv)");
  app->add_flag("--json", o->json, "Print the summary as JSON instead of a table");
  app->add_option("--points", o->points, "At most this many rows in the CSV curve")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{3}, std::size_t{100000000}));
  app->callback([o] { run_simulate(*o); });
}

}  // namespace

void add_fbm_command(CLI::App& app, int& /*exit_code*/) {
  auto* fbm_app =
      app.add_subcommand("fbm", "Fiber bundle model: ELS theory, curves and finite-bundle simulation");
  fbm_app->require_subcommand(1);
  add_theory(*fbm_app);
  add_curves(*fbm_app);
  add_simulate(*fbm_app);
}

}  // namespace rupture::cli
