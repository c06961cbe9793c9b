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
#include <fstream>
#include <memory>

#include "analysis/monitor.hpp"
#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/units.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/csv_stream.hpp"
#include "io/file_lock.hpp"
#include "io/quantity.hpp"
#include "io/vtk.hpp"
#include "loading/checkpoint.hpp"
#include "loading/interrupt.hpp"
#include "loading/ramp.hpp"
#include "loading/run_folder.hpp"
#include "loading/separation.hpp"
#include "loading/snapshot.hpp"
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
                                               "contacts[1]",
                                               "strain_mean[%]",
                                               "force_top_mean[N]",
                                               "elastic_energy_mean[mJ]"};
// Samples each row's means are taken from: every output.interval / row_mean_samples steps (at least
// every step) since the previous row. Twenty per row are enough: on the default study's run, rows
// every 200 and 400 steps averaged so over their interval give δ_x the same to 0.004 and 0.0006 %
// whichever step they start at, where single samples move it by 0.031 and 0.011 % (docs/analysis.md,
// "Where the rows fall").
constexpr std::int64_t row_mean_samples = 20;
// What curves.csv's and breaks.csv's columns mean beyond their names and units (run.json "columns").
const nlohmann::json column_definitions = {
    {"strain", "plate displacement / initial plate separation * 100 %"},
    {"force_top", "force on the moving (top) plate, positive in tension"},
    {"force_bottom", "force on the fixed (bottom) plate, positive in tension"},
    {"strain_mean, force_top_mean, elastic_energy_mean",
     "means over the row's output interval (sampled every interval/20 steps since the previous row): "
     "the curve rupture analyze reads, free of the aliasing of vibrations faster than the rows"},
    {"x, y, z", "midpoint of the broken bond"},
    {"particle_a, particle_b", "ids of the broken bond's particles, as in the sample"}};
const std::vector<std::string> break_header = {"step[1]",         "time[s]",   "strain[%]", "particle_a[1]",
                                               "particle_b[1]",   "x[mm]",     "y[mm]",     "z[mm]",
                                               "rest_length[mm]", "energy[mJ]"};

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
  return {{"dt", io::quantity(plan.dt, "s")},
          {"dt_auto", plan.dt_auto},
          {"critical_dt", io::quantity(plan.critical_dt, "s")},
          {"stiffest_spring_sum", io::quantity(plan.stiffest_spring_sum, "N/mm")},
          {"stiffest_mass", io::quantity(units::mass_to_grams(plan.stiffest_mass), "g")},
          {"ramp_time", io::quantity(plan.ramp_time, "s")},
          {"plate_separation", io::quantity(plan.plate_separation, "mm")},
          {"wave_speed", io::quantity(plan.wave_speed, "mm/s")},
          {"plate_to_wave_speed", plan.speed_ratio},
          {"first_break_strain_estimate", io::quantity(plan.first_break_strain, "%")},
          {"estimated_steps", plan.estimated_steps},
          {"estimated_wall_time", io::quantity(plan.estimated_seconds, "s")},
          {"memory", io::quantity(double(plan.memory_bytes), "B")},
          {"warnings", plan.warnings}};
}

nlohmann::json to_json(const dem::StageTimes& times) {
  return {{"neighbours", io::quantity(times.neighbours, "s")},
          {"integrate", io::quantity(times.integrate, "s")},
          {"forces", io::quantity(times.forces, "s")},
          {"plates", io::quantity(times.plates, "s")},
          {"breaks", io::quantity(times.breaks, "s")}};
}

namespace {

// A particle that moves more than this part of its own radius in one step is taken as a blow-up:
// at the automatic dt a particle moves far less (the plates' step is 1e-5 radii), while a runaway
// mode grows by orders of magnitude within a few steps, so the exact value hardly matters.
constexpr double max_step_move = 0.5;  // 1, of the particle's radius

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

// Whether a curves.csv header names the means' columns (a folder written before them does not).
bool has_row_means(const std::filesystem::path& curves_file) {
  std::ifstream in(curves_file);
  std::string header;
  std::getline(in, header);
  return header.find("strain_mean[") != std::string::npos;
}

// What a resume starts from: the checkpoint with its file and warnings, the resuming command, and
// the folder's lock, taken before anything in it was read.
struct ResumePoint {
  const LoadedCheckpoint& loaded;
  std::string command;  // the resuming command line
  std::unique_ptr<io::FolderLock>& lock;
};

// One run from its first (or resumed) step to its stop. The stages, in the order execute() calls
// them: open the folder (new or resumed) and its files, step until a stop rule fires (each step:
// breaks written, a row and the energy balance when due, snapshots, the separation check,
// checkpoints, progress), then the closing record. Each stage is a member; the run's state is
// the members, so no stage hides a parameter.
class TensionRun {
 public:
  TensionRun(const RunConfig& config, const Sample& sample, const std::filesystem::path& folder,
             const std::string& command, const RunOptions& options, ResumePoint* resume)
      : config_(config),
        sample_(sample),
        folder_(folder),
        command_(command),
        options_(options),
        resume_(resume),
        system_(sample, config.dem_params(sample.density)),
        plan_(plan_run(config, system_, sample)),
        ramp_{config.speed, plan_.ramp_time},
        l0_(plan_.plate_separation),
        curves_file_(folder / "curves.csv"),
        breaks_file_(folder / "breaks.csv"),
        monitor_(monitor_options(config)) {
    row_mean_stride_ = std::uint64_t(std::max<std::int64_t>(1, config.output_interval / row_mean_samples));
    // What the sample holds before the first step (bonds whose rest lengths differ from the initial
    // distances: a pre-stressed sample, e.g. LAMMPS's binned rest lengths). The energy balance
    // counts from it: W = (E now) - (E at the start). Taken from the sample, so a resumed run has it.
    const dem::Energies start = system_.energies();
    initial_energy_ = start.elastic + start.contact + start.glue;
  }

  RunSummary execute() {
    if (resume_ != nullptr)
      open_resumed();
    else
      lock_ = claim_new_folder(folder_, {.command = command_,
                                         .overwrite = options_.existing == Existing::overwrite,
                                         .checkpoint_keep = std::uint64_t(config_.checkpoint_keep),
                                         .checkpoint_state_bytes = system_.state_bytes()});
    write_first_record();
    if (resume_ == nullptr) open_new_files();
    // Said once, as the run begins (a resume continues a plan already said and kept in run.json).
    if (resume_ == nullptr && options_.echo_warnings)
      for (const auto& w : plan_.warnings) fmt::print(stderr, "warning: {}\n", w);
    summary_.max_energy_error = loop_.max_energy_error;
    summary_.max_relative_energy_error = loop_.max_relative_energy_error;
    try {
      step_to_a_stop();
    } catch (const std::exception& e) {
      // A write failed (a full disk): the checkpoints written so far are intact.
      if (dynamic_cast<const RunError*>(&e) == nullptr &&
          dynamic_cast<const std::filesystem::filesystem_error*>(&e) == nullptr)
        throw;
      fail_on_write(e);
    }
    const std::string failure = close();
    if (!stable_) throw UnstableRun(failure, summary_);
    return summary_;
  }

 private:
  double strain_now() const { return 100.0 * system_.top_plate().displacement / l0_; }
  std::size_t broken_bonds() const { return system_.bond_count() - system_.intact_bonds(); }
  double wall_now() const {
    return wall_before_ +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  }

  // Everything is checked before a byte of the folder changes: both files still begin with exactly
  // what the checkpoint saw, and the monitor replays from that part.
  void open_resumed() {
    lock_ = std::move(resume_->lock);
    const Checkpoint& c = resume_->loaded.checkpoint;
    system_.restore_state(c.engine, resume_->loaded.file.string());
    loop_ = c.loop;
    wall_before_ = loop_.wall_seconds;
    last_checkpoint_ = resume_->loaded.file;
    const io::FilePrefix curves_prefix{loop_.curves_bytes, loop_.curves_hash},
        breaks_prefix{loop_.breaks_bytes, loop_.breaks_hash};
    for (const auto& [file, prefix] :
         {std::pair{curves_file_, curves_prefix}, std::pair{breaks_file_, breaks_prefix}})
      if (const auto mismatch = io::prefix_mismatch(file, prefix, c.format >= 2))
        throw InputError(
            file.string(), *mismatch,
            "the run folder was changed after the checkpoint; restore it, or remove its checkpoints "
            "and start over with --overwrite");
    if (config_.monitor) replay(monitor_, curves_file_, loop_);
    with_row_means_ = has_row_means(curves_file_);
    curves_ = std::make_unique<io::CsvStream>(curves_file_, curves_prefix);
    breaks_ = std::make_unique<io::CsvStream>(breaks_file_, breaks_prefix);
    // Earlier resumes stay listed in run.json.
    try {
      const auto before = nlohmann::json::parse(io::read_text_file(folder_ / "run.json"));
      if (before.contains("resumes") && before["resumes"].is_array()) resumes_ = before["resumes"];
    } catch (const std::exception&) {  // an unreadable run.json loses only that list
    }
    resumes_.push_back({{"command", resume_->command},
                        {"checkpoint", resume_->loaded.file.string()},
                        {"step", c.engine.step},
                        {"warnings", resume_->loaded.warnings}});
  }

  // run.json as the run starts ("running"); the closing record completes it.
  void write_first_record() {
    record_ = {{"tool", "rupture run"},
               {"version", version_string},
               {"command", command_},
               {"config", to_json(config_)},
               {"sample", to_json(compute_stats(sample_))},
               {"plan", to_json(plan_)},
               {"threads", config_.threads},
               {"columns", column_definitions},
               {"status", "running"}};
    if (!resumes_.empty()) record_["resumes"] = resumes_;
    try {
      io::write_json_atomically(folder_ / "run.json", record_);
    } catch (const RunError& e) {
      throw InputError(folder_.string(), fmt::format("is not writable ({})", e.what()),
                       "choose a writable folder with -o/--out or output.folder");
    }
  }

  // The files hold the header and the rows only, so that any CSV reader takes them without
  // options; what wrote them and what the columns mean is in run.json.
  void open_new_files() {
    curves_ = std::make_unique<io::CsvStream>(curves_file_, curve_header);
    breaks_ = std::make_unique<io::CsvStream>(breaks_file_, break_header);
  }

  void step_to_a_stop() {
    // run.log: a line a minute and one at the end (steps, rate, ETA, strain, breaks), for batch jobs.
    Progress progress("run", double(plan_.estimated_steps), folder_ / "run.log");
    LoadFreeWatch load_free(config_.load_free_fraction, config_.load_free_strain, loop_.load_free);
    if (resume_ == nullptr) {
      if (config_.snapshot_interval > 0) snapshot();
      stable_ = record_row();
    }
    while (stable_) {
      const std::uint64_t n = system_.steps_done();
      if (n >= std::uint64_t(config_.max_steps)) {
        summary_.stop_reason = "max_steps";
        break;
      }
      const std::uint64_t done = n + 1;
      const bool row_sample = with_row_means_ && done % row_mean_stride_ == 0,
                 row = done % std::uint64_t(config_.output_interval) == 0;
      system_.step(plan_.dt, ramp_.at(double(done) * plan_.dt), row_sample || row);
      if (const dem::StepMove& move = system_.last_step_move(); !(move.fraction <= max_step_move)) {
        instability_ = fmt::format("particle id {} moved {:.3g} of its radius in one step (more than {:g})",
                                   sample_.id[move.sample_index], move.fraction, max_step_move);
        stable_ = false;
        break;
      }
      load_free.add(system_.force_top());
      write_breaks();
      const double strain = strain_now();
      if (row_sample) add_row_sample(strain);
      if (row && !(stable_ = record_row())) break;
      if (config_.snapshot_interval > 0 && done % std::uint64_t(config_.snapshot_interval) == 0) snapshot();
      if (!loop_.separated && done % std::uint64_t(config_.separation_check_interval) == 0)
        check_separation(load_free, strain);
      if (stop_rule_fired(strain)) break;
      // Everything of this step is written: a checkpoint here resumes at the next one.
      signal_ = pending_interrupt();
      if (signal_ == 0 && stop_requested_) signal_ = SIGINT;
      if (signal_ != 0 || checkpoint_due(done)) {
        loop_.load_free = load_free.state();
        checkpoint();
      }
      if (signal_ != 0) {
        summary_.stop_reason = "interrupted";
        break;
      }
      progress.update_with(double(done),
                           [&] { return fmt::format("strain {:.3f} %, {} broken", strain, broken_bonds()); });
    }
    if (stable_ && signal_ == 0 && loop_.last_recorded != system_.steps_done()) stable_ = record_row();
    progress.finish(
        double(system_.steps_done()),
        fmt::format("strain {:.3f} %, {} broken, stopped: {}", strain_now(), broken_bonds(),
                    summary_.stop_reason.empty() ? std::string(stable_ ? "interrupted" : "unstable")
                                                 : summary_.stop_reason));
  }

  void write_breaks() {
    auto& events = system_.break_events();
    if (events.empty()) return;
    for (const auto& ev : events)
      breaks_->row({double(ev.step), system_.time(), strain_now(), double(sample_.id[ev.i]),
                    double(sample_.id[ev.j]), ev.midpoint.x, ev.midpoint.y, ev.midpoint.z, ev.rest_length,
                    ev.energy});
    breaks_->flush();
    events.clear();
  }

  void check_separation(LoadFreeWatch& load_free, double strain) {
    const bool broken = system_.intact_bonds() < system_.bond_count();
    if (separated(system_, sets_))
      loop_.separation_rule = "connectivity";
    else if (load_free.check(strain, broken))
      loop_.separation_rule = "load_free";
    loop_.separated = !loop_.separation_rule.empty();
    loop_.separation_strain = strain;
  }

  bool stop_rule_fired(double strain) {
    if (config_.stop_at_separation && loop_.separated &&
        strain >= loop_.separation_strain + config_.extra_strain)
      summary_.stop_reason = "separated";
    else if (strain >= config_.max_strain)
      summary_.stop_reason = "max_strain";
    return !summary_.stop_reason.empty();
  }

  void add_row_sample(double strain) {
    RowMeans& m = loop_.row_means;
    m.strain += strain;
    m.force_top += system_.force_top();
    m.elastic_energy += system_.energies().elastic;
    ++m.samples;
  }

  // A curves.csv row, the monitor fed, the caller's on_row asked, and the energy balance checked:
  // false when it shows an instability (instability_ says what gave it away).
  bool record_row() {
    const dem::Energies e = system_.energies();
    const double w = system_.plate_work();
    // Energy gained since the start: what the plates' work must pay for.
    const double total = e.elastic + e.kinetic + e.contact + e.glue + system_.released_energy() +
                         system_.damping_energy() - initial_energy_;
    std::vector<double> row{system_.time(),
                            double(system_.steps_done()),
                            strain_now(),
                            system_.force_top(),
                            system_.force_bottom(),
                            e.elastic,
                            e.kinetic,
                            e.contact,
                            e.glue,
                            w,
                            system_.released_energy(),
                            system_.damping_energy(),
                            double(system_.intact_bonds()),
                            double(broken_bonds()),
                            double(e.contacts)};
    if (with_row_means_) {
      // The first row (step 0) has no samples: its means are the instant's values.
      RowMeans& m = loop_.row_means;
      const double n = double(m.samples);
      if (m.samples > 0)
        row.insert(row.end(), {m.strain / n, m.force_top / n, m.elastic_energy / n});
      else
        row.insert(row.end(), {strain_now(), system_.force_top(), e.elastic});
      m = {};
    }
    curves_->row(row);
    curves_->flush();
    ++loop_.curves_rows;
    loop_.last_recorded = system_.steps_done();
    if (config_.monitor) feed_monitor(e.elastic);
    if (options_.on_row &&
        !options_.on_row({system_.steps_done(), strain_now(), system_.force_top(), broken_bonds()}))
      stop_requested_ = true;
    check_energy_balance(w, total, e.kinetic);
    if (instability_.empty()) return true;
    instability_ +=
        fmt::format(", fastest particle id {}", sample_.id[system_.sample_index_of_largest_speed()]);
    return false;
  }

  void feed_monitor(double elastic_energy) {
    const auto warning = monitor_.add_point(strain_now(), system_.force_top(), elastic_energy);
    if (!warning || !options_.echo_warnings) return;
    fmt::print(
        "monitor: warning at strain {:.4g} %: energy-rate maximum passed (x_p = {:.4g} %) while the force "
        "still rises; predicted x_c in [{:.4g}, {:.4g}] %\n",
        warning->strain, warning->x_p, warning->x_c.low, warning->x_c.high);
    if (!warning->in_time)
      fmt::print(
          "monitor: the rows are too far apart to warn in time (the warning comes after the earliest "
          "predicted x_c); output.interval giving rows at most {:.3g} % apart would have warned before "
          "it\n",
          warning->max_row_spacing);
  }

  // `w` the plates' work, `total` the energy gained and released since the start (mJ).
  void check_energy_balance(double w, double total, double kinetic) {
    loop_.max_work = std::max(loop_.max_work, std::abs(w));
    const double error = std::abs(w - total);
    if (std::isfinite(error)) {
      summary_.max_energy_error = std::max(summary_.max_energy_error, error);
      // Relative to the energy in play: the plates' work, or a pre-stressed sample's own energy.
      const double scale = std::max(loop_.max_work, initial_energy_);
      if (scale > 0.0) summary_.max_relative_energy_error = summary_.max_energy_error / scale;
    }
    // Energy appearing from nowhere (kinetic energy growing without the plates' work to pay for
    // it): the balance broken by half of what was put in, and by more than the energy of a 1e-6
    // strain, k_n l0^2 1e-12, so that rounding at rest is never mistaken for it.
    const double floor = 1e-12 * system_.params().bond_stiffness * l0_ * l0_;
    if (!std::isfinite(total) || !std::isfinite(w))
      instability_ = "energies are no longer finite numbers";
    else if (error > 0.5 * std::max({loop_.max_work, total, initial_energy_}) && error > floor)
      instability_ = fmt::format(
          "the energy balance broke down: the plates did {:.4g} mJ of work but the sample gained and "
          "released {:.4g} mJ (kinetic {:.4g} mJ)",
          w, total, kinetic);
  }

  void snapshot() {
    const std::string name = fmt::format("snapshots/step_{:010d}.vtp", system_.steps_done());
    std::filesystem::create_directories(folder_ / "snapshots");
    write_snapshot(system_, sample_, folder_ / name,
                   fmt::format("rupture {} run: {}; step {}, strain {:.6g} %", version_string, command_,
                               system_.steps_done(), strain_now()));
    loop_.snapshots.push_back({system_.time(), name});
    io::write_pvd(folder_ / "snapshots.pvd", loop_.snapshots);
  }

  bool checkpoint_due(std::uint64_t done) const {
    if (config_.checkpoint_every > 0 && done % std::uint64_t(config_.checkpoint_every) == 0) return true;
    return config_.checkpoint_minutes > 0.0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint_time_).count() >=
               60.0 * config_.checkpoint_minutes;
  }

  void checkpoint() {
    Checkpoint c;
    c.version = version_string;
    c.command = command_;
    c.config_file = config_.config_file.string();
    c.config_json = to_json(config_).dump();
    c.sample_fingerprint = sample_fingerprint(sample_);
    const io::FilePrefix curves_written = curves_->sync(), breaks_written = breaks_->sync();
    loop_.curves_bytes = curves_written.bytes;
    loop_.curves_hash = curves_written.hash;
    loop_.breaks_bytes = breaks_written.bytes;
    loop_.breaks_hash = breaks_written.hash;
    loop_.max_energy_error = summary_.max_energy_error;
    loop_.max_relative_energy_error = summary_.max_relative_energy_error;
    loop_.wall_seconds = wall_now();
    c.loop = loop_;
    c.engine = system_.save_state();
    last_checkpoint_ = save_checkpoint(folder_, c, std::size_t(config_.checkpoint_keep));
    last_checkpoint_time_ = std::chrono::steady_clock::now();
  }

  // A failed write: run.json says so (if the disk still takes it) and the error names the last
  // intact checkpoint.
  [[noreturn]] void fail_on_write(const std::exception& e) {
    const std::string next = last_checkpoint_.empty()
                                 ? "no checkpoint was written yet: start the run again once there is space"
                                 : fmt::format(
                                       "the last checkpoint {} is intact: make room, then continue with "
                                       "`rupture run --resume {}`",
                                       last_checkpoint_.string(), folder_.string());
    const std::string message = fmt::format("{}; {}", e.what(), next);
    record_["status"] = "failed";
    record_["stop_reason"] = "write_failed";
    record_["error"] = message;
    try {
      io::write_json_atomically(folder_ / "run.json", record_);
    } catch (const RunError&) {  // the disk that refused the output may refuse this too
    }
    throw RunError(message);
  }

  // What an unstable run's error says: the step, what gave it away, the likely cause and a dt.
  std::string describe_instability() const {
    const bool too_large = plan_.dt > plan_.critical_dt;
    // The automatic dt when the given one is above the limit, else half the given one.
    const double suggested = too_large ? config_.dt_safety * plan_.critical_dt : 0.5 * plan_.dt;
    const std::string cause =
        too_large ? fmt::format(
                        "dt = {:.3g} s is too large for k_n = {:g} N/mm and the stiffest, lightest particle "
                        "(springs summing to {:.3g} N/mm on {:.3g} g: critical dt {:.3g} s)",
                        plan_.dt, config_.bond_stiffness, plan_.stiffest_spring_sum,
                        units::mass_to_grams(plan_.stiffest_mass), plan_.critical_dt)
                  : fmt::format(
                        "the ramp is too abrupt for b_d = {:g} (loading.ramp_steps = {} to {:g} mm/s), or "
                        "contacts {:g} times as stiff as the bonds outrun dt = {:.3g} s",
                        config_.break_distance, config_.ramp_steps, config_.speed,
                        config_.contact_stiffness_factor, plan_.dt);
    return fmt::format(
        "unstable at step {} (t = {:.6g} s, strain {:.4g} %): {}; likely cause: {}; "
        "suggested dt = {:.3g} s: try time.dt = {:.3g}{}",
        summary_.steps, system_.time(), summary_.strain, instability_, cause, suggested, suggested,
        too_large ? " or \"auto\"" : " or a longer loading.ramp_steps");
  }

  // The summary and the closing run.json; a run that cannot go on loses its checkpoints. Returns
  // the failure message of an unstable run ("" otherwise).
  std::string close() {
    summary_.steps = system_.steps_done();
    summary_.dt = plan_.dt;
    summary_.strain = strain_now();
    summary_.broken_bonds = broken_bonds();
    summary_.wall_seconds = wall_now();
    summary_.status = !stable_ ? "failed" : signal_ != 0 ? "interrupted" : "finished";
    std::string failure;
    if (!stable_) {
      summary_.stop_reason = "unstable";
      failure = describe_instability();
    }
    record_["status"] = summary_.status;
    record_["stop_reason"] = summary_.stop_reason;
    if (!failure.empty()) record_["error"] = failure;
    if (signal_ != 0) {
      summary_.checkpoint = last_checkpoint_;
      summary_.signal = signal_;
      record_["checkpoint"] = last_checkpoint_.string();
      record_["resume_with"] = fmt::format("rupture run --resume {}", folder_.string());
    }
    add_results_to_record();
    io::write_json_atomically(folder_ / "run.json", record_);
    // A finished or unstable run has nothing to resume (the same config would blow up again):
    // its checkpoints go, and the folder takes a new run.
    if (signal_ == 0) {
      std::error_code ignored;
      std::filesystem::remove_all(folder_ / "checkpoints", ignored);
    }
    return failure;
  }

  void add_results_to_record() {
    record_["steps"] = summary_.steps;
    record_["final_strain"] = io::quantity(summary_.strain, "%");
    record_["separation_strain"] =
        loop_.separated ? io::quantity(loop_.separation_strain, "%") : nlohmann::json(nullptr);
    record_["separation_rule"] =
        loop_.separated ? nlohmann::json(loop_.separation_rule) : nlohmann::json(nullptr);
    record_["broken_bonds"] = summary_.broken_bonds;
    record_["monitor"] =
        config_.monitor ? analysis::to_json(monitor_.summary(), "%", "mJ") : nlohmann::json(nullptr);
    record_["wall_time"] = io::quantity(summary_.wall_seconds, "s");
    record_["throughput"] =
        io::quantity(double(summary_.steps) * double(sample_.size()) / std::max(summary_.wall_seconds, 1e-9),
                     "particle-steps/s");
    record_["energy_balance"] = {{"max_abs_error", io::quantity(summary_.max_energy_error, "mJ")},
                                 {"max_error_relative_to_work", summary_.max_relative_energy_error},
                                 {"plate_work", io::quantity(system_.plate_work(), "mJ")},
                                 {"initial_energy", io::quantity(initial_energy_, "mJ")}};
    record_["stage_times"] = to_json(system_.stage_times());
    record_["neighbour_rebuilds"] = system_.neighbour_rebuilds();
    record_["snapshots"] = loop_.snapshots.size();
    record_["memory_per_particle"] =
        io::quantity(double(system_.memory_bytes()) / double(std::max<std::size_t>(1, sample_.size())), "B");
  }

  // What the run was given.
  const RunConfig& config_;
  const Sample& sample_;
  const std::filesystem::path folder_;
  const std::string command_;  // the command that started the run
  const RunOptions& options_;
  ResumePoint* const resume_;  // null for a new run
  const std::chrono::steady_clock::time_point wall_start_ = std::chrono::steady_clock::now();

  // The model and what was worked out before the first step.
  dem::System system_;
  const RunPlan plan_;
  const SpeedRamp ramp_;
  const double l0_;            // mm, the initial plate separation
  double initial_energy_ = 0;  // mJ, held by the sample before the first step
  const std::filesystem::path curves_file_, breaks_file_;

  // The folder and its files.
  std::unique_ptr<io::FolderLock> lock_;
  std::unique_ptr<io::CsvStream> curves_, breaks_;
  nlohmann::json record_;                             // run.json
  nlohmann::json resumes_ = nlohmann::json::array();  // earlier resumes and this one

  // What the loop carries (a checkpoint saves loop_), and how it ended.
  LoopState loop_;
  // Whether curves.csv has the means' columns: always, except in a run resumed from a folder written
  // before them, whose rows keep the columns its header names.
  bool with_row_means_ = true;
  std::uint64_t row_mean_stride_ = 1;  // steps between the samples of a row's means
  analysis::Monitor monitor_;
  UnionFind sets_;
  RunSummary summary_;
  double wall_before_ = 0.0;  // s spent before the resumed checkpoint
  std::filesystem::path last_checkpoint_;
  std::chrono::steady_clock::time_point last_checkpoint_time_ = std::chrono::steady_clock::now();
  std::string instability_;      // what gave an instability away, naming the particle ("" while stable)
  bool stop_requested_ = false;  // options.on_row said stop
  bool stable_ = true;
  int signal_ = 0;  // SIGINT/SIGTERM that interrupted the run, or on_row's stop (as SIGINT)
};

RunSummary execute(const RunConfig& config, const Sample& sample, const std::filesystem::path& folder,
                   const std::string& command, const RunOptions& options, ResumePoint* resume) {
  omp_set_num_threads(int(config.threads));
  TensionRun run(config, sample, folder, command, options, resume);
  return run.execute();
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
