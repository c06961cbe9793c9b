// scan/farm: who runs which point. Locally, a pool of jobs that take the next unfinished point as
// they free up; under mpirun, a task farm: rank 0 hands out points one at a time on request (runs
// differ in length by orders of magnitude, so fixed shares would leave ranks idle) and runs points
// itself meanwhile; one point alone for a scheduler's job array; and the aggregate (results.csv,
// scan.json) from whatever the ledger holds. Not: running a point (scan/ledger).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "sample/sample.hpp"
#include "scan/scan.hpp"

namespace rupture::scan {

struct Parallelism {
  int jobs = 1;     // points run at once by this process
  int threads = 1;  // OpenMP threads inside each run
};

// Fills in what the user left at 0 from the core count: by default as many jobs as cores (and
// pending points), since separate runs scale perfectly and one small run does not; leftover cores go
// to threads. Never more than `cores` jobs × threads unless the user asked for it.
Parallelism choose_parallelism(int cores, std::size_t pending, int jobs, int threads);

struct FarmOptions {
  int jobs = 0, threads = 0;  // 0: choose_parallelism
  std::string command;        // recorded in scan.json
  bool print = true;          // one line per finished point on stdout
};

// Cores this process may use (its CPU affinity: a batch allocation, taskset), at least 1.
int available_cores();

// True when this process was started by an MPI launcher (mpirun/mpiexec/srun with PMI).
bool launched_by_mpi();

// Runs every unfinished point (local pool, or the MPI farm when launched_by_mpi() and built with
// MPI), rewriting results.csv after each point; the process that aggregates (rank 0 under MPI)
// writes scan.json at the end. Throws InputError before running anything when a finished point's
// config no longer matches the plan. Returns the number of points finished now or before.
std::size_t run_scan(const Plan& plan, const Sample& sample, const FarmOptions& options);

// One point alone (a job-array task): does nothing when it is finished or held by another process.
void run_task(const Plan& plan, const Sample& sample, std::size_t index, int threads, bool print);

// results.csv and scan.json from the ledger; `info` (jobs, threads, ranks, wall time, command) is
// merged into scan.json. An `info` holding "reanalysed" or "collected" keeps the run's own record of
// the previous scan.json (command, version, cores, wall time), where there is one, and adds its own
// beside it.
void write_aggregate(const Plan& plan, const nlohmann::json& info);

// A table of every point's state for --status, and the counts per state (the last line).
std::string status_report(const Plan& plan);

}  // namespace rupture::scan
