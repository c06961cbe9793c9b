#include "loading/run.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>

#include "analysis/monitor.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/units.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/csv_stream.hpp"
#include "io/file_lock.hpp"
#include "io/vtk.hpp"
#include "loading/checkpoint.hpp"
#include "loading/interrupt.hpp"
#include "loading/ramp.hpp"
#include "loading/separation.hpp"
#include "rupture/version.hpp"
#include "sample/checks.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"
#include "sample/presets.hpp"
#include "sample/stats.hpp"

namespace rupture::loading {

namespace {

// Whole-step throughput used for time estimates (particle-steps/s on 2 threads, intact tissue),
// as measured by `rupture bench` (docs/performance.md).
constexpr double assumed_particle_steps_per_s = 2e7;

const std::vector<std::string> curve_header = {"time[s]",
                                               "step[1]",
                                               "strain[%]",
                                               "force_top[N]",
                                               "force_bottom[N]",
                                               "elastic_energy[mJ]",
                                               "kinetic_energy[mJ]",
                                               "contact_energy[mJ]",
                                               "glue_energy[mJ]",
                                               "plate_work[mJ]",
                                               "released_energy[mJ]",
                                               "damping_energy[mJ]",
                                               "intact_bonds[1]",
                                               "broken_bonds[1]",
                                               "contacts[1]"};
const std::vector<std::string> break_header = {"step[1]",         "time[s]",   "strain[%]", "particle_a[1]",
                                               "particle_b[1]",   "x[mm]",     "y[mm]",     "z[mm]",
                                               "rest_length[mm]", "energy[mJ]"};

// One ParaView snapshot: particles (id, radius, group, velocity) in sample order and the intact
// bonds with their extension r - r0 (mm) and relative extension (r - r0) / r0.
void write_snapshot(const dem::System& system, const Sample& sample, const std::filesystem::path& path,
                    const std::string& provenance) {
  io::VtkPolyData data;
  data.comments = {provenance};
  std::vector<double> radius(sample.size()), velocity(3 * sample.size());
  std::vector<std::int64_t> ids(sample.size()), groups(sample.size());
  data.points.resize(sample.size());
  for (std::size_t a = 0; a < sample.size(); ++a) {
    data.points[a] = system.position(a);
    const Vec3 v = system.velocity(a);
    velocity[3 * a] = v.x;
    velocity[3 * a + 1] = v.y;
    velocity[3 * a + 2] = v.z;
    radius[a] = sample.radius[a];
    ids[a] = sample.id[a];
    groups[a] = static_cast<std::int64_t>(sample.group[a]);
  }
  std::vector<double> extension, relative;
  for (std::size_t b = 0; b < sample.bonds.size(); ++b) {
    if (!system.bond_intact(b)) continue;
    data.lines.push_back({sample.bonds[b].i, sample.bonds[b].j});
    extension.push_back(system.bond_extension(b));
    relative.push_back(extension.back() / sample.bonds[b].rest_length);
  }
  data.point_data = {
      {"id", 1, ids}, {"radius_mm", 1, radius}, {"group", 1, groups}, {"velocity_mm_per_s", 3, velocity}};
  data.line_data = {{"extension_mm", 1, extension}, {"relative_extension", 1, relative}};
  io::write_vtp(path, data);
}

Sample build_sample(const RunConfig& config) {
  if (!config.sample_lattice.empty()) {
    const auto& n = config.lattice_cells;
    const double density = config.density.value_or(default_density);
    if (config.sample_lattice == "chain")
      return make_chain(std::uint32_t(n[1]), config.lattice_radius, density);
    return make_cubic_block(std::uint32_t(n[0]), std::uint32_t(n[1]), std::uint32_t(n[2]),
                            config.lattice_radius, density);
  }
  if (!config.sample_preset.empty()) return make_preset(config.sample_preset, config.seed);
  // A relative sample path is read from the config file's folder, so configs travel with samples.
  std::filesystem::path file = config.sample_file;
  if (file.is_relative()) file = config.config_file.parent_path() / file;
  if (!std::filesystem::exists(file))
    throw InputError(config.config_file.string() + ": sample.file", "no such file: " + file.string(),
                     "give a path relative to the config's folder, or an absolute one");
  return load_sample(file);
}

}  // namespace

Sample resolve_sample(const RunConfig& config) {
  Sample sample = build_sample(config);
  const std::string source = !config.sample_file.empty()     ? config.sample_file
                             : !config.sample_preset.empty() ? "preset " + config.sample_preset
                                                             : "lattice " + config.sample_lattice;
  check_sample(sample, source);
  return sample;
}

RunPlan plan_run(const RunConfig& config, const dem::System& system, const Sample& sample) {
  RunPlan plan;
  plan.critical_dt = system.critical_dt();
  plan.stiffest_spring_sum = system.stiffest_spring_sum();
  plan.stiffest_mass = system.stiffest_mass();
  plan.dt_auto = !config.dt.has_value();
  plan.dt = config.dt.value_or(config.dt_safety * plan.critical_dt);
  if (!plan.dt_auto && plan.dt > plan.critical_dt) {
    const std::string message = fmt::format(
        "dt = {:.3g} s exceeds the stability limit {:.3g} s for k_n = {:g} N/mm (stiffest particle: springs "
        "summing "
        "to {:.3g} N/mm on {:.3g} g)",
        plan.dt, plan.critical_dt, config.bond_stiffness, plan.stiffest_spring_sum,
        units::mass_to_grams(plan.stiffest_mass));
    if (!config.allow_unstable_dt)
      throw InputError(
          config.config_file.string() + ": time.dt", message,
          fmt::format("use dt <= {:.3g}, dt = \"auto\", or time.allow_unstable_dt = true", plan.critical_dt));
    plan.warnings.push_back(message + " (allowed by time.allow_unstable_dt)");
  }
  plan.ramp_time = double(config.ramp_steps) * plan.dt;
  plan.plate_separation = system.initial_plate_separation();
  const dem::Params params = config.dem_params(sample.density);
  plan.wave_speed = dem::wave_speed(sample, params);
  plan.speed_ratio = config.speed / plan.wave_speed;
  plan.first_break_strain = 100.0 * dem::first_break_strain(sample, params);
  // Steps to reach max_strain: the ramp covers speed * T / 2, then constant speed.
  const double target = plan.plate_separation * config.max_strain / 100.0;
  const double ramp_distance = 0.5 * config.speed * plan.ramp_time;
  const double steps_to_target =
      target <= ramp_distance
          ? double(config.ramp_steps)
          : double(config.ramp_steps) + (target - ramp_distance) / (config.speed * plan.dt);
  plan.estimated_steps = std::uint64_t(std::min(steps_to_target, double(config.max_steps)));
  plan.estimated_seconds =
      double(plan.estimated_steps) * double(sample.size()) / assumed_particle_steps_per_s;
  plan.memory_bytes = system.memory_bytes();
  if (plan.speed_ratio > 0.01)
    plan.warnings.push_back(
        fmt::format("plate speed is {:.2g} of the wave speed {:.3g} mm/s: loading is far from "
                    "quasi-static; lower loading.speed",
                    plan.speed_ratio, plan.wave_speed));
  if (plan.dt_auto && config.dt_safety > 0.7)
    plan.warnings.push_back(
        "time.safety above 0.7 leaves little margin for contacts, which the limit does not count");
  if (config.ramp_steps < 1000)
    plan.warnings.push_back(
        "a ramp shorter than 1000 steps sends a shock through the sample; raise loading.ramp_steps");
  return plan;
}

nlohmann::json to_json(const RunPlan& plan) {
  return {{"dt_s", plan.dt},
          {"dt_auto", plan.dt_auto},
          {"critical_dt_s", plan.critical_dt},
          {"stiffest_spring_sum_N_per_mm", plan.stiffest_spring_sum},
          {"stiffest_mass_g", units::mass_to_grams(plan.stiffest_mass)},
          {"ramp_time_s", plan.ramp_time},
          {"plate_separation_mm", plan.plate_separation},
          {"wave_speed_mm_per_s", plan.wave_speed},
          {"plate_to_wave_speed", plan.speed_ratio},
          {"first_break_strain_estimate_percent", plan.first_break_strain},
          {"estimated_steps", plan.estimated_steps},
          {"estimated_wall_s", plan.estimated_seconds},
          {"memory_bytes", plan.memory_bytes},
          {"warnings", plan.warnings}};
}

namespace {

// A particle that moves more than this part of its own radius in one step is taken as a blow-up:
// at the automatic dt a particle moves far less (the plates' step is 1e-5 radii), while a runaway
// mode grows by orders of magnitude within a few steps, so the exact value hardly matters.
constexpr double max_step_move = 0.5;  // 1, of the particle's radius

// What `rupture run` leaves in its folder, and what analyze, plot and report add about that run:
// the files --overwrite removes (and nothing else, so a user's own files beside them survive).
const std::vector<std::string> run_outputs = {"run.json",      "curves.csv",  "breaks.csv",  "snapshots.pvd",
                                              "analysis.json", "report.html", "checkpoints", "snapshots",
                                              "figures",       "run.log"};

// A folder's run.json, if rupture run wrote one there (null otherwise, also when unreadable).
nlohmann::json read_run_record(const std::filesystem::path& folder) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(folder / "run.json", ec)) return nullptr;
  try {
    auto record = nlohmann::json::parse(io::read_text_file(folder / "run.json"));
    if (record.is_object() && record.value("tool", "") == "rupture run") return record;
  } catch (const std::exception&) {
  }
  return nullptr;
}

// A run that cannot go on: it finished, or blew up (the same config would blow up again).
bool has_ended(const nlohmann::json& record) {
  const std::string status = record.value("status", "");
  return status == "finished" || (status == "failed" && record.value("stop_reason", "") == "unstable");
}

// The folder of a new run, claimed before the first step: not `/`, created, locked against other
// writers, free of a run that could still be resumed, of a run that ended (unless `existing` says
// overwrite) and of files rupture did not write, writable, and with room for its checkpoints. A
// refusal leaves the folder as it was (one it created is removed again).
std::unique_ptr<io::FolderLock> claim_new_folder(const std::filesystem::path& folder, const RunConfig& config,
                                                 const dem::System& system, const std::string& command,
                                                 Existing existing) {
  namespace fs = std::filesystem;
  const std::string fix = "choose a writable folder with -o/--out or output.folder";
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  if (!ec && resolved == resolved.root_path())
    throw InputError(folder.string(), "is the root folder; a run writes a dozen files into its folder",
                     "give a folder of its own, e.g. -o run");
  const bool existed = fs::exists(folder, ec);
  fs::create_directories(folder, ec);
  if (ec)
    throw InputError(folder.string(), fmt::format("cannot create the output folder ({})", ec.message()), fix);
  auto lock = std::make_unique<io::FolderLock>(folder, command);
  const auto refuse = [&](const std::string& problem, const std::string& remedy) {
    lock.reset();
    if (!existed) fs::remove_all(folder, ec);
    throw InputError(folder.string(), problem, remedy);
  };
  const nlohmann::json record = read_run_record(folder);
  if (record.is_null()) {
    for (const auto& entry : fs::directory_iterator(folder, ec))
      if (entry.path().filename() != io::folder_lock_name)
        refuse(fmt::format("holds files that rupture run did not write (e.g. {})",
                           entry.path().filename().string()),
               "give an empty or new folder with -o/--out or output.folder");
  } else if (!has_ended(record) && !list_checkpoints(folder).empty()) {
    refuse("holds the checkpoints of an unfinished run",
           fmt::format("continue it with `rupture run --resume {}`, or remove {} to start over",
                       folder.string(), (folder / "checkpoints").string()));
  } else if (existing == Existing::refuse) {
    const std::string status = record.value("status", "");
    refuse(has_ended(record) || status == "failed"
               ? fmt::format("holds a {} run ({}), which is kept", status, record.value("stop_reason", ""))
               : "holds a run that was stopped before its first checkpoint, which is kept",
           "give --overwrite to replace it, or choose another folder with -o/--out");
  } else {
    for (const auto& name : run_outputs) fs::remove_all(folder / name, ec);
  }
  // A checkpoint is the engine state plus a little text; the newest `keep` stay while one more is
  // written. The curve files are small beside them.
  const double checkpoint_bytes = double(system.state_bytes()) + 65536.0;
  const double needed = double(config.checkpoint_keep + 1) * checkpoint_bytes;
  const auto space = fs::space(folder, ec);
  if (!ec && double(space.available) < needed)
    refuse(fmt::format("has {:.3g} MB free, but {} checkpoints of {:.3g} MB need {:.3g} MB",
                       double(space.available) / 1e6, config.checkpoint_keep + 1, checkpoint_bytes / 1e6,
                       needed / 1e6),
           "free space, choose another output folder, or lower checkpoint.keep");
  return lock;
}

analysis::MonitorOptions monitor_options(const RunConfig& config) {
  return {.window = std::size_t(config.monitor_window),
          .drop = config.monitor_drop,
          .confirm = std::size_t(config.monitor_confirm)};
}

// The monitor's state at a checkpoint: it has only ever seen the curves.csv rows, so feed them
// again (the file holds the shortest text that reads back to each double, so the bits match).
// Only the part the checkpoint recorded is read.
void replay(analysis::Monitor& monitor, const std::filesystem::path& curves_file, const LoopState& loop) {
  const std::string text = io::read_text_file(curves_file);
  const io::CsvTable curves =
      io::parse_csv(std::string_view(text).substr(0, loop.curves_bytes), curves_file.string());
  if (curves.rows() != loop.curves_rows)
    throw InputError(
        curves_file.string(),
        fmt::format("holds {} rows where its checkpoint recorded {}", curves.rows(), loop.curves_rows),
        "the run folder was changed after the checkpoint; restore it, or remove its checkpoints and start "
        "over "
        "with --overwrite");
  const auto& strain = curves.column("strain");
  const auto& force = curves.column("force_top");
  const auto& energy = curves.column("elastic_energy");
  for (std::size_t r = 0; r < loop.curves_rows; ++r) (void)monitor.add_point(strain[r], force[r], energy[r]);
}

// What a resume starts from: the checkpoint with its file and warnings, the resuming command, and
// the folder's lock, taken before anything in it was read.
struct ResumePoint {
  const LoadedCheckpoint& loaded;
  std::string command;  // the resuming command line
  std::unique_ptr<io::FolderLock>& lock;
};

RunSummary execute(const RunConfig& config, const Sample& sample, const std::filesystem::path& folder,
                   const std::string& command, const RunOptions& options, ResumePoint* resume) {
  const auto wall_start = std::chrono::steady_clock::now();
  omp_set_num_threads(int(config.threads));
  const dem::Params params = config.dem_params(sample.density);
  dem::System system(sample, params);
  // What the sample holds before the first step (bonds whose rest lengths differ from the initial
  // distances: a pre-stressed sample, e.g. LAMMPS's binned rest lengths). The energy balance counts
  // from it: W = (E now) - (E at the start). Taken from the sample, so a resumed run has it too.
  const dem::Energies start_energies = system.energies();
  const double initial_energy = start_energies.elastic + start_energies.contact + start_energies.glue;
  const RunPlan plan = plan_run(config, system, sample);
  const SpeedRamp ramp{config.speed, plan.ramp_time};
  const double l0 = plan.plate_separation;
  const std::uint64_t fingerprint = sample_fingerprint(sample);
  const std::filesystem::path curves_file = folder / "curves.csv", breaks_file = folder / "breaks.csv";

  LoopState loop;
  nlohmann::json resumes = nlohmann::json::array();
  std::unique_ptr<io::FolderLock> lock;
  std::unique_ptr<io::CsvStream> curves, breaks;
  analysis::Monitor monitor(monitor_options(config));
  if (resume != nullptr) {
    lock = std::move(resume->lock);
    const Checkpoint& c = resume->loaded.checkpoint;
    system.restore_state(c.engine, resume->loaded.file.string());
    loop = c.loop;
    // Everything is checked before a byte of the folder changes: both files still begin with
    // exactly what the checkpoint saw, and the monitor replays from that part.
    const io::FilePrefix curves_prefix{loop.curves_bytes, loop.curves_hash},
        breaks_prefix{loop.breaks_bytes, loop.breaks_hash};
    for (const auto& [file, prefix] :
         {std::pair{curves_file, curves_prefix}, std::pair{breaks_file, breaks_prefix}})
      if (const auto mismatch = io::prefix_mismatch(file, prefix, c.format >= 2))
        throw InputError(
            file.string(), *mismatch,
            "the run folder was changed after the checkpoint; restore it, or remove its checkpoints "
            "and start over with --overwrite");
    if (config.monitor) replay(monitor, curves_file, loop);
    curves = std::make_unique<io::CsvStream>(curves_file, curves_prefix);
    breaks = std::make_unique<io::CsvStream>(breaks_file, breaks_prefix);
    // Earlier resumes stay listed in run.json.
    try {
      const auto before = nlohmann::json::parse(io::read_text_file(folder / "run.json"));
      if (before.contains("resumes") && before["resumes"].is_array()) resumes = before["resumes"];
    } catch (const std::exception&) {  // an unreadable run.json loses only that list
    }
    resumes.push_back({{"command", resume->command},
                       {"checkpoint", resume->loaded.file.string()},
                       {"step", c.engine.step},
                       {"warnings", resume->loaded.warnings}});
  } else {
    lock = claim_new_folder(folder, config, system, command, options.existing);
  }

  nlohmann::json report = {{"tool", "rupture run"},
                           {"version", version_string},
                           {"command", command},
                           {"config", to_json(config)},
                           {"sample", to_json(compute_stats(sample))},
                           {"plan", to_json(plan)},
                           {"threads", config.threads},
                           {"status", "running"}};
  if (!resumes.empty()) report["resumes"] = resumes;
  try {
    io::write_json_atomically(folder / "run.json", report);
  } catch (const RunError& e) {
    throw InputError(folder.string(), fmt::format("is not writable ({})", e.what()),
                     "choose a writable folder with -o/--out or output.folder");
  }
  if (resume == nullptr) {
    // The header names the command that started the run; a resume keeps it, so the files of an
    // interrupted run are byte for byte those of an uninterrupted one.
    const std::vector<std::string> comments = {
        fmt::format("rupture {} run: {}", version_string, command),
        "strain = plate displacement / initial plate separation * 100 %; forces positive in tension"};
    curves = std::make_unique<io::CsvStream>(curves_file, comments, curve_header);
    breaks = std::make_unique<io::CsvStream>(breaks_file, comments, break_header);
  }

  RunSummary summary;
  summary.max_energy_error = loop.max_energy_error;
  summary.max_relative_energy_error = loop.max_relative_energy_error;
  const auto strain_now = [&] { return 100.0 * system.top_plate().displacement / l0; };
  std::string instability;      // what gave the instability away, naming the particle ("" while stable)
  bool stop_requested = false;  // options.on_row said stop
  const auto record = [&] {
    const dem::Energies e = system.energies();
    const double w = system.plate_work();
    // Energy gained since the start: what the plates' work must pay for.
    const double total = e.elastic + e.kinetic + e.contact + e.glue + system.released_energy() +
                         system.damping_energy() - initial_energy;
    curves->row({system.time(), double(system.steps_done()), strain_now(), system.force_top(),
                 system.force_bottom(), e.elastic, e.kinetic, e.contact, e.glue, w, system.released_energy(),
                 system.damping_energy(), double(system.intact_bonds()),
                 double(system.bond_count() - system.intact_bonds()), double(e.contacts)});
    curves->flush();
    ++loop.curves_rows;
    loop.last_recorded = system.steps_done();
    if (config.monitor) {
      const auto warning = monitor.add_point(strain_now(), system.force_top(), e.elastic);
      if (warning && options.echo_monitor) {
        fmt::print(
            "monitor: warning at strain {:.4g} %: energy-rate maximum passed (x_p = {:.4g} %) while the "
            "force "
            "still rises; predicted x_c in [{:.4g}, {:.4g}] %\n",
            warning->strain, warning->x_p, warning->x_c.low, warning->x_c.high);
        if (!warning->in_time)
          fmt::print(
              "monitor: the rows are too far apart to warn in time (the warning comes after the earliest "
              "predicted "
              "x_c); output.interval giving rows at most {:.3g} % apart would have warned before it\n",
              warning->max_row_spacing);
      }
    }
    if (options.on_row && !options.on_row({system.steps_done(), strain_now(), system.force_top(),
                                           std::size_t(system.bond_count() - system.intact_bonds())}))
      stop_requested = true;
    loop.max_work = std::max(loop.max_work, std::abs(w));
    const double error = std::abs(w - total);
    if (std::isfinite(error)) {
      summary.max_energy_error = std::max(summary.max_energy_error, error);
      // Relative to the energy in play: the plates' work, or a pre-stressed sample's own energy.
      const double scale = std::max(loop.max_work, initial_energy);
      if (scale > 0.0) summary.max_relative_energy_error = summary.max_energy_error / scale;
    }
    // Energy appearing from nowhere (kinetic energy growing without the plates' work to pay for
    // it): the balance broken by half of what was put in, and by more than the energy of a 1e-6
    // strain, k_n l0^2 1e-12, so that rounding at rest is never mistaken for it.
    const double floor = 1e-12 * params.bond_stiffness * l0 * l0;
    if (!std::isfinite(total) || !std::isfinite(w))
      instability = "energies are no longer finite numbers";
    else if (error > 0.5 * std::max({loop.max_work, total, initial_energy}) && error > floor)
      instability = fmt::format(
          "the energy balance broke down: the plates did {:.4g} mJ of work but the sample gained and "
          "released "
          "{:.4g} mJ (kinetic {:.4g} mJ)",
          w, total, e.kinetic);
    if (instability.empty()) return true;
    instability += fmt::format(", fastest particle id {}", sample.id[system.sample_index_of_largest_speed()]);
    return false;
  };

  const auto snapshot = [&] {
    const std::string name = fmt::format("snapshots/step_{:010d}.vtp", system.steps_done());
    std::filesystem::create_directories(folder / "snapshots");
    write_snapshot(system, sample, folder / name,
                   fmt::format("rupture {} run: {}; step {}, strain {:.6g} %", version_string, command,
                               system.steps_done(), strain_now()));
    loop.snapshots.push_back({system.time(), name});
    io::write_pvd(folder / "snapshots.pvd", loop.snapshots);
  };

  const double wall_before = loop.wall_seconds;
  const auto wall_now = [&] {
    return wall_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  };
  std::filesystem::path last_checkpoint = resume != nullptr ? resume->loaded.file : std::filesystem::path();
  auto last_checkpoint_time = std::chrono::steady_clock::now();
  const auto checkpoint = [&] {
    Checkpoint c;
    c.version = version_string;
    c.command = command;
    c.config_file = config.config_file.string();
    c.config_json = to_json(config).dump();
    c.sample_fingerprint = fingerprint;
    const io::FilePrefix curves_written = curves->sync(), breaks_written = breaks->sync();
    loop.curves_bytes = curves_written.bytes;
    loop.curves_hash = curves_written.hash;
    loop.breaks_bytes = breaks_written.bytes;
    loop.breaks_hash = breaks_written.hash;
    loop.max_energy_error = summary.max_energy_error;
    loop.max_relative_energy_error = summary.max_relative_energy_error;
    loop.wall_seconds = wall_now();
    c.loop = loop;
    c.engine = system.save_state();
    last_checkpoint = save_checkpoint(folder, c, std::size_t(config.checkpoint_keep));
    last_checkpoint_time = std::chrono::steady_clock::now();
  };
  const auto checkpoint_due = [&](std::uint64_t done) {
    if (config.checkpoint_every > 0 && done % std::uint64_t(config.checkpoint_every) == 0) return true;
    return config.checkpoint_minutes > 0.0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint_time).count() >=
               60.0 * config.checkpoint_minutes;
  };

  // run.log: a line a minute and one at the end (steps, rate, ETA, strain, breaks), for batch jobs.
  Progress progress("run", double(plan.estimated_steps), folder / "run.log");
  UnionFind sets;
  LoadFreeWatch load_free(config.load_free_fraction, config.load_free_strain, loop.load_free);
  bool stable = true;
  int signal = 0;
  try {
    if (resume == nullptr) {
      if (config.snapshot_interval > 0) snapshot();
      stable = record();
    }
    while (stable) {
      const std::uint64_t n = system.steps_done();
      if (n >= std::uint64_t(config.max_steps)) {
        summary.stop_reason = "max_steps";
        break;
      }
      system.step(plan.dt, ramp.at(double(n + 1) * plan.dt));
      if (const dem::StepMove& move = system.last_step_move(); !(move.fraction <= max_step_move)) {
        instability = fmt::format("particle id {} moved {:.3g} of its radius in one step (more than {:g})",
                                  sample.id[move.sample_index], move.fraction, max_step_move);
        stable = false;
        break;
      }
      load_free.add(system.force_top());
      auto& events = system.break_events();
      if (!events.empty()) {
        for (const auto& ev : events)
          breaks->row({double(ev.step), system.time(), strain_now(), double(sample.id[ev.i]),
                       double(sample.id[ev.j]), ev.midpoint.x, ev.midpoint.y, ev.midpoint.z, ev.rest_length,
                       ev.energy});
        breaks->flush();
        events.clear();
      }
      const std::uint64_t done = n + 1;
      const double strain = strain_now();
      if (done % std::uint64_t(config.output_interval) == 0 && !(stable = record())) break;
      if (config.snapshot_interval > 0 && done % std::uint64_t(config.snapshot_interval) == 0) snapshot();
      if (!loop.separated && done % std::uint64_t(config.separation_check_interval) == 0) {
        const bool broken = system.intact_bonds() < system.bond_count();
        if (separated(system, sets))
          loop.separation_rule = "connectivity";
        else if (load_free.check(strain, broken))
          loop.separation_rule = "load_free";
        loop.separated = !loop.separation_rule.empty();
        loop.separation_strain = strain;
      }
      if (config.stop_at_separation && loop.separated &&
          strain >= loop.separation_strain + config.extra_strain) {
        summary.stop_reason = "separated";
        break;
      }
      if (strain >= config.max_strain) {
        summary.stop_reason = "max_strain";
        break;
      }
      // Everything of this step is written: a checkpoint here resumes at the next one.
      signal = pending_interrupt();
      if (signal == 0 && stop_requested) signal = SIGINT;
      if (signal != 0 || checkpoint_due(done)) {
        loop.load_free = load_free.state();
        checkpoint();
      }
      if (signal != 0) {
        summary.stop_reason = "interrupted";
        break;
      }
      progress.update_with(double(done), [&] {
        return fmt::format("strain {:.3f} %, {} broken", strain, system.bond_count() - system.intact_bonds());
      });
    }
    if (stable && signal == 0 && loop.last_recorded != system.steps_done()) stable = record();
  } catch (const std::exception& e) {
    // A write failed (a full disk): the checkpoints written so far are intact.
    if (dynamic_cast<const RunError*>(&e) == nullptr &&
        dynamic_cast<const std::filesystem::filesystem_error*>(&e) == nullptr)
      throw;
    const std::string next =
        last_checkpoint.empty()
            ? "no checkpoint was written yet: start the run again once there is space"
            : fmt::format(
                  "the last checkpoint {} is intact: make room, then continue with `rupture run --resume {}`",
                  last_checkpoint.string(), folder.string());
    const std::string message = fmt::format("{}; {}", e.what(), next);
    report["status"] = "failed";
    report["stop_reason"] = "write_failed";
    report["error"] = message;
    try {
      io::write_json_atomically(folder / "run.json", report);
    } catch (const RunError&) {  // the disk that refused the output may refuse this too
    }
    throw RunError(message);
  }
  progress.finish(double(system.steps_done()),
                  fmt::format("strain {:.3f} %, {} broken, stopped: {}", strain_now(),
                              system.bond_count() - system.intact_bonds(),
                              summary.stop_reason.empty() ? std::string(stable ? "interrupted" : "unstable")
                                                          : summary.stop_reason));

  summary.steps = system.steps_done();
  summary.strain = strain_now();
  summary.broken_bonds = system.bond_count() - system.intact_bonds();
  summary.wall_seconds = wall_now();
  summary.status = !stable ? "failed" : signal != 0 ? "interrupted" : "finished";
  std::string failure;
  if (!stable) {
    summary.stop_reason = "unstable";
    const bool too_large = plan.dt > plan.critical_dt;
    // The automatic dt when the given one is above the limit, else half the given one.
    const double suggested = too_large ? config.dt_safety * plan.critical_dt : 0.5 * plan.dt;
    const std::string cause =
        too_large ? fmt::format(
                        "dt = {:.3g} s is too large for k_n = {:g} N/mm and the stiffest, lightest particle "
                        "(springs summing to {:.3g} N/mm on {:.3g} g: critical dt {:.3g} s)",
                        plan.dt, config.bond_stiffness, plan.stiffest_spring_sum,
                        units::mass_to_grams(plan.stiffest_mass), plan.critical_dt)
                  : fmt::format(
                        "the ramp is too abrupt for b_d = {:g} (loading.ramp_steps = {} to {:g} mm/s), or "
                        "contacts {:g} times as stiff as the bonds outrun dt = {:.3g} s",
                        config.break_distance, config.ramp_steps, config.speed,
                        config.contact_stiffness_factor, plan.dt);
    failure = fmt::format(
        "unstable at step {} (t = {:.6g} s, strain {:.4g} %): {}; likely cause: {}; "
        "suggested dt = {:.3g} s: try time.dt = {:.3g}{}",
        summary.steps, system.time(), summary.strain, instability, cause, suggested, suggested,
        too_large ? " or \"auto\"" : " or a longer loading.ramp_steps");
  }
  const dem::StageTimes& t = system.stage_times();
  report["status"] = summary.status;
  report["stop_reason"] = summary.stop_reason;
  if (!failure.empty()) report["error"] = failure;
  if (signal != 0) {
    summary.checkpoint = last_checkpoint;
    summary.signal = signal;
    report["checkpoint"] = last_checkpoint.string();
    report["resume_with"] = fmt::format("rupture run --resume {}", folder.string());
  }
  report["steps"] = summary.steps;
  report["final_strain_percent"] = summary.strain;
  report["separation_strain_percent"] =
      loop.separated ? nlohmann::json(loop.separation_strain) : nlohmann::json(nullptr);
  report["separation_rule"] = loop.separated ? nlohmann::json(loop.separation_rule) : nlohmann::json(nullptr);
  report["broken_bonds"] = summary.broken_bonds;
  report["monitor"] = config.monitor ? analysis::to_json(monitor.summary()) : nlohmann::json(nullptr);
  if (config.monitor) report["monitor"]["units"] = {{"strain", "%"}, {"force", "N"}, {"energy", "mJ"}};
  report["wall_s"] = summary.wall_seconds;
  report["particle_steps_per_s"] =
      double(summary.steps) * double(sample.size()) / std::max(summary.wall_seconds, 1e-9);
  report["energy_balance"] = {{"max_abs_error_mJ", summary.max_energy_error},
                              {"max_error_relative_to_work", summary.max_relative_energy_error},
                              {"plate_work_mJ", system.plate_work()},
                              {"initial_energy_mJ", initial_energy}};
  report["stage_seconds"] = {{"neighbours", t.neighbours},
                             {"integrate", t.integrate},
                             {"forces", t.forces},
                             {"plates", t.plates},
                             {"breaks", t.breaks}};
  report["neighbour_rebuilds"] = system.neighbour_rebuilds();
  report["snapshots"] = loop.snapshots.size();
  report["memory_bytes_per_particle"] =
      double(system.memory_bytes()) / double(std::max<std::size_t>(1, sample.size()));
  io::write_json_atomically(folder / "run.json", report);
  // A finished or unstable run has nothing to resume (the same config would blow up again):
  // its checkpoints go, and the folder takes a new run.
  if (signal == 0) {
    std::error_code ignored;
    std::filesystem::remove_all(folder / "checkpoints", ignored);
  }
  if (!stable) throw RunError(failure);
  return summary;
}

}  // namespace

RunSummary run_simulation(const RunConfig& config, const Sample& sample, const std::filesystem::path& folder,
                          const std::string& command, const RunOptions& options) {
  return execute(config, sample, folder, command, options, nullptr);
}

RunSummary resume_simulation(const std::filesystem::path& folder, const std::string& command,
                             const RunOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw InputError(folder.string(), "is not a run folder", "give the folder of the run to continue");
  std::unique_ptr<io::FolderLock> lock = std::make_unique<io::FolderLock>(folder, command);
  if (const nlohmann::json record = read_run_record(folder); !record.is_null() && has_ended(record))
    throw InputError((folder / "run.json").string(),
                     fmt::format("the run already ended ({}, {}); there is nothing to resume",
                                 record.value("status", ""), record.value("stop_reason", "")),
                     "start a new run with `rupture run CONFIG.toml`");
  const LoadedCheckpoint loaded = load_newest_checkpoint(folder);
  const Checkpoint& c = loaded.checkpoint;
  const std::string source = loaded.file.string();
  nlohmann::json resolved;
  try {
    resolved = nlohmann::json::parse(c.config_json);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source + ": config", fmt::format("is not JSON ({})", e.what()), "start the run again");
  }
  const RunConfig config = config_from_json(resolved, c.config_file);
  const Sample sample = resolve_sample(config);
  if (sample_fingerprint(sample) != c.sample_fingerprint)
    throw InputError(source + ": sample_fingerprint",
                     "the sample differs from the one the run started from (the sample file changed?)",
                     "restore the sample the run began with, or start the run again");
  for (const auto& w : loaded.warnings) fmt::print(stderr, "warning: {}\n", w);
  if (c.version != version_string)
    fmt::print(
        stderr,
        "warning: {} was written by rupture {}, this is {}: the continued run may differ in the last bits\n",
        source, c.version, version_string);
  if (c.format < 2)
    fmt::print(stderr,
               "warning: {} (format {}) records only the lengths of curves.csv and breaks.csv, not their "
               "content: an edit to them before the resume would go unnoticed\n",
               source, c.format);
  ResumePoint point{loaded, command, lock};
  return execute(config, sample, folder, c.command, options, &point);
}

}  // namespace rupture::loading
