#include "scan/farm.hpp"

#include <fmt/format.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#ifdef RUPTURE_HAVE_MPI
#include <mpi.h>
#endif

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/quantity.hpp"
#include "rupture/version.hpp"
#include "scan/ledger.hpp"
#include "scan/results.hpp"

namespace rupture::scan {

namespace {

using Clock = std::chrono::steady_clock;

// Points not finished yet, after checking that the finished ones still belong to this plan.
std::vector<std::size_t> unfinished_points(const Plan& plan) {
  std::vector<std::size_t> pending;
  for (const auto& point : plan.points) {
    if (const auto result = read_result(plan, point))
      check_result_matches(plan, point, *result);
    else
      pending.push_back(point.index);
  }
  return pending;
}

std::string measured_text(const nlohmann::json& row, const char* name, const char* unit) {
  if (!row.contains(name)) return "";
  return fmt::format(", {} = {:.4g} {}", name, row.at(name).get<double>(), unit);
}

// "[3/6] kn_1000_bd_0.005: ok, x_c = 1.2 %, delta_x = 0.1 % (12.3 s)"
void print_point(const Plan& plan, std::size_t index, std::size_t done) {
  const Point& point = plan.points[index];
  const auto result = read_result(plan, point);
  if (!result) return;
  const auto& row = result->at("row");
  std::string line =
      fmt::format("[{}/{}] {}: {}", done, plan.points.size(), point.name, result->value("status", "?"));
  line += measured_text(row, "x_c", "%") + measured_text(row, "delta_x", "%");
  if (row.contains("class")) line += ", " + row.at("class").get<std::string>();
  if (row.contains("why")) line += "; " + row.at("why").get<std::string>();
  fmt::print("{} ({:.3g} s)\n", line, row.value("wall_time", 0.0));
  std::fflush(stdout);
}

nlohmann::json farm_info(const FarmOptions& options, Parallelism p, int ranks, Clock::time_point start) {
  return {{"command", options.command},
          {"jobs", p.jobs},
          {"threads", p.threads},
          {"mpi_ranks", ranks},
          {"cores", available_cores()},
          {"wall_time", io::quantity(std::chrono::duration<double>(Clock::now() - start).count(), "s")}};
}

// Runs `pending` points on `jobs` threads of this process, each taking the next point when free.
// `finished(index)` is called (serially) after each point.
template <class OnFinished>
void run_pool(const Plan& plan, const Sample& sample, const std::vector<std::size_t>& pending, Parallelism p,
              OnFinished&& finished) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;
  std::exception_ptr failure;
  const auto work = [&] {
    try {
      while (!stop) {
        const std::size_t k = next.fetch_add(1);
        if (k >= pending.size()) break;
        if (run_point(plan, plan.points[pending[k]], sample, p.threads)) {
          const std::lock_guard guard(mutex);
          finished(pending[k]);
        }
      }
    } catch (...) {
      const std::lock_guard guard(mutex);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < p.jobs; ++j) workers.emplace_back(work);
  work();
  for (auto& w : workers) w.join();
  if (failure) std::rethrow_exception(failure);
}

#ifdef RUPTURE_HAVE_MPI

// MPI for the lifetime of one scan; only the main thread calls MPI (FUNNELED).
class MpiSession {
 public:
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &local_size_);
    MPI_Comm_free(&node);
  }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  int local_size() const { return local_size_; }

 private:
  int rank_ = 0, size_ = 1, local_size_ = 1;
};

constexpr int tag_request = 1;  // worker -> rank 0: the index it just finished (or -1), asking for more
constexpr int tag_assign = 2;   // rank 0 -> worker: the next point, or -1: no more

std::size_t run_mpi(const Plan& plan, const Sample& sample, const FarmOptions& options) {
  const auto start = Clock::now();
  MpiSession mpi;
  const int cores = available_cores();
  // One run at a time per rank, with this node's cores shared among its ranks.
  const Parallelism p{1, options.threads > 0 ? options.threads : std::max(1, cores / mpi.local_size())};
  // Every rank checks the plan, so bad input stops them all alike before anything runs.
  const std::vector<std::size_t> pending = unfinished_points(plan);
  if (mpi.rank() != 0) {
    int finished = -1, assigned = -1;
    try {
      for (;;) {
        MPI_Send(&finished, 1, MPI_INT, 0, tag_request, MPI_COMM_WORLD);
        MPI_Recv(&assigned, 1, MPI_INT, 0, tag_assign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (assigned < 0) break;
        finished = run_point(plan, plan.points[std::size_t(assigned)], sample, p.threads) ? assigned : -1;
      }
    } catch (const std::exception& e) {
      // The ledger itself failed (a full disk, a lost file system): rank 0 would wait for this rank's
      // next request forever, so end the whole job; a restart resumes it.
      fmt::print(stderr, "rupture: error: MPI rank {}: {}\n", mpi.rank(), e.what());
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
    return 0;
  }
  write_plan(plan);
  if (options.print)
    fmt::print("scan {}: {} points, {} to run on {} MPI ranks x {} threads\n", plan.folder.string(),
               plan.points.size(), pending.size(), mpi.size(), p.threads);
  std::mutex mutex;
  std::size_t next = 0, done = plan.points.size() - pending.size();
  const auto take = [&]() -> int {
    const std::lock_guard guard(mutex);
    return next < pending.size() ? int(pending[next++]) : -1;
  };
  const auto finished = [&](std::size_t index) {
    const std::lock_guard guard(mutex);
    ++done;
    if (options.print) print_point(plan, index, done);
    write_aggregate(plan, farm_info(options, p, mpi.size(), start));
  };
  // Rank 0 runs points too, on a thread of its own, while the main thread serves requests.
  std::exception_ptr local_failure;
  std::thread local([&] {
    try {
      for (int k = take(); k >= 0; k = take())
        if (run_point(plan, plan.points[std::size_t(k)], sample, p.threads)) finished(std::size_t(k));
    } catch (...) {
      local_failure = std::current_exception();
    }
  });
  int stopped = 0;
  while (stopped < mpi.size() - 1) {
    int flag = 0;
    MPI_Status probe;
    MPI_Iprobe(MPI_ANY_SOURCE, tag_request, MPI_COMM_WORLD, &flag, &probe);
    if (!flag) {
      // Polling with a pause, not a blocking receive: OpenMPI busy-waits in MPI_Recv and would take
      // a core from rank 0's own run.
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    int finished_index = -1;
    MPI_Recv(&finished_index, 1, MPI_INT, probe.MPI_SOURCE, tag_request, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (finished_index >= 0) finished(std::size_t(finished_index));
    const int assigned = take();
    MPI_Send(&assigned, 1, MPI_INT, probe.MPI_SOURCE, tag_assign, MPI_COMM_WORLD);
    if (assigned < 0) ++stopped;
  }
  local.join();
  if (local_failure) std::rethrow_exception(local_failure);
  write_aggregate(plan, farm_info(options, p, mpi.size(), start));
  return done;
}

#endif

}  // namespace

Parallelism choose_parallelism(int cores, std::size_t pending, int jobs, int threads) {
  cores = std::max(cores, 1);
  const int work = int(std::clamp<std::size_t>(pending, 1, 1 << 20));
  Parallelism p;
  if (jobs > 0 && threads > 0) return {jobs, threads};
  if (threads > 0) return {std::max(1, std::min(work, cores / threads)), threads};
  p.jobs = jobs > 0 ? jobs : std::min(work, cores);
  p.threads = std::max(1, cores / p.jobs);
  return p;
}

int available_cores() {
  // The cores this process may run on (a batch scheduler's allocation, taskset), not the machine's.
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return int(std::max(1u, std::thread::hardware_concurrency()));
}

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

std::size_t run_scan(const Plan& plan, const Sample& sample, const FarmOptions& options) {
#ifdef RUPTURE_HAVE_MPI
  if (launched_by_mpi()) return run_mpi(plan, sample, options);
#endif
  const auto start = Clock::now();
  const std::vector<std::size_t> pending = unfinished_points(plan);
  write_plan(plan);
  const Parallelism p = choose_parallelism(available_cores(), pending.size(), options.jobs, options.threads);
  if (options.print)
    fmt::print("scan {}: {} points, {} to run, {} jobs x {} threads\n", plan.folder.string(),
               plan.points.size(), pending.size(), p.jobs, p.threads);
  std::size_t done = plan.points.size() - pending.size();
  run_pool(plan, sample, pending, p, [&](std::size_t index) {
    ++done;
    if (options.print) print_point(plan, index, done);
    write_aggregate(plan, farm_info(options, p, 1, start));
  });
  write_aggregate(plan, farm_info(options, p, 1, start));
  return done;
}

void run_task(const Plan& plan, const Sample& sample, std::size_t index, int threads, bool print) {
  if (index >= plan.points.size())
    throw InputError("--task-index",
                     fmt::format("{} is past the last point ({} points, indices 0 to {})", index,
                                 plan.points.size(), plan.points.size() - 1),
                     fmt::format("submit the array as --array=0-{}", plan.points.size() - 1));
  const Point& point = plan.points[index];
  if (const auto result = read_result(plan, point)) {
    check_result_matches(plan, point, *result);
    if (print) fmt::print("{}: finished before ({})\n", point.name, result->value("status", "?"));
    return;
  }
  write_plan(plan);
  const int t = threads > 0 ? threads : available_cores();
  if (!run_point(plan, point, sample, t)) {
    if (print) fmt::print("{}: held by another process; left to it\n", point.name);
    return;
  }
  if (print) print_point(plan, index, 1);
}

void write_aggregate(const Plan& plan, const nlohmann::json& info) {
  std::vector<nlohmann::json> rows;
  std::map<std::string, int> counts;
  nlohmann::json points = nlohmann::json::array();
  for (const auto& point : plan.points) {
    rows.push_back(result_row(plan, point));
    const auto& row = rows.back();
    const std::string s = row.value("status", "");
    ++counts[s];
    points.push_back({{"index", point.index},
                      {"folder", "points/" + point.name},
                      {"status", s},
                      {"why", row.contains("why") ? row.at("why") : nlohmann::json(nullptr)}});
  }
  io::write_file_atomically(plan.folder / "results.csv",
                            format_results(rows, {fmt::format("rupture {} scan results; units in brackets, "
                                                              "text columns have none, an empty field is a "
                                                              "missing value (docs/formats.md)",
                                                              version_string)}));
  // A re-analysis or a collection keeps the run's record (its command, version, cores and wall
  // time) and adds its own beside it: the runs it aggregates are still those.
  const bool after_the_run = info.contains("reanalysed") || info.contains("collected");
  nlohmann::json scan = nlohmann::json::object();
  if (const auto previous = plan.folder / "scan.json"; after_the_run && std::filesystem::exists(previous)) {
    try {
      scan = nlohmann::json::parse(io::read_text_file(previous));
    } catch (const nlohmann::json::exception&) {
      scan = nlohmann::json::object();  // unreadable: the aggregate below is still whole
    }
    if (!scan.is_object()) scan = nlohmann::json::object();
  }
  if (!after_the_run || !scan.contains("version")) scan["version"] = version_string;
  scan.update({{"tool", "rupture scan"},
               {"scan_config", plan.scan_config},
               {"base", plan.base.string()},
               {"points_total", plan.points.size()},
               {"counts", counts},
               {"points", points}});
  scan.update(info);
  io::write_json_atomically(plan.folder / "scan.json", scan);
}

std::string status_report(const Plan& plan) {
  std::string out =
      fmt::format("{:>5}  {:<32} {:<14} {:>8}  {}\n", "point", "folder", "status", "attempts", "why");
  int done = 0, failed = 0, running = 0, pending = 0, partial = 0;
  for (const auto& point : plan.points) {
    const PointStatus s = point_status(plan, point);
    done += s.status == status::ok;
    failed += s.state == PointState::finished && s.status != status::ok;
    running += s.state == PointState::running;
    pending += s.state == PointState::pending || s.state == PointState::partial;
    partial += s.state == PointState::partial;
    out +=
        fmt::format("{:>5}  {:<32} {:<14} {:>8}  {}\n", point.index, point.name, s.status, s.attempts, s.why);
  }
  return out + fmt::format(
                   "{} points: {} done, {} failed, {} running, {} pending ({} of them partial: an attempt "
                   "was interrupted and will be redone)\n",
                   plan.points.size(), done, failed, running, pending, partial);
}

}  // namespace rupture::scan
