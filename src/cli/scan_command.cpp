// cli/scan_command: `rupture scan SCAN.toml` — a parameter scan over (k_n, b_d): every point run and
// analysed in its own folder, in parallel on this machine or across MPI ranks, resumable; plus one
// point for a job array (--task-index), the aggregate (--collect), the ledger (--status DIR) and the
// paper's claims checked against finished scans (--claims DIR...).
// Owns option parsing and terminal text; the scan itself is src/scan.
#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "core/error.hpp"
#include "loading/run.hpp"
#include "rupture/version.hpp"
#include "scan/claims.hpp"
#include "scan/farm.hpp"
#include "scan/ledger.hpp"
#include "scan/scan.hpp"

namespace rupture::cli {

namespace {

struct ScanOptions {
  std::string target;  // SCAN.toml, or a scan folder for --collect
  std::string output;
  std::string status_folder;
  std::vector<std::string> claims_folders;
  int jobs = 0, threads = 0;
  long long task_index = -1;
  bool collect = false, dry_run = false, reanalyze = false, help_config = false;
};

std::string command_line(const ScanOptions& o) {
  std::string line = "rupture scan " + o.target;
  if (!o.output.empty()) line += " --out " + o.output;
  if (o.jobs > 0) line += fmt::format(" --jobs {}", o.jobs);
  if (o.threads > 0) line += fmt::format(" --threads {}", o.threads);
  if (o.task_index >= 0) line += fmt::format(" --task-index {}", o.task_index);
  return line;
}

// The array task index: --task-index, else SLURM_ARRAY_TASK_ID when the scheduler set it.
long long task_index(const ScanOptions& o) {
  if (o.task_index >= 0) return o.task_index;
  const char* slurm = std::getenv("SLURM_ARRAY_TASK_ID");
  if (slurm == nullptr || *slurm == '\0') return -1;
  char* end = nullptr;
  const long long index = std::strtoll(slurm, &end, 10);
  if (*end != '\0' || index < 0)
    throw InputError("SLURM_ARRAY_TASK_ID", fmt::format("'{}' is not a point index", slurm),
                     "submit the array as --array=0-(points-1), or unset it to run the whole scan");
  return index;
}

void print_plan(const scan::Plan& plan) {
  fmt::print("{:>5}  {:<32} {:>12} {:>10} {:>11} {:>13} {:>15}\n", "point", "folder", "k_n[N/mm]", "b_d[mm]",
             "ramp_steps", "max_strain[%]", "row_interval[1]");
  for (const auto& p : plan.points)
    fmt::print("{:>5}  {:<32} {:>12} {:>10} {:>11} {:>13} {:>15}\n", p.index, p.name, p.k_n, p.b_d,
               p.ramp_steps, p.max_strain, p.output_interval);
  fmt::print("{} points into {}; a job array needs --array=0-{}\n", plan.points.size(), plan.folder.string(),
             plan.points.size() - 1);
}

void run(const ScanOptions& o) {
  if (o.help_config) {
    fmt::print("{}", scan::rules_reference());
    return;
  }
  if (!o.claims_folders.empty()) {
    for (const auto& folder : o.claims_folders)
      fmt::print(
          "{}",
          scan::claims_markdown(
              scan::check_claims(scan::read_results(std::filesystem::path(folder) / "results.csv")), folder));
    return;
  }
  if (!o.status_folder.empty()) {
    fmt::print("{}", scan::status_report(scan::read_plan(o.status_folder)));
    return;
  }
  if (o.target.empty())
    throw InputError("rupture scan", "no scan config given",
                     "run `rupture scan SCAN.toml` (see docs/scan.md)");
  if (o.reanalyze) {
    if (!std::filesystem::is_directory(o.target))
      throw InputError(o.target, "--reanalyze needs a scan folder",
                       "give the folder a scan wrote ([scan] output)");
    const scan::Plan plan = scan::read_plan(o.target);
    std::size_t done = 0;
    for (const auto& point : plan.points) done += scan::reanalyze_point(plan, point);
    scan::write_aggregate(
        plan, {{"reanalysed", {{"command", command_line(o) + " --reanalyze"}, {"version", version_string}}}});
    fmt::print("re-analysed {} of {} points; wrote {}\n", done, plan.points.size(),
               (plan.folder / "results.csv").string());
    return;
  }
  if (o.collect && std::filesystem::is_directory(o.target)) {
    const scan::Plan plan = scan::read_plan(o.target);
    scan::write_aggregate(
        plan, {{"collected", {{"command", command_line(o) + " --collect"}, {"version", version_string}}}});
    fmt::print("{}", scan::status_report(plan));
    fmt::print("wrote {} and {}\n", (plan.folder / "results.csv").string(),
               (plan.folder / "scan.json").string());
    return;
  }
  scan::ScanConfig config = scan::load_scan_config(o.target);
  if (!o.output.empty()) config.output = o.output;
  const Sample sample = loading::resolve_sample(scan::base_config(config));
  const scan::Plan plan = scan::make_plan(config, sample);
  if (o.dry_run) {
    print_plan(plan);
    return;
  }
  if (o.collect) {
    scan::write_aggregate(
        plan, {{"collected", {{"command", command_line(o) + " --collect"}, {"version", version_string}}}});
    fmt::print("{}", scan::status_report(plan));
    return;
  }
  if (const long long index = task_index(o); index >= 0) {
    scan::run_task(plan, sample, std::size_t(index), o.threads, true);
    return;
  }
  scan::FarmOptions farm;
  farm.jobs = o.jobs;
  farm.threads = o.threads;
  farm.command = command_line(o);
  scan::run_scan(plan, sample, farm);
}

}  // namespace

void add_scan_command(CLI::App& app, int& /*exit_code*/) {
  auto o = std::make_shared<ScanOptions>();
  auto* cmd = app.add_subcommand("scan",
                                 "Scan bond stiffness k_n and breaking distance b_d: run and analyse every "
                                 "point, resumably, in parallel or under MPI");
  cmd->add_option("scan", o->target,
                  "Scan config (TOML; see docs/scan.md); with --collect also a scan folder");
  cmd->add_option("-o,--out,--output", o->output, "Scan folder (overrides [scan] output)");
  cmd->add_option("-j,--jobs", o->jobs, "Points run at once (default: from the core count)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("-t,--threads", o->threads, "Threads inside each run (default: the cores left per job)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--task-index", o->task_index,
                  "Run only this point (0-based; a job array's index, also read from SLURM_ARRAY_TASK_ID)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--collect", o->collect,
                "Write results.csv and scan.json from the finished points, run nothing");
  cmd->add_flag(
      "--reanalyze", o->reanalyze,
      "Analyse every finished point of a scan folder again (the runs are kept), then rewrite results.csv");
  cmd->add_option("--status", o->status_folder,
                  "Show every point of the scan in this folder: done, failed, running, pending");
  cmd->add_option("--claims", o->claims_folders,
                  "Print the paper's claims checked against each scan folder's results.csv (markdown)");
  cmd->add_flag("--dry-run", o->dry_run, "List the points with their ramp and stop strain, run nothing");
  cmd->add_flag("--help-config", o->help_config, "Print every [rules] key with its unit, range and default");
  cmd->callback([o] { run(*o); });
}

}  // namespace rupture::cli
