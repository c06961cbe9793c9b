#include "loading/run.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/units.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/vtk.hpp"
#include "analysis/monitor.hpp"
#include "loading/ramp.hpp"
#include "loading/separation.hpp"
#include "rupture/version.hpp"
#include "sample/formats.hpp"
#include "sample/lattice.hpp"
#include "sample/presets.hpp"
#include "sample/stats.hpp"

namespace rupture::loading {

namespace {

// Whole-step throughput used for time estimates (particle-steps/s on 2 threads, intact tissue),
// as measured by `rupture bench` (docs/performance.md).
constexpr double assumed_particle_steps_per_s = 2e7;

// A streamed CSV file: written row by row during the run (it cannot be atomic), flushed after
// every row so that a killed run keeps everything recorded so far.
class CsvStream {
 public:
  CsvStream(const std::filesystem::path& path, const std::vector<std::string>& comments,
            const std::vector<std::string>& header)
      : file_(std::fopen(path.c_str(), "w"), &std::fclose) {
    if (!file_) throw RunError(fmt::format("cannot write {}", path.string()));
    for (const auto& c : comments) std::fprintf(file_.get(), "# %s\n", c.c_str());
    std::fputs(io::format_csv_header(header).c_str(), file_.get());
    std::fflush(file_.get());
  }
  void row(const std::vector<double>& values) { std::fputs(io::format_csv_row(values).c_str(), file_.get()); }
  void flush() { std::fflush(file_.get()); }

 private:
  std::unique_ptr<std::FILE, decltype(&std::fclose)> file_;
};

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

double mean_rest_length(const Sample& sample) {
  double sum = 0.0;
  for (const auto& b : sample.bonds) sum += b.rest_length;
  return sample.bonds.empty() ? 0.0 : sum / double(sample.bonds.size());
}

}  // namespace

Sample resolve_sample(const RunConfig& config) {
  if (!config.sample_lattice.empty()) {
    const auto& n = config.lattice_cells;
    const double density = config.density.value_or(2.5e-4);
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
  const double r0 = mean_rest_length(sample);
  const dem::Params params = config.dem_params(sample.density);
  double mean_mass = 0.0;
  for (double r : sample.radius)
    mean_mass += units::density_from_g_per_mm3(params.density) * units::sphere_volume(r);
  mean_mass /= double(std::max<std::size_t>(1, sample.size()));
  const double k = params.scale_stiffness ? params.bond_stiffness * r0 / 4.0 : params.bond_stiffness;
  plan.wave_speed = r0 * std::sqrt(k / mean_mass);
  plan.speed_ratio = config.speed / plan.wave_speed;
  plan.first_break_strain =
      100.0 *
      (params.break_rule == dem::BreakRule::absolute ? config.break_distance / r0 : config.break_distance);
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

RunSummary run_simulation(const RunConfig& config, const Sample& sample, const std::filesystem::path& folder,
                          const std::string& command) {
  const auto wall_start = std::chrono::steady_clock::now();
  omp_set_num_threads(int(config.threads));
  const dem::Params params = config.dem_params(sample.density);
  dem::System system(sample, params);
  const RunPlan plan = plan_run(config, system, sample);
  const SpeedRamp ramp{config.speed, plan.ramp_time};
  const double l0 = plan.plate_separation;

  std::filesystem::create_directories(folder);
  const std::vector<std::string> comments = {
      fmt::format("rupture {} run: {}", version_string, command),
      "strain = plate displacement / initial plate separation * 100 %; forces positive in tension"};
  CsvStream curves(folder / "curves.csv", comments, curve_header);
  CsvStream breaks(folder / "breaks.csv", comments, break_header);

  nlohmann::json report = {{"tool", "rupture run"},
                           {"version", version_string},
                           {"command", command},
                           {"config", to_json(config)},
                           {"sample", to_json(compute_stats(sample))},
                           {"plan", to_json(plan)},
                           {"threads", config.threads},
                           {"status", "running"}};
  io::write_json_atomically(folder / "run.json", report);

  RunSummary summary;
  analysis::Monitor monitor({.window = std::size_t(config.monitor_window),
                             .drop = config.monitor_drop,
                             .confirm = std::size_t(config.monitor_confirm)});
  double max_work = 0.0;
  const auto strain_now = [&] { return 100.0 * system.top_plate().displacement / l0; };
  const auto record = [&] {
    const dem::Energies e = system.energies();
    const double w = system.plate_work();
    const double total =
        e.elastic + e.kinetic + e.contact + e.glue + system.released_energy() + system.damping_energy();
    curves.row({system.time(), double(system.steps_done()), strain_now(), system.force_top(),
                system.force_bottom(), e.elastic, e.kinetic, e.contact, e.glue, w, system.released_energy(),
                system.damping_energy(), double(system.intact_bonds()),
                double(system.bond_count() - system.intact_bonds()), double(e.contacts)});
    curves.flush();
    if (config.monitor) {
      if (const auto warning = monitor.add_point(strain_now(), system.force_top(), e.elastic))
        fmt::print("monitor: warning at strain {:.4g} %: energy-rate maximum passed (x_p = {:.4g} %) while the force "
                   "still rises; predicted x_c in [{:.4g}, {:.4g}] %\n",
                   warning->strain, warning->x_p, warning->x_c.low, warning->x_c.high);
    }
    max_work = std::max(max_work, std::abs(w));
    const double error = std::abs(w - total);
    if (std::isfinite(error)) {
      summary.max_energy_error = std::max(summary.max_energy_error, error);
      if (max_work > 0.0) summary.max_relative_energy_error = summary.max_energy_error / max_work;
    }
    // Unstable: numbers gone non-finite, or energy appearing from nowhere (the integrator's own
    // conservation broken by half of what was put in, and by more than the energy of a 1e-6 strain,
    // k_n l0^2 1e-12, so that rounding at rest is never mistaken for it).
    const double floor = 1e-12 * params.bond_stiffness * l0 * l0;
    return std::isfinite(total) && std::isfinite(w) &&
           !(error > 0.5 * std::max(max_work, total) && error > floor);
  };

  std::vector<io::PvdEntry> snapshots;
  const auto snapshot = [&] {
    const std::string name = fmt::format("snapshots/step_{:010d}.vtp", system.steps_done());
    std::filesystem::create_directories(folder / "snapshots");
    write_snapshot(system, sample, folder / name,
                   fmt::format("rupture {} run: {}; step {}, strain {:.6g} %", version_string, command,
                               system.steps_done(), strain_now()));
    snapshots.push_back({system.time(), name});
    io::write_pvd(folder / "snapshots.pvd", snapshots);
  };
  if (config.snapshot_interval > 0) snapshot();

  Progress progress("run", double(plan.estimated_steps));
  UnionFind sets;
  LoadFreeWatch load_free(config.load_free_fraction, config.load_free_strain);
  bool separated_yet = false, stable = record();
  double separation_strain = 0.0;
  std::string separation_rule;
  std::uint64_t last_recorded = 0;
  while (stable) {
    const std::uint64_t n = system.steps_done();
    if (n >= std::uint64_t(config.max_steps)) {
      summary.stop_reason = "max_steps";
      break;
    }
    system.step(plan.dt, ramp.at(double(n + 1) * plan.dt));
    load_free.add(system.force_top());
    auto& events = system.break_events();
    if (!events.empty()) {
      for (const auto& ev : events)
        breaks.row({double(ev.step), system.time(), strain_now(), double(sample.id[ev.i]),
                    double(sample.id[ev.j]), ev.midpoint.x, ev.midpoint.y, ev.midpoint.z, ev.rest_length,
                    ev.energy});
      breaks.flush();
      events.clear();
    }
    const std::uint64_t done = n + 1;
    const double strain = strain_now();
    if (done % std::uint64_t(config.output_interval) == 0) {
      stable = record();
      last_recorded = done;
      if (!stable) break;
    }
    if (config.snapshot_interval > 0 && done % std::uint64_t(config.snapshot_interval) == 0) snapshot();
    if (!separated_yet && done % std::uint64_t(config.separation_check_interval) == 0) {
      const bool broken = system.intact_bonds() < system.bond_count();
      if (separated(system, sets))
        separation_rule = "connectivity";
      else if (load_free.check(strain, broken))
        separation_rule = "load_free";
      separated_yet = !separation_rule.empty();
      separation_strain = strain;
    }
    if (separated_yet && strain >= separation_strain + config.extra_strain) {
      summary.stop_reason = "separated";
      break;
    }
    if (strain >= config.max_strain) {
      summary.stop_reason = "max_strain";
      break;
    }
    progress.update_with(double(done), [&] {
      return fmt::format("strain {:.3f} %, {} broken", strain, system.bond_count() - system.intact_bonds());
    });
  }
  if (stable && last_recorded != system.steps_done()) stable = record();
  progress.finish();

  summary.steps = system.steps_done();
  summary.strain = strain_now();
  summary.broken_bonds = system.bond_count() - system.intact_bonds();
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  summary.status = stable ? "finished" : "failed";
  std::string failure;
  if (!stable) {
    summary.stop_reason = "unstable";
    const std::size_t worst = system.sample_index_of_largest_speed();
    failure = fmt::format(
        "unstable at step {} (t = {:.6g} s, strain {:.4g} %): the energy balance broke down, fastest "
        "particle id {}; "
        "likely cause: dt = {:.3g} s is too large for the stiffest springs (critical dt {:.3g} s{}) or the "
        "start is "
        "too abrupt (loading.ramp_steps = {}); try time.dt = {:.3g} or a longer ramp",
        summary.steps, system.time(), summary.strain, sample.id[worst], plan.dt, plan.critical_dt,
        plan.dt > plan.critical_dt ? ", exceeded" : "", config.ramp_steps,
        0.5 * std::min(plan.dt, plan.critical_dt));
  }
  const dem::StageTimes& t = system.stage_times();
  report["status"] = summary.status;
  report["stop_reason"] = summary.stop_reason;
  if (!failure.empty()) report["error"] = failure;
  report["steps"] = summary.steps;
  report["final_strain_percent"] = summary.strain;
  report["separation_strain_percent"] =
      separated_yet ? nlohmann::json(separation_strain) : nlohmann::json(nullptr);
  report["separation_rule"] = separated_yet ? nlohmann::json(separation_rule) : nlohmann::json(nullptr);
  report["broken_bonds"] = summary.broken_bonds;
  report["monitor"] = config.monitor ? analysis::to_json(monitor.summary()) : nlohmann::json(nullptr);
  if (config.monitor) report["monitor"]["units"] = {{"strain", "%"}, {"force", "N"}, {"energy", "mJ"}};
  report["wall_s"] = summary.wall_seconds;
  report["particle_steps_per_s"] =
      double(summary.steps) * double(sample.size()) / std::max(summary.wall_seconds, 1e-9);
  report["energy_balance"] = {{"max_abs_error_mJ", summary.max_energy_error},
                              {"max_error_relative_to_work", summary.max_relative_energy_error},
                              {"plate_work_mJ", system.plate_work()}};
  report["stage_seconds"] = {{"neighbours", t.neighbours},
                             {"integrate", t.integrate},
                             {"forces", t.forces},
                             {"plates", t.plates},
                             {"breaks", t.breaks}};
  report["neighbour_rebuilds"] = system.neighbour_rebuilds();
  report["snapshots"] = snapshots.size();
  report["memory_bytes_per_particle"] =
      double(system.memory_bytes()) / double(std::max<std::size_t>(1, sample.size()));
  io::write_json_atomically(folder / "run.json", report);
  if (!stable) throw RunError(failure);
  return summary;
}

}  // namespace rupture::loading
