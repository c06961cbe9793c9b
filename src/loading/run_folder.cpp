#include "loading/run_folder.hpp"

#include <fmt/format.h>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "loading/checkpoint.hpp"

namespace rupture::loading {

const std::vector<std::string> run_outputs = {"run.json",      "curves.csv",  "breaks.csv",  "snapshots.pvd",
                                              "analysis.json", "report.html", "checkpoints", "snapshots",
                                              "figures",       "run.log"};

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

bool has_ended(const nlohmann::json& record) {
  const std::string status = record.value("status", "");
  return status == "finished" || (status == "failed" && record.value("stop_reason", "") == "unstable");
}

std::unique_ptr<io::FolderLock> claim_new_folder(const std::filesystem::path& folder,
                                                 const FolderClaim& claim) {
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
  auto lock = std::make_unique<io::FolderLock>(folder, claim.command);
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
  } else if (!claim.overwrite) {
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
  const double checkpoint_bytes = double(claim.checkpoint_state_bytes) + 65536.0;
  const double needed = double(claim.checkpoint_keep + 1) * checkpoint_bytes;
  const auto space = fs::space(folder, ec);
  if (!ec && double(space.available) < needed)
    refuse(fmt::format("has {:.3g} MB free, but {} checkpoints of {:.3g} MB need {:.3g} MB",
                       double(space.available) / 1e6, claim.checkpoint_keep + 1, checkpoint_bytes / 1e6,
                       needed / 1e6),
           "free space, choose another output folder, or lower checkpoint.keep");
  return lock;
}

}  // namespace rupture::loading
