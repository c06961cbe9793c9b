// `rupture run` killed, interrupted, starved of disk and blown up, end to end. A run killed with
// SIGKILL, or stopped by SIGTERM, or by a failing write, continues with `rupture run --resume` to
// curves.csv and breaks.csv byte-identical to an uninterrupted run (also past a damaged newest
// checkpoint); a deliberately too-large dt stops as unstable with the suggested dt; an unwritable
// output folder is refused before the first step.
#include <fcntl.h>
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "dem/system.hpp"
#include "io/atomic_file.hpp"
#include "loading/checkpoint.hpp"
#include "loading/config.hpp"
#include "loading/run.hpp"
#include "support/tool.hpp"

extern char** environ;

namespace rupture::loading {
namespace {

namespace fs = std::filesystem;
using rupture::testing::slurp;
using rupture::testing::TempDir;
using ::testing::HasSubstr;

const std::string block_config = std::string(RUPTURE_EXAMPLES_DIR) + "block.toml";

// The example block made 8 x 24 x 4 (768 particles) and pulled slower: about 25,000 steps to
// separation with a curve row every 30 and a checkpoint every 1000 steps, so that a checkpoint falls
// inside a row's interval and carries its means' sums. Every run is started
// from its own folder with `-o run`, so that all of them record the same command line.
std::vector<std::string> run_args(std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"run",   block_config,
                                   "-o",    "run",
                                   "--set", "sample.lattice_cells=[8, 24, 4]",
                                   "--set", "loading.speed=100",
                                   "--set", "output.interval=30",
                                   "--set", "checkpoint.every=1000"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

struct Child {
  pid_t pid = -1;
  fs::path out, err;
};

// Starts `rupture ARGS` in `cwd` (CI=1: no progress line). A `file_limit` (bytes) caps the size of
// every file it writes (RLIMIT_FSIZE, `ulimit -f`); SIGXFSZ keeps its default action (killing the
// process), so only rupture's own handling turns a write past the limit into a failed write.
// A `wrapper` command line (strace) runs rupture under it.
Child start(const fs::path& cwd, const std::vector<std::string>& args, rlim_t file_limit = RLIM_INFINITY,
            const std::vector<std::string>& wrapper = {}) {
  static int count = 0;
  Child child{-1, cwd / fmt::format("rupture_{}.out", count), cwd / fmt::format("rupture_{}.err", count)};
  ++count;
  // Everything the child needs is prepared before fork: it only calls async-signal-safe functions.
  std::vector<std::string> words = wrapper;
  words.push_back(RUPTURE_BINARY);
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  std::string ci = "CI=1";
  std::vector<char*> envp = {ci.data()};
  for (char** e = environ; *e != nullptr; ++e) envp.push_back(*e);
  envp.push_back(nullptr);
  const std::string dir = cwd.string(), out = child.out.string(), err = child.err.string();
  child.pid = fork();
  if (child.pid == 0) {
    const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int in = open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || in < 0 || chdir(dir.c_str()) != 0) _exit(126);
    dup2(in, 0);
    dup2(o, 1);
    dup2(e, 2);
    if (file_limit != RLIM_INFINITY) {
      signal(SIGXFSZ, SIG_DFL);
      const rlimit limit{file_limit, file_limit};
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  EXPECT_GT(child.pid, 0) << "fork failed";
  return child;
}

struct Ended {
  int exit_code = -1;  // -1 when ended by a signal
  int signal = 0;
  std::string out, err;
};

Ended wait_for_end(const Child& child) {
  int status = 0;
  waitpid(child.pid, &status, 0);
  Ended ended;
  if (WIFEXITED(status)) ended.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) ended.signal = WTERMSIG(status);
  ended.out = slurp(child.out);
  ended.err = slurp(child.err);
  return ended;
}

Ended run_to_end(const fs::path& cwd, const std::vector<std::string>& args) {
  return wait_for_end(start(cwd, args));
}

// Waits until `ready()` holds while the child still runs (the child ending first fails the test:
// the run must be caught midway).
bool wait_until(const Child& child, const std::function<bool()>& ready) {
  while (!ready()) {
    int status = 0;
    if (waitpid(child.pid, &status, WNOHANG) == child.pid) {
      ADD_FAILURE() << "the run ended before it could be stopped midway";
      return false;
    }
    usleep(1000);
  }
  return true;
}

// Waits for the checkpoint of `step` and for curves.csv to grow past the bytes it recorded, so that
// the resume has rows to cut away.
bool wait_for_checkpoint(const Child& child, const fs::path& folder, std::uint64_t step) {
  const fs::path file = checkpoint_path(folder, step);
  if (!wait_until(child, [&] { return fs::exists(file); })) return false;
  const std::uint64_t recorded = read_checkpoint(file).loop.curves_bytes;
  return wait_until(child, [&] { return fs::file_size(folder / "curves.csv") > recorded; });
}

// The uninterrupted run, in `dir`/reference/run.
fs::path reference_run(const TempDir& dir, std::vector<std::string> extra = {}) {
  const fs::path cwd = dir / "reference";
  fs::create_directories(cwd);
  const Ended r = run_to_end(cwd, run_args(std::move(extra)));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("finished: separated"));
  return cwd / "run";
}

void expect_same_outputs(const fs::path& resumed, const fs::path& reference) {
  for (const char* name : {"curves.csv", "breaks.csv"}) {
    const std::string a = slurp(resumed / name), b = slurp(reference / name);
    EXPECT_GT(b.size(), 1000u) << name;
    EXPECT_TRUE(a == b) << name << " differs from the uninterrupted run (" << a.size() << " vs " << b.size()
                        << " bytes)";
  }
  const auto a = nlohmann::json::parse(slurp(resumed / "run.json"));
  const auto b = nlohmann::json::parse(slurp(reference / "run.json"));
  EXPECT_EQ(a["status"], "finished");
  for (const char* key : {"stop_reason", "steps", "final_strain", "separation_strain", "broken_bonds",
                          "monitor", "energy_balance", "command"})
    EXPECT_EQ(a[key], b[key]) << key;
  EXPECT_FALSE(fs::exists(resumed / "checkpoints")) << "a finished run removes its checkpoints";
}

TEST(Resume, KilledRunContinuesToByteIdenticalFiles) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const fs::path cwd = dir / "killed", folder = cwd / "run";
  fs::create_directories(cwd);
  const Child child = start(cwd, run_args());
  ASSERT_TRUE(wait_for_checkpoint(child, folder, 2000));
  kill(child.pid, SIGKILL);
  const Ended killed = wait_for_end(child);
  ASSERT_EQ(killed.signal, SIGKILL);
  EXPECT_LT(slurp(folder / "curves.csv").size(), slurp(reference / "curves.csv").size());

  // Starting afresh over the unfinished run is refused, pointing at --resume.
  const Ended again = run_to_end(cwd, run_args());
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_THAT(again.err, HasSubstr("holds the checkpoints of an unfinished run"));
  EXPECT_THAT(again.err, HasSubstr("rupture run --resume run"));

  const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(resumed.err, "");
  expect_same_outputs(folder, reference);
  const auto report = nlohmann::json::parse(slurp(folder / "run.json"));
  ASSERT_EQ(report["resumes"].size(), 1u);
  EXPECT_GE(report["resumes"][0]["step"].get<std::uint64_t>(), 2000u);
  EXPECT_EQ(report["resumes"][0]["command"], "rupture run --resume run");

  const Ended twice = run_to_end(cwd, {"run", "--resume", "run"});
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_THAT(twice.err, HasSubstr("the run already ended (finished, separated)"));
}

TEST(Resume, DamagedNewestCheckpointFallsBackToTheOlderWithAWarning) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const fs::path cwd = dir / "killed", folder = cwd / "run";
  fs::create_directories(cwd);
  const Child child = start(cwd, run_args());
  ASSERT_TRUE(wait_for_checkpoint(child, folder, 3000));
  kill(child.pid, SIGKILL);
  ASSERT_EQ(wait_for_end(child).signal, SIGKILL);

  const auto files = list_checkpoints(folder);
  ASSERT_EQ(files.size(), 2u) << "the newest two are kept";
  const std::uint64_t older = read_checkpoint(files[1]).engine.step;
  std::string bytes = slurp(files[0]);
  bytes[bytes.size() / 2] ^= 0x20;  // one flipped bit in the engine state
  io::write_file_atomically(files[0], bytes);

  const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr("warning: skipping unreadable checkpoint"));
  EXPECT_THAT(resumed.err, HasSubstr(files[0].filename().string() + ": checksum"));
  expect_same_outputs(folder, reference);
  const auto report = nlohmann::json::parse(slurp(folder / "run.json"));
  EXPECT_EQ(report["resumes"][0]["step"].get<std::uint64_t>(), older);
  EXPECT_EQ(report["resumes"][0]["warnings"].size(), 1u);
}

TEST(Resume, SigtermWritesACheckpointAndExitsWithTheResumeCommand) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const fs::path cwd = dir / "stopped", folder = cwd / "run";
  fs::create_directories(cwd);
  const Child child = start(cwd, run_args());
  ASSERT_TRUE(wait_for_checkpoint(child, folder, 1000));
  kill(child.pid, SIGTERM);
  const Ended stopped = wait_for_end(child);
  EXPECT_EQ(stopped.exit_code, 128 + SIGTERM) << stopped.err;
  EXPECT_THAT(stopped.err, HasSubstr("interrupted by SIGTERM after step"));
  EXPECT_THAT(stopped.err, HasSubstr("continue with `rupture run --resume run`"));
  const auto report = nlohmann::json::parse(slurp(folder / "run.json"));
  EXPECT_EQ(report["status"], "interrupted");
  const std::uint64_t step = report["steps"];
  EXPECT_GT(step, 1000u);
  EXPECT_EQ(list_checkpoints(folder).front(), checkpoint_path(folder, step))
      << "the final checkpoint is newest";

  const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(folder, reference);
}

TEST(Resume, FailedWriteKeepsTheLastCheckpointAndTheRunResumes) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const fs::path cwd = dir / "full", folder = cwd / "run";
  fs::create_directories(cwd);
  // Files may grow to 150 kB: the checkpoints (about 127 kB) fit, the final curves.csv
  // (about 260 kB) does not.
  const std::uint64_t limit = 150000;
  ASSERT_GT(fs::file_size(reference / "curves.csv"), limit);
  const Ended full = wait_for_end(start(cwd, run_args(), limit));
  EXPECT_EQ(full.exit_code, 1) << "signal " << full.signal;
  EXPECT_THAT(full.err,
              HasSubstr("curves.csv: write failed (File too large); the file size limit is reached"));
  EXPECT_THAT(full.err, HasSubstr("is intact: make room, then continue with `rupture run --resume run`"));
  const auto report = nlohmann::json::parse(slurp(folder / "run.json"));
  EXPECT_EQ(report["status"], "failed");
  EXPECT_EQ(report["stop_reason"], "write_failed");
  const LoadedCheckpoint last = load_newest_checkpoint(folder);
  EXPECT_TRUE(last.warnings.empty());
  EXPECT_LE(last.checkpoint.loop.curves_bytes, limit);
  EXPECT_THAT(full.err, HasSubstr(last.file.filename().string()));

  const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(folder, reference);
}

TEST(Resume, TooLargeDtIsStoppedAsUnstableWithTheSuggestedDt) {
  TempDir dir;
  const RunConfig config = load_config(block_config);
  const Sample sample = resolve_sample(config);
  const dem::System system(sample, config.dem_params(sample.density));
  // 12 times the stability limit, let through by time.allow_unstable_dt.
  const double dt = 12.0 * system.critical_dt();
  const Ended r =
      run_to_end(dir.path(), {"run", block_config, "-o", "run", "--set", fmt::format("time.dt={}", dt),
                              "--set", "time.allow_unstable_dt=true", "--set", "checkpoint.every=2"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("unstable at step"));
  EXPECT_THAT(r.err, HasSubstr("of its radius in one step"));
  EXPECT_THAT(r.err, HasSubstr("particle id"));
  EXPECT_THAT(r.err, HasSubstr("is too large for k_n = 1000 N/mm"));
  // The suggestion is the automatic dt: time.safety (0.4) times the critical dt.
  const std::string suggested = fmt::format("suggested dt = {:.3g} s", 0.4 * system.critical_dt());
  EXPECT_THAT(r.err, HasSubstr(suggested));
  const auto report = nlohmann::json::parse(slurp(dir / "run" / "run.json"));
  EXPECT_EQ(report["status"], "failed");
  EXPECT_EQ(report["stop_reason"], "unstable");
  EXPECT_THAT(report["error"].get<std::string>(), HasSubstr(suggested));
  EXPECT_THAT(slurp(dir / "run" / "curves.csv"), HasSubstr("\n0,0,0,")) << "the rows so far are kept";
  EXPECT_FALSE(fs::exists(dir / "run" / "checkpoints")) << "an unstable run cannot be resumed";
}

TEST(Resume, UnwritableOutputFolderIsRefusedBeforeTheRun) {
  TempDir dir;
  io::write_file_atomically(dir / "occupied", "a file where the folder should go\n");
  const Ended r = run_to_end(dir.path(), {"run", block_config, "-o", "occupied/run"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("occupied/run: cannot create the output folder"));
  EXPECT_THAT(r.err, HasSubstr("choose a writable folder"));

  const Ended none = run_to_end(dir.path(), {"run", "--resume", "nowhere"});
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.err, HasSubstr("nowhere: is not a run folder"));
}

// Every file under `folder` with its bytes, but the lock file: a resume that takes the lock and
// then refuses may leave its own name there, which is not data.
std::map<std::string, std::string> folder_bytes(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().filename() != ".rupture-lock")
      files[fs::relative(entry.path(), folder).string()] = slurp(entry.path());
  return files;
}

// A run killed after its checkpoint of `step`, in `dir`/NAME/run.
fs::path killed_run(const TempDir& dir, const std::string& name, std::uint64_t step,
                    std::vector<std::string> extra = {}) {
  const fs::path cwd = dir / name;
  fs::create_directories(cwd);
  const Child child = start(cwd, run_args(std::move(extra)));
  EXPECT_TRUE(wait_for_checkpoint(child, cwd / "run", step));
  kill(child.pid, SIGKILL);
  EXPECT_EQ(wait_for_end(child).signal, SIGKILL);
  return cwd / "run";
}

TEST(RunFolder, ASecondWriterIsRefusedNamingTheFirst) {
  TempDir dir;
  const fs::path cwd = dir / "busy", folder = cwd / "run";
  fs::create_directories(cwd);
  const Child first = start(cwd, run_args());
  ASSERT_TRUE(wait_for_checkpoint(first, folder, 1000));
  for (const auto& args :
       {run_args(), run_args({"--overwrite"}), std::vector<std::string>{"run", "--resume", "run"}}) {
    const Ended second = run_to_end(cwd, args);
    EXPECT_EQ(second.exit_code, 2) << second.err;
    EXPECT_THAT(second.err, HasSubstr(fmt::format(
                                "run: is being written by another process (pid {}: rupture run", first.pid)));
    EXPECT_THAT(second.err, HasSubstr("wait for it to end, or choose another output folder"));
  }
  const Ended report = run_to_end(cwd, {"report", "run"});
  EXPECT_EQ(report.exit_code, 2);
  EXPECT_THAT(report.err, HasSubstr("is being written by another process"));
  // The kernel drops the lock of a killed run: it resumes.
  kill(first.pid, SIGKILL);
  ASSERT_EQ(wait_for_end(first).signal, SIGKILL);
  const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
  EXPECT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(folder / "run.json"))["status"], "finished");
}

TEST(RunFolder, AnEndedRunIsReplacedOnlyWithOverwriteAndOtherFilesNever) {
  TempDir dir;
  const fs::path folder = reference_run(dir), cwd = folder.parent_path();
  const auto before = folder_bytes(folder);
  const Ended again = run_to_end(cwd, run_args());
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_THAT(again.err, HasSubstr("run: holds a finished run (separated), which is kept; give --overwrite"));
  EXPECT_EQ(folder_bytes(folder), before);

  io::write_file_atomically(folder / "notes.txt", "my own notes\n");
  const Ended replaced = run_to_end(cwd, run_args({"--overwrite"}));
  ASSERT_EQ(replaced.exit_code, 0) << replaced.err;
  EXPECT_EQ(slurp(folder / "notes.txt"), "my own notes\n") << "--overwrite removes only rupture's outputs";
  EXPECT_THAT(nlohmann::json::parse(slurp(folder / "run.json"))["command"].get<std::string>(),
              HasSubstr(" --overwrite"));

  const fs::path foreign = cwd / "foreign";
  fs::create_directories(foreign);
  io::write_file_atomically(foreign / "data.csv", "1,2\n");
  const Ended refused = run_to_end(cwd, {"run", block_config, "-o", "foreign", "--overwrite"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, HasSubstr("foreign: holds files that rupture run did not write (e.g. data.csv)"));
  EXPECT_EQ(folder_bytes(foreign), (std::map<std::string, std::string>{{"data.csv", "1,2\n"}}));
}

// What a kill at each step of the finish sequence leaves (each step is one atomic write or one
// removal), rebuilt from real run folders: every state either resumes, or is named and replaced
// with --overwrite; none is stuck.
TEST(RunFolder, EveryPhaseOfTheFinishSequenceLeavesAUsableFolder) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const fs::path killed = killed_run(dir, "killed", 1000);

  // Killed after run.json said "finished", before the checkpoints were removed.
  const fs::path cwd = dir / "finishing", folder = cwd / "run";
  fs::create_directories(cwd);
  fs::copy(reference, folder, fs::copy_options::recursive);
  fs::copy(killed / "checkpoints", folder / "checkpoints", fs::copy_options::recursive);
  const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
  EXPECT_EQ(resumed.exit_code, 2);
  EXPECT_THAT(resumed.err, HasSubstr("the run already ended (finished, separated)"));
  const Ended fresh = run_to_end(cwd, run_args());
  EXPECT_EQ(fresh.exit_code, 2);
  EXPECT_THAT(fresh.err, HasSubstr("holds a finished run (separated), which is kept; give --overwrite"));
  const Ended replaced = run_to_end(cwd, run_args({"--overwrite"}));
  EXPECT_EQ(replaced.exit_code, 0) << replaced.err;
  EXPECT_FALSE(fs::exists(folder / "checkpoints"));

  // Killed before the first checkpoint: run.json says "running" and there is nothing to resume.
  const fs::path early = dir / "early";
  fs::create_directories(early);
  fs::copy(killed, early / "run", fs::copy_options::recursive);
  fs::remove_all(early / "run" / "checkpoints");
  const Ended nothing = run_to_end(early, {"run", "--resume", "run"});
  EXPECT_EQ(nothing.exit_code, 2);
  EXPECT_THAT(nothing.err, HasSubstr("holds no checkpoint"));
  const Ended stopped = run_to_end(early, run_args());
  EXPECT_EQ(stopped.exit_code, 2);
  EXPECT_THAT(stopped.err,
              HasSubstr("holds a run that was stopped before its first checkpoint, which is kept"));
  EXPECT_EQ(run_to_end(early, run_args({"--overwrite"})).exit_code, 0);

  // Killed between a checkpoint and the next rows: resumes (the kill tests above), and even with
  // --overwrite a fresh run does not destroy a run that can still be continued.
  const Ended over = run_to_end(killed.parent_path(), run_args({"--overwrite"}));
  EXPECT_EQ(over.exit_code, 2);
  EXPECT_THAT(over.err, HasSubstr("holds the checkpoints of an unfinished run"));
}

// The finish sequence killed for real: strace lists the run's renames and removals once, then
// kills (SIGKILL, injected at the syscall's entry) a second, identical run exactly at the rename
// that would have made run.json "finished", at the first removal of a checkpoint after it, and at
// the removal of the emptied checkpoints folder. Each folder is then usable: the first resumes to
// the uninterrupted run's files, the others say the run ended and take --overwrite.
TEST(RunFolder, KillsInjectedAtEachStepOfTheFinishSequence) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const std::string calls = "rename,renameat,renameat2,unlink,unlinkat,rmdir";
  // LeakSanitizer stops the world with ptrace, which a traced process cannot (sanitizer build).
  const std::string no_leak_check = "ASAN_OPTIONS=detect_leaks=0";
  const fs::path traced = dir / "traced";
  fs::create_directories(traced);
  const Ended listed =
      wait_for_end(start(traced, run_args(), RLIM_INFINITY,
                         {RUPTURE_STRACE, "-E", no_leak_check, "-o", "trace.txt", "-e", "trace=" + calls}));
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  // Each call as (name, its count among calls of that name so far): strace's when=N counts so.
  struct Call {
    std::string name, line;
    int nth;
  };
  std::vector<Call> sequence;
  std::map<std::string, int> seen;
  {
    std::istringstream trace(slurp(traced / "trace.txt"));
    for (std::string line; std::getline(trace, line);) {
      const auto paren = line.find('(');
      if (paren == std::string::npos || line.find("resumed>") != std::string::npos) continue;
      const std::string name = line.substr(0, paren);
      sequence.push_back({name, line, ++seen[name]});
    }
  }
  std::size_t finished_at = sequence.size();
  for (std::size_t i = 0; i < sequence.size(); ++i)
    if (sequence[i].name.starts_with("rename") &&
        sequence[i].line.find("run/run.json\"") != std::string::npos)
      finished_at = i;  // the last rename of run.json: the "finished" one
  ASSERT_LT(finished_at + 2, sequence.size()) << "no checkpoint removal after the final run.json";
  const Call& checkpoint_removal = sequence[finished_at + 1];
  const Call& folder_removal = sequence.back();
  ASSERT_THAT(checkpoint_removal.line, HasSubstr(".ckpt\"")) << "remove_all unlinks each checkpoint";
  ASSERT_THAT(folder_removal.line, HasSubstr("run/checkpoints\""));

  const auto kill_at = [&](const Call& call, const std::string& name) {
    const fs::path cwd = dir / name;
    fs::create_directories(cwd);
    const Ended killed = wait_for_end(
        start(cwd, run_args(), RLIM_INFINITY,
              {RUPTURE_STRACE, "-E", no_leak_check, "-o", "/dev/null", "-e", "trace=" + call.name, "-e",
               fmt::format("inject={}:signal=KILL:when={}", call.name, call.nth)}));
    EXPECT_NE(killed.exit_code, 0) << name << ": the run was not killed";
    return cwd;
  };
  {
    const fs::path cwd = kill_at(sequence[finished_at], "before-finished");
    EXPECT_EQ(nlohmann::json::parse(slurp(cwd / "run" / "run.json"))["status"], "running");
    const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
    ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
    expect_same_outputs(cwd / "run", reference);
  }
  for (const auto& [call, name] : {std::pair{checkpoint_removal, "removing-checkpoints"},
                                   std::pair{folder_removal, "removing-the-folder"}}) {
    SCOPED_TRACE(name);
    const fs::path cwd = kill_at(call, name);
    EXPECT_EQ(nlohmann::json::parse(slurp(cwd / "run" / "run.json"))["status"], "finished");
    EXPECT_TRUE(fs::exists(cwd / "run" / "checkpoints"));
    const Ended resumed = run_to_end(cwd, {"run", "--resume", "run"});
    EXPECT_EQ(resumed.exit_code, 2);
    EXPECT_THAT(resumed.err, HasSubstr("the run already ended (finished, separated)"));
    const Ended replaced = run_to_end(cwd, run_args({"--overwrite"}));
    EXPECT_EQ(replaced.exit_code, 0) << replaced.err;
    EXPECT_FALSE(fs::exists(cwd / "run" / "checkpoints"));
  }
}

TEST(RunFolder, ARefusedResumeChangesNothing) {
  TempDir dir;
  const fs::path reference = reference_run(dir);
  const fs::path pristine = killed_run(dir, "killed", 2000);
  const fs::path newest = list_checkpoints(pristine).front();
  const Checkpoint saved = read_checkpoint(newest);
  ASSERT_EQ(saved.format, checkpoint_format_version);

  // Each damage is applied to a fresh copy of the killed run's folder.
  struct Damage {
    const char* name;
    std::function<void(const fs::path&)> apply;
    const char* expected;
  };
  const auto rewrite_checkpoint = [&](const std::function<void(Checkpoint&)>& edit) {
    return [&, edit](const fs::path& folder) {
      Checkpoint c = saved;
      edit(c);  // re-encoded: the checksum fits, the content does not
      write_checkpoint(folder / "checkpoints" / newest.filename(), c);
      fs::remove(folder / "checkpoints" / list_checkpoints(pristine).back().filename());
    };
  };
  const std::vector<Damage> damages = {
      {"a row inside the checkpointed part edited",
       [](const fs::path& folder) {
         std::string text = slurp(folder / "curves.csv");
         text[text.find("\n0,0,0,") + 1] = '7';
         io::write_file_atomically(folder / "curves.csv", text);
       },
       "curves.csv: its first "},
      {"breaks.csv cut short", [](const fs::path& folder) { fs::resize_file(folder / "breaks.csv", 50); },
       "breaks.csv: holds 50 bytes, fewer than the "},
      {"breaks_bytes = 1", rewrite_checkpoint([](Checkpoint& c) { c.loop.breaks_bytes = 1; }),
       "breaks.csv: its first 1 bytes are not those its checkpoint recorded"},
      {"curves_bytes shortened by a row",
       rewrite_checkpoint([](Checkpoint& c) { c.loop.curves_bytes -= 40; }), "curves.csv: its first "},
      {"another run's checkpoint (other rows)",
       rewrite_checkpoint([](Checkpoint& c) { c.loop.curves_hash ^= 1; }), "curves.csv: its first "},
  };
  for (const auto& damage : damages) {
    SCOPED_TRACE(damage.name);
    const fs::path cwd = dir / "damaged", folder = cwd / "run";
    fs::remove_all(cwd);
    fs::create_directories(cwd);
    fs::copy(pristine, folder, fs::copy_options::recursive);
    damage.apply(folder);
    const auto before = folder_bytes(folder);
    const Ended refused = run_to_end(cwd, {"run", "--resume", "run"});
    EXPECT_EQ(refused.exit_code, 2) << refused.err;
    EXPECT_THAT(refused.err, HasSubstr(damage.expected));
    EXPECT_EQ(folder_bytes(folder), before) << "the refused resume changed the folder";
  }
  // The undamaged folder still resumes to the uninterrupted run's files.
  const Ended resumed = run_to_end(pristine.parent_path(), {"run", "--resume", "run"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  expect_same_outputs(pristine, reference);
}

TEST(RunFolder, ACheckpointOfRupture01ResumesWithAWarning) {
  TempDir dir;
  // Checkpoints on row boundaries (every 900 steps, rows every 30): rupture 0.1 wrote no row means,
  // so a checkpoint of its format has no row's sums to lose only there.
  const std::vector<std::string> on_rows = {"--set", "checkpoint.every=900"};
  const fs::path reference = reference_run(dir, on_rows);
  const fs::path folder = killed_run(dir, "old", 900, on_rows);
  for (const auto& file : list_checkpoints(folder)) {
    Checkpoint c = read_checkpoint(file);
    c.format = 1;  // as rupture 0.1 wrote it: no prefix hashes
    write_checkpoint(file, c);
  }
  const Ended resumed = run_to_end(folder.parent_path(), {"run", "--resume", "run"});
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr("(format 1) records only the lengths of curves.csv and breaks.csv"));
  expect_same_outputs(folder, reference);
}

}  // namespace
}  // namespace rupture::loading
