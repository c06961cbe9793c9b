// loading/run: the tension test from a resolved config: sample, plan (dt, checks, estimates), the
// stepping loop with its stop rules and instability checks, the outputs (curves.csv, breaks.csv,
// run.json, snapshots), when to checkpoint and how to resume. Not: the engine (dem/), the
// checkpoint file (loading/checkpoint) or the command line (cli/run_command).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "dem/system.hpp"
#include "loading/config.hpp"
#include "sample/sample.hpp"

namespace rupture::loading {

// The sample a config names: a file, a generator preset or a test lattice.
Sample resolve_sample(const RunConfig& config);

// What a run will do, worked out without stepping.
struct RunPlan {
  double dt = 0.0;           // s, the step used
  double critical_dt = 0.0;  // s, velocity-Verlet stability limit
  bool dt_auto = true;
  double stiffest_spring_sum = 0.0;   // N/mm, where the limit is reached
  double stiffest_mass = 0.0;         // t
  double ramp_time = 0.0;             // s
  double plate_separation = 0.0;      // mm, l0
  double wave_speed = 0.0;            // mm/s, longitudinal wave speed of a bond chain, r0 sqrt(k/m)
  double speed_ratio = 0.0;           // 1, plate speed / wave speed
  double first_break_strain = 0.0;    // %, dem::first_break_strain: affine estimate of the first break
  std::uint64_t estimated_steps = 0;  // to the max-strain or max-steps stop, whichever is first
  double estimated_seconds = 0.0;     // wall time at the throughput measured in docs/performance.md
  std::size_t memory_bytes = 0;
  std::vector<std::string> warnings;
};

// Throws InputError when dt exceeds the stability limit and the config does not allow it.
RunPlan plan_run(const RunConfig& config, const dem::System& system, const Sample& sample);
nlohmann::json to_json(const RunPlan& plan);
// Each stage's wall time as {"value", "unit": "s"}: run.json's and `rupture bench`'s stage_times.
nlohmann::json to_json(const dem::StageTimes& times);

struct RunSummary {
  std::string status;       // "finished", "failed" or "interrupted"
  std::string stop_reason;  // "separated", "max_strain", "max_steps", "unstable", "interrupted"
  std::uint64_t steps = 0;
  double dt = 0.0;      // s, the step used
  double strain = 0.0;  // % at the end
  double wall_seconds = 0.0;
  double max_energy_error = 0.0;  // mJ: max |W - (E_e + E_k + E_contact + E_glue + E_released + E_damped)|
  double max_relative_energy_error = 0.0;  // 1: the above / largest W so far
  std::size_t broken_bonds = 0;
  // An interrupted run (SIGINT/SIGTERM, see loading/interrupt): the signal and the checkpoint
  // written after the step it came in.
  int signal = 0;
  std::filesystem::path checkpoint;
};

// A run that became unstable: RunError's message (the step, the particle, the likely cause, a dt)
// with the run's summary (status "failed", stop_reason "unstable"), which run.json also holds.
class UnstableRun : public RunError {
 public:
  UnstableRun(const std::string& message, RunSummary ended) : RunError(message), summary(std::move(ended)) {}
  RunSummary summary;
};

// What a new run does with a folder that holds a run which ended (finished, unstable, or killed
// before its first checkpoint): refuse, naming it, or replace its outputs.
enum class Existing { refuse, overwrite };

// Where a run stands, after each curve row.
struct RunProgress {
  std::uint64_t steps = 0;
  double strain = 0.0;  // %
  double force = 0.0;   // N, on the top plate
  std::size_t broken_bonds = 0;
};

struct RunOptions {
  Existing existing = Existing::refuse;
  // The plan's warnings (a ramp too short, a plate too fast: what `rupture check` says) on stderr as
  // a new run starts, and the on-line monitor's warning on stdout as it comes, unless false (a scan runs
  // points side by side and reports each in a line of its own); run.json records both either way.
  bool echo_warnings = true;
  // Called after each curve row; returning false stops the run as SIGINT would (a checkpoint, then
  // status "interrupted"). For callers that run simulations inside another program (the Python
  // module), where the signal handlers belong to that program.
  std::function<bool(const RunProgress&)> on_row = nullptr;
};

// Runs to a stop rule, writing into `folder`. `command` is recorded in run.json and in the header
// of curves.csv and breaks.csv. Before the first step it claims the folder (InputError, and the
// folder left as it was, when it is `/`, is written by another process, holds an unfinished run,
// an ended one unless `options.existing` is overwrite, or files rupture did not write, or has no room
// for the checkpoints), and holds a lock on it to the end. Writes a checkpoint every
// checkpoint.every steps or checkpoint.minutes, and after the step in which SIGINT/SIGTERM came
// (if install_interrupt_handlers() was called) or `on_row` said stop, then returns with status
// "interrupted".
// An unstable run keeps what it wrote, marks run.json failed and throws UnstableRun naming the step,
// the particle, the likely cause and a dt; a failed write throws RunError naming the file and the
// last intact checkpoint. A finished or unstable run removes its checkpoints.
RunSummary run_simulation(const RunConfig& config, const Sample& sample, const std::filesystem::path& folder,
                          const std::string& command, const RunOptions& options = {});

// Continues the run in `folder` from its newest readable checkpoint (warning on stderr about each
// damaged newer one): the config and command stored there, the output files cut back to the
// checkpoint's byte counts and appended to, so that curves.csv and breaks.csv come out
// byte-identical to an uninterrupted run. `command` (the resuming command line) is listed under
// "resumes" in run.json. Everything is checked before anything in the folder changes; throws
// InputError, the folder untouched, when another process writes it, there is no readable
// checkpoint, the run already ended, the sample changed since the run began, or curves.csv or
// breaks.csv no longer begin with what the checkpoint recorded (their length and hash).
// `options.on_row` and `echo_warnings` apply as in run_simulation (`existing` does not).
RunSummary resume_simulation(const std::filesystem::path& folder, const std::string& command,
                             const RunOptions& options = {});

}  // namespace rupture::loading
