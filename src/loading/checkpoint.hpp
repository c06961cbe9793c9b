// loading/checkpoint: restart files of `rupture run`. Owns the binary format (magic, version,
// payload size, payload, FNV-1a 64 checksum), writing it atomically, reading it back with every
// size and index checked, and the run folder's checkpoints/ (the newest two kept, the newest valid
// one found). Not: when to checkpoint or how to resume (loading/run), the engine's state (dem/).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "dem/system.hpp"
#include "io/vtk.hpp"
#include "loading/separation.hpp"
#include "sample/sample.hpp"

namespace rupture::loading {

// Written into every checkpoint. A reader takes this one and format 1 (rupture 0.1, which did not
// record the prefix hashes) and refuses any other.
inline constexpr std::uint32_t checkpoint_format_version = 3;

// The run loop's own state between two steps (besides the engine's). The live monitor is not
// stored: it only ever consumed the curves.csv rows, so a resume replays them.
// The running sums of one curves.csv row's means: strain (%), top plate force (N) and elastic energy
// (mJ), sampled every row_mean_stride steps since the previous row.
struct RowMeans {
  double strain = 0.0, force_top = 0.0, elastic_energy = 0.0;
  std::uint64_t samples = 0;
};

struct LoopState {
  std::uint64_t curves_bytes = 0;  // bytes of curves.csv written and synced at this step
  std::uint64_t curves_rows = 0;   // data rows among them
  std::uint64_t breaks_bytes = 0;  // bytes of breaks.csv
  // FNV-1a 64 of those first curves_bytes and breaks_bytes (format 2): a resume checks that the
  // files still begin with exactly what the checkpoint saw before it cuts them back.
  std::uint64_t curves_hash = 0, breaks_hash = 0;
  std::uint64_t last_recorded = 0;         // step of the last curves.csv row
  double max_work = 0.0;                   // mJ: largest |W| recorded so far
  double max_energy_error = 0.0;           // mJ
  double max_relative_energy_error = 0.0;  // 1
  bool separated = false;                  // a separation rule has fired
  double separation_strain = 0.0;          // % where it fired
  std::string separation_rule;             // which one ("" before)
  LoadFreeWatch::State load_free;          // the load-free rule's running sums
  std::vector<io::PvdEntry> snapshots;     // the snapshots.pvd list so far
  double wall_seconds = 0.0;               // s of wall time spent before this checkpoint
  RowMeans row_means;                      // the sums of the curves.csv row being averaged (format 3)
};

struct Checkpoint {
  std::uint32_t format = checkpoint_format_version;  // as read (1: no prefix hashes)
  std::string version;                               // rupture version that wrote it
  std::string command;                               // the command that started the run
  std::string config_file;  // the config it read (relative sample paths resolve against it)
  std::string config_json;  // the resolved config (loading::to_json): a resume rebuilds the run from it
  std::uint64_t sample_fingerprint = 0;  // of the sample the run started from (sample_fingerprint())
  LoopState loop;
  dem::EngineState engine;
};

// FNV-1a 64 of everything that defines a sample (positions, radii, groups, ids, bonds, density):
// a resume refuses a sample that changed since the run began.
std::uint64_t sample_fingerprint(const Sample& sample);

// The file's bytes, and their parse. parse_checkpoint throws InputError naming `source`, the field
// and the fix for any malformed input (wrong magic or version, bad checksum, truncation, sizes
// that do not add up) and never reads outside `bytes`: the entry point for fuzzing.
std::string encode_checkpoint(const Checkpoint& checkpoint);
Checkpoint parse_checkpoint(std::string_view bytes, const std::string& source);
// Atomic write (temporary file, fsync, rename); throws RunError and leaves `path` untouched if the
// write fails (a full disk). read_checkpoint throws InputError as parse_checkpoint does.
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& checkpoint);
Checkpoint read_checkpoint(const std::filesystem::path& path);

// A run folder's checkpoints: FOLDER/checkpoints/step_NNNNNNNNNN.ckpt.
std::filesystem::path checkpoint_path(const std::filesystem::path& folder, std::uint64_t step);
// Writes the checkpoint of `checkpoint.engine.step`, then removes all but the newest `keep`.
// Returns the file written.
std::filesystem::path save_checkpoint(const std::filesystem::path& folder, const Checkpoint& checkpoint,
                                      std::size_t keep = 2);
// The folder's checkpoint files, newest (highest step) first.
std::vector<std::filesystem::path> list_checkpoints(const std::filesystem::path& folder);

struct LoadedCheckpoint {
  Checkpoint checkpoint;
  std::filesystem::path file;
  std::vector<std::string> warnings;  // one per newer checkpoint that was unreadable, and why
};
// The newest checkpoint that reads back whole; throws InputError when there is none.
LoadedCheckpoint load_newest_checkpoint(const std::filesystem::path& folder);

}  // namespace rupture::loading
