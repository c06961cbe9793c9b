// cli/plot_command: `rupture plot DIR_OR_FILE [--out FOLDER] [--format png|svg|both]` — the paper's
// figures from a run folder or an FBM curve CSV, via gnuplot (src/figures). Exit 0 drawn, 2 bad input,
// 1 gnuplot missing or complaining.
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "figures/figures.hpp"

namespace rupture::cli {

void add_plot_command(CLI::App& app, int& /*exit_code*/) {
  struct PlotOptions {
    std::string input, out, format = "both";
  };
  auto options = std::make_shared<PlotOptions>();
  auto* command = app.add_subcommand(
      "plot", "Draw the loading-curve figures (PNG/SVG) of a run folder or an FBM curve CSV with gnuplot");
  command->add_option("input", options->input, "Run folder (curves.csv [+ analysis.json, breaks.csv]) or a curve CSV")
      ->required();
  command->add_option("--out", options->out, "Folder for NAME.gp, NAME.dat, NAME.png, NAME.svg (default: figures/ beside the input)");
  command->add_option("--format", options->format, "png, svg or both")->check(CLI::IsMember({"png", "svg", "both"}));
  command->callback([options] {
    const std::filesystem::path input = options->input;
    const std::filesystem::path out = options->out.empty() ? figures::default_out(input) : std::filesystem::path(options->out);
    for (const auto& file : figures::plot(input, out, figures::parse_format(options->format))) {
      fmt::print("wrote {}\n", file.string());
    }
  });
}

}  // namespace rupture::cli
