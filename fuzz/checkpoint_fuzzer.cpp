// Fuzzes the checkpoint reader and the engine's restore of what it read. The input is the
// payload: the fuzzer frames it as a file (magic, version, size, payload, FNV-1a 64 checksum, as
// docs/formats.md gives them) so that mutations reach the fields behind the checksum instead of
// stopping at it; the frame's own checks are bad-input cases in tests/reliability. Whatever
// parses is restored into an engine built from the block the seed came from: restore_state must
// refuse any state whose sizes or indices do not fit that sample. (Values that fit, e.g. far-off
// positions, are the engine's to survive or report as unstable; they are not fuzzed here.)
#include <cstring>

#include "dem/system.hpp"
#include "fuzz_support.hpp"
#include "loading/checkpoint.hpp"
#include "loading/ramp.hpp"
#include "sample/lattice.hpp"

namespace {

using namespace rupture;

constexpr std::size_t header_size = 8 + 4 + 8, checksum_size = 8;

const Sample& block() {
  static const Sample sample = make_cubic_block(2, 4, 1, 0.5);
  return sample;
}

dem::Params params() {
  dem::Params p;
  p.bond_stiffness = 1e3;     // N/mm
  p.break_distance = 2e-3;    // mm
  p.contact_stiffness = 1e3;  // N/mm
  p.glue_stiffness = 1e4;     // N/mm
  return p;
}

std::string frame(std::string_view payload) {
  std::string file = "RUPTCKPT";
  const auto append = [&](const auto& value) {
    file.append(reinterpret_cast<const char*>(&value), sizeof value);
  };
  append(loading::checkpoint_format_version);
  append(std::uint64_t(payload.size()));
  file += payload;
  std::uint64_t hash = 0xcbf29ce484222325ULL;  // FNV-1a 64 of everything before the checksum
  for (const char c : file) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  append(hash);
  return file;
}

}  // namespace

// Seed: the payload of a checkpoint of the block after a few steps (bonds stretched, lists built).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::write_seeds_if_asked([] {
    dem::System system(block(), params());
    const double dt = 0.4 * system.critical_dt();     // s
    const loading::SpeedRamp ramp{2000.0, 100 * dt};  // mm/s, reached after a ramp of s
    for (int s = 1; s <= 20; ++s) system.step(dt, ramp.at(s * dt));
    loading::Checkpoint c;
    c.version = "fuzz";
    c.command = "rupture run block.toml";
    c.config_json = R"({"bonds": {"stiffness": 1000.0}})";
    c.loop.separation_rule = "connectivity";
    c.loop.snapshots = {{0.0, "snapshots/step_0000000000.vtp"}};
    c.engine = system.save_state();
    const std::string file = loading::encode_checkpoint(c);
    return fuzz::Seeds{
        {"block.payload", file.substr(header_size, file.size() - header_size - checksum_size)}};
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::expect_value_or_clean_rejection("fuzz.ckpt", [&] {
    const loading::Checkpoint checkpoint =
        loading::parse_checkpoint(frame(fuzz::as_text(data, size)), "fuzz.ckpt");
    dem::System system(block(), params());
    system.restore_state(checkpoint.engine, "fuzz.ckpt");
  });
  return 0;
}
