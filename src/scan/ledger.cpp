#include "scan/ledger.hpp"

#include <fmt/format.h>

#include <chrono>

#include "analysis/curve_file.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/file_lock.hpp"
#include "io/quantity.hpp"
#include "loading/run.hpp"
#include "rupture/version.hpp"
#include "scan/results.hpp"

namespace rupture::scan {

namespace {

int count_attempts(const std::filesystem::path& folder) {
  int n = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec))
    if (entry.is_directory() && entry.path().filename().string().rfind("attempt-", 0) == 0) ++n;
  return n;
}

// A fresh attempt folder: the first attempt-N that does not exist yet (created atomically by mkdir).
std::filesystem::path new_attempt(const std::filesystem::path& folder) {
  for (int n = 1;; ++n) {
    const auto attempt = folder / fmt::format("attempt-{}", n);
    if (std::filesystem::create_directory(attempt)) return attempt;
  }
}

nlohmann::json comparable(nlohmann::json config) {
  config["run"].erase("threads");  // threads never change results (tested in dem/)
  return config;
}

void put(nlohmann::json& row, const std::string& name, const std::optional<analysis::Measured>& m) {
  if (!m) return;
  row[name] = m->value;
  row[name + "_err"] = m->error;
}

void add_analysis(nlohmann::json& row, const analysis::AnalysisResult& r) {
  put(row, "x_c", r.x_c);
  put(row, "F_c", r.F_c);
  put(row, "x_p", r.x_p);
  put(row, "Erate_max", r.Erate_max);
  put(row, "x_m", r.x_m);
  put(row, "E_max", r.E_max);
  if (r.delay) {
    row["delta_x"] = r.delay->mean;
    row["delta_x_sd"] = r.delay->sd;
    row["delta_x_map"] = r.delay->map;
    row["delta_x_lo68"] = r.delay->ci68_low;
    row["delta_x_hi68"] = r.delay->ci68_high;
    row["delta_x_lo95"] = r.delay->ci95_low;
    row["delta_x_hi95"] = r.delay->ci95_high;
  }
  put(row, "Gamma", r.Gamma);
  put(row, "A_r", r.A_r);
  if (r.alpha.alpha) row["alpha"] = *r.alpha.alpha;
  if (r.mechanism && r.accepted) row["class"] = analysis::to_string(r.mechanism->mechanism);
  row["accepted"] = r.accepted ? 1 : 0;
  if (!r.accepted) row["why"] = r.rejection;
}

// Analyses the attempt's curve into analysis.json and the row. A separated run whose curve cannot
// be analysed is an error; `why` gathers the reasons.
void analyse_attempt(const std::filesystem::path& attempt, nlohmann::json& row, std::string& status,
                     std::string& why) {
  analysis::CurveFileInputs inputs;
  inputs.curves = attempt / "curves.csv";
  try {
    auto analysed = analysis::analyze_curve_file(inputs, "rupture scan");
    io::write_json_atomically(attempt / "analysis.json", analysed.document);
    add_analysis(row, analysed.result);
  } catch (const InputError& e) {
    if (status == status::ok) status = status::error;
    why = (why.empty() ? "" : why + "; ") + "analysis failed: " + e.what();
  }
}

// result.json's "point": the index and the point's k_n and b_d in the base config's units.
nlohmann::json point_json(const Point& point, const loading::RunConfig& config) {
  return {{"index", point.index},
          {"k_n", io::quantity(point.k_n, loading::bond_stiffness_unit(config))},
          {"b_d", io::quantity(point.b_d, loading::break_distance_unit(config))}};
}

nlohmann::json base_row(const Point& point) {
  return {{"point", point.index},
          {"k_n", point.k_n},
          {"b_d", point.b_d},
          {"ramp_steps", point.ramp_steps},
          {"max_strain", point.max_strain}};
}

}  // namespace

const char* to_string(PointState state) {
  switch (state) {
    case PointState::pending:
      return "pending";
    case PointState::partial:
      return "partial";
    case PointState::running:
      return "running";
    case PointState::finished:
      return "finished";
  }
  return "?";
}

std::filesystem::path point_folder(const Plan& plan, const Point& point) {
  return plan.folder / "points" / point.name;
}

std::optional<nlohmann::json> read_result(const Plan& plan, const Point& point) {
  const auto file = point_folder(plan, point) / "result.json";
  if (!std::filesystem::exists(file)) return std::nullopt;
  try {
    return nlohmann::json::parse(io::read_text_file(file));
  } catch (const nlohmann::json::exception& e) {
    // Cannot happen through the ledger (the file appears whole); a hand-edited file is bad input.
    throw InputError(file.string(), std::string("unreadable result: ") + e.what(),
                     "delete it to run the point again");
  }
}

PointStatus point_status(const Plan& plan, const Point& point) {
  PointStatus s;
  const auto folder = point_folder(plan, point);
  if (!std::filesystem::exists(folder)) return s;
  s.attempts = count_attempts(folder);
  if (const auto result = read_result(plan, point)) {
    s.state = PointState::finished;
    s.status = result->value("status", "");
    s.why = result->at("row").value("why", "");
    return s;
  }
  s.state = io::is_locked(folder / "lock") ? PointState::running
            : s.attempts > 0               ? PointState::partial
                                           : PointState::pending;
  s.status = to_string(s.state);
  return s;
}

void check_result_matches(const Plan& plan, const Point& point, const nlohmann::json& result) {
  const std::string file = (point_folder(plan, point) / "result.json").string();
  const std::string fix =
      "restore them, or give [scan] output a new folder (or remove " + file + " to recompute it)";
  // Results of rupture 0.1 carry no fingerprint: only their config can be compared.
  const std::string now = fingerprint_text(plan.sample_fingerprint);
  if (result.contains("sample_fingerprint") && result.at("sample_fingerprint") != now)
    throw InputError(
        file,
        fmt::format("this point was computed on another sample (fingerprint {}; the sample now gives {})",
                    result.at("sample_fingerprint").get<std::string>(), now),
        fix);
  if (!result.contains("config") ||
      comparable(result.at("config")) != comparable(loading::to_json(point_config(plan, point, 1))))
    throw InputError(file, "this point was computed with a different run config than the scan now gives it",
                     fix);
}

std::optional<nlohmann::json> run_point(const Plan& plan, const Point& point, const Sample& sample,
                                        int threads) {
  const auto folder = point_folder(plan, point);
  std::filesystem::create_directories(folder);
  const io::FileLock lock(folder / "lock");
  if (!lock.held()) return std::nullopt;
  if (auto done = read_result(plan, point)) return done;  // finished while we were looking

  const auto start = std::chrono::steady_clock::now();
  const auto attempt = new_attempt(folder);
  const loading::RunConfig config = point_config(plan, point, threads);
  const std::string command = point_command(plan, point, threads);
  nlohmann::json row = base_row(point);
  std::string status = status::error, why;
  const auto record_run = [&](const loading::RunSummary& summary) {
    row["dt"] = summary.dt;
    row["stop_reason"] = summary.stop_reason;
    row["steps"] = summary.steps;
    row["final_strain"] = summary.strain;
    row["broken_bonds"] = summary.broken_bonds;
  };
  try {
    const auto summary = loading::run_simulation(config, sample, attempt, command, {.echo_warnings = false});
    record_run(summary);
    const bool separated = summary.stop_reason == "separated";
    status = separated ? status::ok : status::no_separation;
    if (!separated)
      why = fmt::format("not separated at the {} stop (strain {:.4g} %, {} steps)", summary.stop_reason,
                        summary.strain, summary.steps);
    analyse_attempt(attempt, row, status, why);
  } catch (const loading::UnstableRun& e) {
    record_run(e.summary);
    status = status::unstable;
    why = e.what();
  } catch (const std::exception& e) {  // e.g. a full disk
    status = status::error;
    why = e.what();
  }
  row["status"] = status;
  if (status != status::ok) {
    row["accepted"] = 0;
    row["why"] = why;
  }
  row["wall_time"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json result = {{"tool", "rupture scan"},
                           {"version", version_string},
                           {"point", point_json(point, config)},
                           {"attempt", attempt.filename().string()},
                           {"command", command},
                           {"config", loading::to_json(config)},
                           {"sample_fingerprint", fingerprint_text(plan.sample_fingerprint)},
                           {"status", status},
                           {"row", row}};
  io::write_json_atomically(folder / "result.json", result);  // last: the point is now finished
  return result;
}

bool reanalyze_point(const Plan& plan, const Point& point) {
  const auto folder = point_folder(plan, point);
  if (!std::filesystem::exists(folder / "result.json")) return false;  // not finished (or never started)
  const io::FileLock lock(folder / "lock");
  if (!lock.held()) return false;  // a process is working on it
  auto result = read_result(plan, point);
  if (!result) return false;
  const auto attempt = folder / result->at("attempt").get<std::string>();
  std::string status = result->at("status").get<std::string>();
  if ((status != status::ok && status != status::no_separation) ||
      !std::filesystem::exists(attempt / "curves.csv"))
    return false;
  // The run's part of the row stays; the analysis's part is made anew.
  const nlohmann::json old = result->at("row");
  nlohmann::json row = base_row(point);
  for (const char* key : {"stop_reason", "steps", "final_strain", "broken_bonds", "dt", "wall_time"})
    if (old.contains(key)) row[key] = old.at(key);
  status = row.value("stop_reason", "") == "separated" ? status::ok : status::no_separation;
  std::string why;
  if (status == status::no_separation)
    why =
        fmt::format("not separated at the {} stop (strain {:.4g} %, {} steps)", row.value("stop_reason", ""),
                    row.value("final_strain", 0.0), row.value("steps", std::uint64_t(0)));
  analyse_attempt(attempt, row, status, why);
  row["status"] = status;
  if (status != status::ok) {
    row["accepted"] = 0;
    row["why"] = why;
  }
  (*result)["status"] = status;
  (*result)["point"] = point_json(point, plan.base_config);  // a file of an earlier build: this form
  (*result)["row"] = row;
  (*result)["analysis_version"] = version_string;
  io::write_json_atomically(folder / "result.json", *result);
  return true;
}

nlohmann::json result_row(const Plan& plan, const Point& point) {
  if (const auto result = read_result(plan, point)) {
    nlohmann::json row = result->at("row");
    row["point"] = point.index;  // the plan's order, which a longer scan may have changed
    return row;
  }
  nlohmann::json row = base_row(point);
  const PointStatus s = point_status(plan, point);
  row["status"] = s.state == PointState::running ? status::running : status::pending;
  return row;
}

}  // namespace rupture::scan
