// scan/ledger: each point's record in the scan folder, which is the only state a scan keeps, so that
// any process (a local job, an MPI rank, an array task, a restart after a kill) can tell what is
// done. A point is claimed by a lock on points/NAME/lock (released by the kernel when its holder
// dies), runs in a fresh points/NAME/attempt-N/ (never reused, so attempts never mix), and is finished
// exactly when points/NAME/result.json exists — written last, by rename.
// Not: choosing which point runs where (scan/farm).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "sample/sample.hpp"
#include "scan/scan.hpp"

namespace rupture::scan {

enum class PointState { pending, partial, running, finished };
const char* to_string(PointState state);

struct PointStatus {
  PointState state = PointState::pending;
  std::string status;  // finished: results.hpp status (ok, no_separation, unstable, error); else the state
  std::string why;     // finished: the failure or rejection reason
  int attempts = 0;    // attempt folders present
};

std::filesystem::path point_folder(const Plan& plan, const Point& point);
PointStatus point_status(const Plan& plan, const Point& point);

// The point's result.json, or nullopt when it is not finished.
std::optional<nlohmann::json> read_result(const Plan& plan, const Point& point);

// Throws InputError when a finished point was computed with a different run config than the plan
// now gives it (the base config or the scan's rules changed under an old scan folder).
void check_result_matches(const Plan& plan, const Point& point, const nlohmann::json& result);

// Runs and analyses one point if it is not finished and no other process holds it; returns its
// result (also written to result.json), or nullopt when another process holds it. Failures of the
// run or the analysis are results (status unstable, no_separation, error), not exceptions.
std::optional<nlohmann::json> run_point(const Plan& plan, const Point& point, const Sample& sample,
                                        int threads);

// Analyses a finished point's curve again with this version's analysis (the run is kept): rewrites
// its analysis.json and its result's row. False when the point is not finished, has no curve (an
// unstable or failed run) or another process holds it.
bool reanalyze_point(const Plan& plan, const Point& point);

// The point's results.csv row: from its result when finished, else its parameters and state.
nlohmann::json result_row(const Plan& plan, const Point& point);

}  // namespace rupture::scan
