// cli/sample_command: `rupture sample generate | info | convert`: make the standard tissue or any
// packing, print a sample's statistics, and move samples between rupture, LAMMPS, ESyS-Particle and
// ParaView files.
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/commands.hpp"
#include "io/quantity.hpp"
#include "rupture/version.hpp"
#include "sample/formats.hpp"
#include "sample/generator.hpp"
#include "sample/presets.hpp"
#include "sample/stats.hpp"

namespace rupture::cli {

namespace {

void print_stats(const std::string& title, const SampleStats& s, const Sample& sample) {
  const Vec3 size = sample.box.size();
  fmt::print("{}\n", title);
  fmt::print("  particles          {}\n", s.particles);
  fmt::print("  bonds              {}\n", s.bonds);
  fmt::print("  box                {} x {} x {} mm (width x, height y, depth z)\n", size.x, size.y, size.z);
  fmt::print("  solid fraction     {:.4f}\n", s.solid_fraction);
  fmt::print("  mean coordination  {:.3f} bonds per particle ({} without any bond)\n", s.mean_coordination,
             s.isolated);
  fmt::print("  radius             min {:.4f}, mean {:.4f}, max {:.4f} mm\n", s.r_min, s.r_mean, s.r_max);
  fmt::print("  glued layers       bottom {} particles, top {} particles\n", s.bottom_layer, s.top_layer);
  fmt::print("  largest overlap    {:.3g} mm\n", s.max_overlap);
  fmt::print("  mass               {:.6g} g (density {} g/mm^3)\n", s.total_mass, sample.density);
  fmt::print("  radius histogram   [mm]  particles\n");
  std::size_t peak = 1;
  for (auto c : s.radius_histogram) peak = std::max(peak, c);
  for (std::size_t b = 0; b < s.radius_histogram.size(); ++b)
    fmt::print("    {:.3f}-{:.3f}  {:>8}  {}\n", s.radius_bin_edges[b], s.radius_bin_edges[b + 1],
               s.radius_histogram[b], std::string(40 * s.radius_histogram[b] / peak, '#'));
}

nlohmann::json provenance_json(const std::string& command) {
  return {{"tool", "rupture"}, {"version", version_string}, {"command", command}};
}

}  // namespace

namespace {

struct GenerateOptions {
  std::string preset, out, format;
  std::uint64_t seed = 1;
  PackingParams params;
  bool json = false;
};

// Generates, saves and reports a sample with `params` (the preset's, with the options given).
void run_generate(const GenerateOptions& options, const PackingParams& params) {
  const SampleFormat format =
      options.format.empty() ? sample_format_for_path(options.out) : sample_format_from_name(options.format);

  GenerationReport report;
  const auto start = std::chrono::steady_clock::now();
  Sample sample = generate_sample(params, options.seed, &report);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.preset.empty())
    sample.provenance.insert(sample.provenance.begin() + 1, "preset: " + options.preset);
  save_sample(sample, options.out, format);

  const SampleStats stats = compute_stats(sample);
  if (options.json) {
    auto doc = provenance_json("sample generate");
    doc["inputs"] = {{"preset", options.preset},
                     {"seed", options.seed},
                     {"out", options.out},
                     {"format", sample_format_name(format)},
                     {"box", io::quantity({params.size.x, params.size.y, params.size.z}, "mm")},
                     {"r_min", io::quantity(params.r_min, "mm")},
                     {"r_max", io::quantity(params.r_max, "mm")},
                     {"r_median", io::quantity(params.r_median, "mm")},
                     {"r_sigma", params.r_sigma},
                     {"bond_tolerance", params.bond_tolerance},
                     {"fill_rate", params.min_fill_rate},
                     {"density", io::quantity(params.density, "g/mm^3")}};
    doc["sample"] = to_json(stats);
    doc["generation"] = {{"drawn_placed", report.drawn_placed},
                         {"gap_filled", report.gap_filled},
                         {"draws", report.draws},
                         {"positions_tried", report.positions_tried},
                         {"solid_fraction_after_drawn", report.solid_fraction_drawn},
                         {"wall_time", io::quantity(seconds, "s")}};
    fmt::print("{}\n", doc.dump(2));
  } else {
    print_stats(fmt::format("sample {} ({} format, seed {}, {:.2f} s)", options.out,
                            sample_format_name(format), options.seed, seconds),
                stats, sample);
    fmt::print(
        "  generation         {} drawn radii placed of {} drawn (solid fraction {:.4f}), then {} gap "
        "fillers\n",
        report.drawn_placed, report.draws, report.solid_fraction_drawn, report.gap_filled);
  }
}

// `rupture sample generate`: a new packing from a preset or explicit box and radii.
void add_generate(CLI::App* sample_cmd) {
  auto gen = std::make_shared<GenerateOptions>();
  auto* generate = sample_cmd->add_subcommand(
      "generate", "Generate a dense random bonded packing (GenGeo-style insertion)");
  generate->add_option("--preset", gen->preset,
                       "Named sample: tissue (80x25x5 mm, ~25k particles) or tissue-small");
  generate->add_option("--seed", gen->seed, "Random seed (same seed, same sample, byte for byte)")
      ->required();
  generate
      ->add_option("-o,--out", gen->out,
                   "Output file; format from the extension (.sample own, .data LAMMPS, "
                   ".geo LSMGeometry, .vtp VTK) unless --format")
      ->required();
  generate->add_option("--format", gen->format, "own | lammps | lsm | vtp");
  auto* width = generate->add_option("--width", gen->params.size.x, "Box width along x (mm)");
  auto* height =
      generate->add_option("--height", gen->params.size.y, "Box height along y, the loading direction (mm)");
  auto* depth = generate->add_option("--depth", gen->params.size.z, "Box depth along z (mm)");
  auto* r_min = generate->add_option("--r-min", gen->params.r_min, "Smallest radius (mm)");
  auto* r_max = generate->add_option("--r-max", gen->params.r_max, "Largest radius (mm)");
  auto* r_median = generate->add_option("--r-median", gen->params.r_median,
                                        "Median of the log-normal radius distribution (mm)");
  auto* r_sigma = generate->add_option("--r-sigma", gen->params.r_sigma, "Standard deviation of ln r (1)");
  auto* tolerance =
      generate->add_option("--bond-tolerance", gen->params.bond_tolerance,
                           "Bond pairs whose surface gap is below this times their mean radius (1)");
  auto* fill = generate->add_option(
      "--fill-rate", gen->params.min_fill_rate,
      "Gap filling stops once fewer than this fraction of random positions admit a sphere (1)");
  auto* density = generate->add_option("--density", gen->params.density, "Particle density (g/mm^3)");
  generate->add_flag("--json", gen->json, "Print the statistics as JSON");
  generate->callback([gen, width, height, depth, r_min, r_max, r_median, r_sigma, tolerance, fill, density] {
    PackingParams params = gen->preset.empty() ? PackingParams{} : preset_params(gen->preset);
    // Options given on the command line override the preset.
    const auto take = [](CLI::Option* option, auto& field, const auto& value) {
      if (option->count() > 0) field = value;
    };
    take(width, params.size.x, gen->params.size.x);
    take(height, params.size.y, gen->params.size.y);
    take(depth, params.size.z, gen->params.size.z);
    take(r_min, params.r_min, gen->params.r_min);
    take(r_max, params.r_max, gen->params.r_max);
    take(r_median, params.r_median, gen->params.r_median);
    take(r_sigma, params.r_sigma, gen->params.r_sigma);
    take(tolerance, params.bond_tolerance, gen->params.bond_tolerance);
    take(fill, params.min_fill_rate, gen->params.min_fill_rate);
    take(density, params.density, gen->params.density);
    run_generate(*gen, params);
  });
}

// `rupture sample info`: a sample's statistics.
void add_info(CLI::App* sample_cmd) {
  auto info_file = std::make_shared<std::string>();
  auto info_json = std::make_shared<bool>(false);
  auto* info = sample_cmd->add_subcommand("info", "Print a sample's statistics (any format rupture reads)");
  info->add_option("file", *info_file, "Sample file (own, LAMMPS data, LSMGeometry)")->required();
  info->add_flag("--json", *info_json, "Print the statistics as JSON");
  info->callback([info_file, info_json] {
    const Sample sample = load_sample(*info_file);
    const SampleStats stats = compute_stats(sample);
    if (*info_json) {
      auto doc = provenance_json("sample info");
      doc["inputs"] = {{"file", *info_file}};
      doc.update(to_json(stats));
      fmt::print("{}\n", doc.dump(2));
    } else {
      print_stats("sample " + *info_file, stats, sample);
    }
  });
}

// `rupture sample convert`: a sample from one format into another.
void add_convert(CLI::App* sample_cmd) {
  struct ConvertOptions {
    std::string in, out, format;
  };
  auto conv = std::make_shared<ConvertOptions>();
  auto* convert = sample_cmd->add_subcommand(
      "convert", "Convert a sample between formats (own, LAMMPS data, LSMGeometry, VTK)");
  convert->add_option("in", conv->in, "Input sample file")->required();
  convert->add_option("out", conv->out, "Output file; format from the extension unless --format")->required();
  convert->add_option("--format", conv->format, "own | lammps | lsm | vtp");
  convert->callback([conv] {
    const SampleFormat format =
        conv->format.empty() ? sample_format_for_path(conv->out) : sample_format_from_name(conv->format);
    Sample sample = load_sample(conv->in);
    sample.provenance.push_back(fmt::format("converted by rupture {} from {}", version_string, conv->in));
    save_sample(sample, conv->out, format);
    fmt::print("wrote {} ({} format): {} particles, {} bonds\n", conv->out, sample_format_name(format),
               sample.size(), sample.bonds.size());
  });
}

}  // namespace

void add_sample_command(CLI::App& app, int& /*exit_code*/) {
  auto* sample_cmd = app.add_subcommand("sample", "Make, inspect and convert bonded particle samples");
  sample_cmd->require_subcommand(1);
  add_generate(sample_cmd);
  add_info(sample_cmd);
  add_convert(sample_cmd);
}

}  // namespace rupture::cli
