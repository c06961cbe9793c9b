// cli/plot_command: `rupture plot INPUT [--out FOLDER] [--format png,svg,pdf|all] [--snapshots-at X,...]` —
// the paper's figures from a run folder, an FBM curve CSV or a scan folder, via gnuplot (src/figures).
// Exit 0 drawn, 2 bad input, 1 gnuplot missing or complaining.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "figures/figures.hpp"

namespace rupture::cli {

void add_plot_command(CLI::App& app, int& /*exit_code*/) {
  struct PlotArguments {
    std::string input, out, format = "all";
    std::vector<double> snapshot_strains;
  };
  auto options = std::make_shared<PlotArguments>();
  auto* command = app.add_subcommand("plot",
                                     "Draw the paper's figures (PNG, SVG, PDF) of a run folder, an FBM curve "
                                     "CSV or a scan folder with gnuplot");
  command
      ->add_option(
          "input", options->input,
          "Run folder (curves.csv [+ analysis.json, breaks.csv, snapshots/]), a curve CSV, or a scan folder "
          "(results.csv)")
      ->required();
  command->add_option(
      "-o,--out", options->out,
      "Folder for NAME.gp, NAME.dat, NAME.png, NAME.svg, NAME.pdf (default: figures/ beside the input)");
  command->add_option("--format", options->format,
                      "Pictures to draw: png, svg and/or pdf, comma-separated, or all (both = png,svg)");
  command
      ->add_option(
          "--snapshots-at", options->snapshot_strains,
          "Strains [%] for the bond snapshots, comma-separated (default: near x_p, x_c and the last one)")
      ->delimiter(',');
  command->callback([options] {
    const std::filesystem::path input = options->input;
    const std::filesystem::path out =
        options->out.empty() ? figures::default_out(input) : std::filesystem::path(options->out);
    figures::PlotOptions plot_options;
    plot_options.formats = figures::parse_formats(options->format);
    plot_options.snapshot_strains = options->snapshot_strains;
    for (const auto& drawn : figures::plot(input, out, plot_options)) {
      for (const auto& file : drawn.files) fmt::print("wrote {}\n", file.string());
    }
  });
}

}  // namespace rupture::cli
