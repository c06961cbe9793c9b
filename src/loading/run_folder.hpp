// loading/run_folder: the folder a run writes into: which files are a run's, whether the run there
// has ended, and claiming a folder for a new run (checked, created, locked). Not: the files'
// content (loading/run, loading/checkpoint) or the lock itself (io/file_lock).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/file_lock.hpp"

namespace rupture::loading {

// What `rupture run` leaves in its folder, and what analyze, plot and report add about that run:
// the files --overwrite removes (and nothing else, so a user's own files beside them survive).
extern const std::vector<std::string> run_outputs;

// A folder's run.json, if rupture run wrote one there (null otherwise, also when unreadable).
nlohmann::json read_run_record(const std::filesystem::path& folder);

// A run that cannot go on: it finished, or blew up (the same config would blow up again).
bool has_ended(const nlohmann::json& record);

// What claiming a folder needs to know of the run.
struct FolderClaim {
  std::string command;                       // recorded in the lock
  bool overwrite = false;                    // replace the outputs of a run that ended
  std::uint64_t checkpoint_keep = 0;         // checkpoints kept (one more is written before the oldest goes)
  std::uint64_t checkpoint_state_bytes = 0;  // the engine state a checkpoint holds
};

// The folder of a new run, claimed before the first step: not `/`, created, locked against other
// writers, free of a run that could still be resumed, of a run that ended (unless overwrite) and
// of files rupture did not write, writable, and with room for its checkpoints. A refusal throws
// InputError and leaves the folder as it was (one it created is removed again).
std::unique_ptr<io::FolderLock> claim_new_folder(const std::filesystem::path& folder,
                                                 const FolderClaim& claim);

}  // namespace rupture::loading
