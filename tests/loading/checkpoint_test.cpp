// Checkpoints: an engine restored from a checkpoint steps in lockstep with the one that wrote it
// (state hash, breaks, ledger, for any thread count); the file format round-trips every field;
// corrupt, truncated, foreign or inconsistent files are refused with the file and field named; a
// folder keeps its newest two and falls back to the older one when the newest is damaged.
#include "loading/checkpoint.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.hpp"
#include "dem/system.hpp"
#include "io/atomic_file.hpp"
#include "loading/config.hpp"
#include "loading/ramp.hpp"
#include "sample/generator.hpp"
#include "sample/lattice.hpp"
#include "support/tool.hpp"

namespace rupture::loading {
namespace {

using rupture::testing::TempDir;
using ::testing::HasSubstr;

// A block pulled hard enough that bonds break and broken pairs become contacts.
dem::Params breaking_params() {
  dem::Params p;
  p.bond_stiffness = 1e3;
  p.break_distance = 2e-3;
  p.contact_stiffness = 1e3;
  p.glue_stiffness = 1e4;
  return p;
}

struct Pull {
  double dt;
  SpeedRamp ramp;
  void step(dem::System& system) const { system.step(dt, ramp.at(double(system.steps_done() + 1) * dt)); }
};

Pull fast_pull(const dem::System& system) {
  const double dt = 0.4 * system.critical_dt();
  return {dt, SpeedRamp{2000.0, 100 * dt}};
}

Checkpoint checkpoint_of(const dem::System& system) {
  Checkpoint c;
  c.version = "test";
  c.command = "rupture run test.toml";
  c.config_json = R"({"bonds": {"stiffness": 1000.0}})";
  c.sample_fingerprint = 42;
  c.loop.curves_bytes = 1234;
  c.loop.separation_rule = "connectivity";
  c.config_file = "configs/test.toml";
  c.loop.curves_rows = 17;
  c.loop.load_free = {
      .sum = 3.5, .count = 7, .last_strain = 1.25, .peak = 9.0, .load_free = true, .free_since = 1.5};
  c.loop.snapshots = {{0.0, "snapshots/step_0000000000.vtp"}, {1e-4, "snapshots/step_0000000500.vtp"}};
  c.engine = system.save_state();
  return c;
}

// Steps `a` and `b` together, requiring the same state after every step; returns the breaks seen.
std::size_t lockstep(dem::System& a, dem::System& b, const Pull& pull, int steps) {
  std::size_t breaks = 0;
  for (int s = 0; s < steps; ++s) {
    pull.step(a);
    pull.step(b);
    EXPECT_EQ(a.state_hash(), b.state_hash()) << "step " << a.steps_done();
    EXPECT_EQ(a.break_events().size(), b.break_events().size()) << "step " << a.steps_done();
    breaks += a.break_events().size();
    a.break_events().clear();
    b.break_events().clear();
    if (::testing::Test::HasFailure()) break;
  }
  EXPECT_EQ(a.released_energy(), b.released_energy());
  EXPECT_EQ(a.plate_work(), b.plate_work());
  EXPECT_EQ(a.time(), b.time());
  EXPECT_EQ(a.neighbour_rebuilds(), b.neighbour_rebuilds());
  return breaks;
}

// A small random packing: irregular, so that every change of summation order shows in the bits.
Sample small_packing() {
  PackingParams p;
  p.size = {6.0, 6.0, 3.0};
  return generate_sample(p, 3);
}

TEST(Checkpoint, RestoredEngineStepsInLockstepThroughBreaks) {
  const Sample block = small_packing();
  dem::System original(block, breaking_params());
  const Pull pull = fast_pull(original);
  for (int s = 0; s < 300; ++s) pull.step(original);
  original.break_events().clear();
  const std::size_t broken_before = original.bond_count() - original.intact_bonds();

  const Checkpoint read = parse_checkpoint(encode_checkpoint(checkpoint_of(original)), "mem.ckpt");
  dem::System restored(block, breaking_params());
  restored.restore_state(read.engine, "mem.ckpt");
  EXPECT_EQ(restored.state_hash(), original.state_hash());
  EXPECT_EQ(restored.steps_done(), original.steps_done());
  const std::size_t breaks_after = lockstep(original, restored, pull, 600);
  EXPECT_GT(broken_before, 0u) << "bonds must have broken before the checkpoint";
  EXPECT_GT(breaks_after, 0u) << "and after it";
}

// Large enough for the parallel loops: written with 2 threads, resumed with 1 and 3.
TEST(Checkpoint, RestoreIsIndependentOfThreadCount) {
  const Sample block = make_cubic_block(16, 16, 10, 0.5);
  omp_set_num_threads(2);
  dem::System original(block, breaking_params());
  const Pull pull = fast_pull(original);
  for (int s = 0; s < 120; ++s) pull.step(original);
  const std::string bytes = encode_checkpoint(checkpoint_of(original));
  for (int s = 0; s < 150; ++s) pull.step(original);
  EXPECT_GT(original.bond_count(), original.intact_bonds()) << "bonds must break";
  for (int threads : {1, 3}) {
    omp_set_num_threads(threads);
    dem::System copy(block, breaking_params());
    copy.restore_state(parse_checkpoint(bytes, "mem.ckpt").engine, "mem.ckpt");
    for (int s = 0; s < 150; ++s) pull.step(copy);
    EXPECT_EQ(copy.state_hash(), original.state_hash()) << threads << " threads";
    EXPECT_EQ(copy.intact_bonds(), original.intact_bonds()) << threads << " threads";
  }
  omp_set_num_threads(2);
}

TEST(Checkpoint, EveryFieldRoundTrips) {
  const Sample chain = make_chain(10, 0.5);
  dem::System system(chain, breaking_params());
  const Checkpoint c = checkpoint_of(system);
  const std::string bytes = encode_checkpoint(c);
  EXPECT_EQ(bytes.substr(0, 8), "RUPTCKPT");
  const Checkpoint r = parse_checkpoint(bytes, "mem.ckpt");
  EXPECT_EQ(r.version, c.version);
  EXPECT_EQ(r.command, c.command);
  EXPECT_EQ(r.config_json, c.config_json);
  EXPECT_EQ(r.sample_fingerprint, 42u);
  EXPECT_EQ(r.loop.curves_bytes, 1234u);
  EXPECT_EQ(r.loop.separation_rule, "connectivity");
  EXPECT_EQ(r.config_file, "configs/test.toml");
  EXPECT_EQ(r.loop.curves_rows, 17u);
  EXPECT_EQ(r.loop.load_free.count, 7u);
  EXPECT_EQ(r.loop.load_free.peak, 9.0);
  EXPECT_TRUE(r.loop.load_free.load_free);
  EXPECT_EQ(r.loop.load_free.free_since, 1.5);
  ASSERT_EQ(r.loop.snapshots.size(), 2u);
  EXPECT_EQ(r.loop.snapshots[1].time, 1e-4);
  EXPECT_EQ(r.loop.snapshots[1].file, "snapshots/step_0000000500.vtp");
  EXPECT_EQ(r.engine.x, c.engine.x);
  EXPECT_EQ(r.engine.link_bond, c.engine.link_bond);
  EXPECT_EQ(r.engine.nb, c.engine.nb);
  EXPECT_EQ(encode_checkpoint(r), bytes) << "re-encoding gives the same bytes";
}

std::string message_of(const std::string& bytes) {
  try {
    parse_checkpoint(bytes, "run/checkpoints/step_0000000100.ckpt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Checkpoint, DamagedBytesAreRefusedNamingTheField) {
  const std::string good =
      encode_checkpoint(checkpoint_of(dem::System(make_chain(10, 0.5), breaking_params())));
  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  EXPECT_THAT(message_of(flipped), HasSubstr("step_0000000100.ckpt: checksum"));
  EXPECT_THAT(message_of(flipped), HasSubstr("older checkpoint"));
  EXPECT_THAT(message_of(good.substr(0, good.size() - 100)), HasSubstr(": payload_size"));
  EXPECT_THAT(message_of(good.substr(0, 10)), HasSubstr(": header"));
  EXPECT_THAT(message_of("NOTACKPT" + good.substr(8)), HasSubstr(": magic"));
  std::string newer = good;
  newer[8] = char(checkpoint_format_version + 1);
  EXPECT_THAT(message_of(newer), HasSubstr(": version"));
  // Every prefix is refused cleanly (never a crash or a read past the end).
  for (std::size_t n = 0; n < good.size(); ++n) EXPECT_NE(message_of(good.substr(0, n)), "(accepted)") << n;
}

// A checkpoint with a valid checksum but fields that do not fit: re-encoded so that the
// checksum matches, it must be refused by the field checks.
TEST(Checkpoint, InconsistentStateIsRefusedBeforeTouchingTheEngine) {
  const Sample block = make_cubic_block(4, 8, 2, 0.5);
  dem::System system(block, breaking_params());
  const Pull pull = fast_pull(system);
  for (int s = 0; s < 5; ++s) pull.step(system);
  const std::uint64_t hash = system.state_hash();
  const auto refused = [&](const Checkpoint& c) {
    try {
      system.restore_state(parse_checkpoint(encode_checkpoint(c), "x.ckpt").engine, "x.ckpt");
    } catch (const InputError& e) {
      EXPECT_EQ(system.state_hash(), hash) << "the engine is left as it was";
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  Checkpoint c = checkpoint_of(system);
  c.engine.vx.pop_back();
  EXPECT_THAT(refused(c), HasSubstr("x.ckpt: vx: holds 63 values where this run has 64"));
  c = checkpoint_of(system);
  c.engine.link_count[3] += 1;
  EXPECT_THAT(refused(c), HasSubstr("x.ckpt: link_count"));
  c = checkpoint_of(system);
  c.engine.link_bond[0] = c.engine.link_bond[1];
  EXPECT_THAT(refused(c), HasSubstr("x.ckpt: link_bond"));
  c = checkpoint_of(system);
  c.engine.nb_count[0] = 1u << 30;
  EXPECT_THAT(refused(c), HasSubstr("x.ckpt: nb_count"));
  c = checkpoint_of(system);
  c.engine.intact[0] = 7;
  EXPECT_THAT(refused(c), HasSubstr("x.ckpt: intact"));
  // Another sample: the particle order and sizes differ.
  c = checkpoint_of(dem::System(make_cubic_block(4, 6, 2, 0.5), breaking_params()));
  EXPECT_THAT(refused(c), HasSubstr("x.ckpt: sample_of_storage"));
}

TEST(Checkpoint, FolderKeepsTheNewestTwoAndFallsBackPastADamagedOne) {
  TempDir dir;
  dem::System system(make_chain(10, 0.5), breaking_params());
  const Pull pull = fast_pull(system);
  for (int round = 0; round < 3; ++round) {
    for (int s = 0; s < 10; ++s) pull.step(system);
    save_checkpoint(dir.path(), checkpoint_of(system));
  }
  const auto files = list_checkpoints(dir.path());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], checkpoint_path(dir.path(), 30));
  EXPECT_EQ(files[1], checkpoint_path(dir.path(), 20));
  EXPECT_EQ(load_newest_checkpoint(dir.path()).checkpoint.engine.step, 30u);

  std::string bytes = testing::slurp(files[0]);
  bytes[bytes.size() / 3] ^= 1;
  io::write_file_atomically(files[0], bytes);
  const LoadedCheckpoint loaded = load_newest_checkpoint(dir.path());
  EXPECT_EQ(loaded.file, files[1]);
  EXPECT_EQ(loaded.checkpoint.engine.step, 20u);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("step_0000000030.ckpt: checksum"));

  io::write_file_atomically(files[1], bytes.substr(0, 50));
  try {
    load_newest_checkpoint(dir.path());
    ADD_FAILURE() << "no readable checkpoint must be an error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("holds no readable checkpoint"));
  }
}

// A resume rebuilds the run from the config stored as JSON: every key must come back unchanged.
TEST(Checkpoint, StoredConfigReadsBackToTheSameRun) {
  const RunConfig c = parse_config(
      "[sample]\nfile = \"tissue.txt\"\ndensity = 3e-4\n[bonds]\nstiffness = 123.25\nbreak_rule = "
      "\"relative\"\n"
      "[time]\ndt = 1.5e-8\n[checkpoint]\nevery = 5000\nminutes = 7.5\nkeep = 3\n",
      "configs/run.toml");
  const nlohmann::json stored = nlohmann::json::parse(to_json(c).dump());
  const RunConfig back = config_from_json(stored, "configs/run.toml");
  EXPECT_EQ(to_json(back), to_json(c));
  EXPECT_EQ(back.sample_file, "tissue.txt");
  EXPECT_EQ(back.config_file, "configs/run.toml") << "relative sample paths resolve against it";
  EXPECT_EQ(back.dt, 1.5e-8);
  EXPECT_EQ(back.checkpoint_keep, 3);
  EXPECT_EQ(back.checkpoint_minutes, 7.5);
  // An automatic dt and the sample's own density (null) come back as such.
  const RunConfig defaults = parse_config("[sample]\npreset = \"tissue-small\"\n", "d.toml");
  const RunConfig defaults_back = config_from_json(to_json(defaults), "d.toml");
  EXPECT_FALSE(defaults_back.dt.has_value());
  EXPECT_FALSE(defaults_back.density.has_value());
  EXPECT_EQ(defaults_back.checkpoint_every, 0) << "by wall time only unless asked";
}

TEST(Checkpoint, CheckpointKeysAreChecked) {
  const auto message = [](const std::string& text) {
    try {
      parse_config("[sample]\npreset = \"tissue-small\"\n[checkpoint]\n" + text + "\n", "c.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_THAT(
      message("keep = 0"),
      HasSubstr("c.toml: checkpoint.keep: 0 is outside the plausible range [1, 100]; the default is 2"));
  EXPECT_THAT(message("every = -1"),
              HasSubstr("c.toml: checkpoint.every: -1 is outside the plausible range [0, 1e+15] steps"));
  EXPECT_THAT(message("minutes = -2"),
              HasSubstr("c.toml: checkpoint.minutes: -2 is outside the plausible range [0, 1e+06] min"));
  EXPECT_THAT(message("often = 3"), HasSubstr("c.toml: checkpoint.often: unknown key"));
  EXPECT_EQ(message("every = 100\nminutes = 0"), "(accepted)");
}

}  // namespace
}  // namespace rupture::loading
