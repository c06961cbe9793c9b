// loading/config: the run configuration (`rupture run CONFIG.toml`): every key with its unit and
// default, TOML parsing with `--set key=value` overrides, range checks and the resolved form as
// JSON. Not: running anything (loading/run) or loading samples (sample/formats).
#pragma once

#include <toml++/toml.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dem/system.hpp"
#include "loading/schema.hpp"

namespace rupture::loading {

struct RunConfig {
  // [sample]: exactly one of file, preset, lattice.
  std::string sample_file;                              // path, relative to the config file's folder
  std::string sample_preset;                            // generator preset ("tissue", "tissue-small")
  std::string sample_lattice;                           // "chain" or "block" (analytic test samples)
  std::array<std::int64_t, 3> lattice_cells{1, 10, 1};  // 1: particles along x, y, z
  double lattice_radius = 0.5;                          // mm
  std::uint64_t seed = 1;                               // 1: generator seed (preset)
  std::optional<double> density;                        // g/mm^3; default: the sample's own
  // [bonds]
  // The model's defaults are dem::Params' (one place for each); the factors below are config-only.
  double bond_stiffness = dem::Params{}.bond_stiffness;  // N/mm (N/mm^2 with scale_stiffness)
  double break_distance = dem::Params{}.break_distance;  // mm (absolute) or 1 (relative)
  std::string break_rule = "absolute";                   // "absolute" | "relative"
  bool scale_stiffness = false;                          // ESyS: k = normalK * r0 / 4
  // [contacts]
  double contact_stiffness_factor = 1.0;  // 1: contact stiffness / k_n
  double skin = dem::Params{}.skin;       // mm: Verlet-list skin to start from
  // [glue]
  std::string glue_mode = "spring";     // "spring" | "rigid"
  double glue_stiffness_factor = 10.0;  // 1: glue stiffness / k_n
  // [loading]
  double speed = 50.0;                     // mm/s
  std::int64_t ramp_steps = 10000;         // steps of the smooth speed ramp
  double damping = dem::Params{}.damping;  // 1/s
  // [time]
  std::optional<double> dt;        // s; empty: automatic
  double dt_safety = 0.4;          // 1: dt = safety * critical dt
  bool allow_unstable_dt = false;  // accept a dt above the stability limit
  // [stop]
  bool stop_at_separation = true;                 // false: run to max_strain / max_steps whatever happens
  double extra_strain = 0.5;                      // %: keep pulling this much after separation
  double max_strain = 100.0;                      // %
  std::int64_t max_steps = 100'000'000;           // steps
  std::int64_t separation_check_interval = 1000;  // steps
  // The load-free rule: also separated once the mean plate force has stayed below this fraction
  // of its peak over `load_free_strain` of pulling (0 turns the rule off; see loading/separation).
  double load_free_fraction = 0.1;  // 1
  double load_free_strain = 0.2;    // %
  // [monitor] the live precursor warning, fed every curves.csv row (analysis/monitor)
  bool monitor = true;
  std::int64_t monitor_window = 41;   // rows per causal cubic fit
  double monitor_drop = 0.03;         // 1: fall of ℰ below its running maximum
  std::int64_t monitor_confirm = 10;  // rows below that level that confirm the maximum
  // [output]
  std::string output_folder = "run";    // relative to the working directory
  std::int64_t output_interval = 1000;  // steps between curve rows
  std::int64_t snapshot_interval = 0;   // steps between snapshots (0: none)
  // [checkpoint] restart files for `rupture run --resume` (loading/checkpoint); a checkpoint is
  // due when either interval has passed, and one is always written on SIGINT/SIGTERM.
  std::int64_t checkpoint_every = 0;  // steps between checkpoints (0: by wall time only)
  double checkpoint_minutes = 30.0;   // wall-clock minutes between checkpoints (0: by steps only)
  std::int64_t checkpoint_keep = 2;   // newest checkpoints kept; older ones are removed
  // [run]
  std::int64_t threads = 2;

  std::filesystem::path config_file;  // where it was read from (for messages)

  dem::Params dem_params(double sample_density) const;
};

// A TOML document; InputError naming `source` and the line for a NUL byte or a syntax error. The
// one TOML reader of run and scan configs.
toml::table parse_toml(std::string_view text, const std::string& source);

// Reads a TOML file and applies overrides "section.key=value" (a TOML value; a bare word is read as
// a string). Unknown keys and out-of-range values throw InputError naming the file and key.
RunConfig load_config(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
RunConfig parse_config(const std::string& toml_text, const std::string& source,
                       const std::vector<std::string>& overrides = {});

// The resolved form back (to_json's output, as a checkpoint stores it), checked as a TOML file is.
// `config_file` is where the original was read from: relative sample paths resolve against it.
RunConfig config_from_json(const nlohmann::json& resolved, const std::filesystem::path& config_file);

// `base` with some keys set to typed values ({"section": {"key": value}}, to_json's form; a null
// leaves the key as it is), each read and range-checked by the schema as a file's key would be, and
// the relations between keys checked again. `source` names the values in errors.
RunConfig with_values(RunConfig base, const nlohmann::json& values, const std::string& source);

// Every key with unit, default and meaning, as a commented TOML document (for --help-config).
std::string config_reference();

// The unit of a key given as "section.name" ("1" for a pure number, "" for text and flags or an
// unknown key), as the schema states it: for tables that print a resolved config.
std::string config_key_unit(const std::string& path);

// The units of k_n and b_d as `config` uses them: N/mm, or ESyS's normalK in N/mm^2 with
// bonds.scale_stiffness; mm, or 1 (a strain) with the relative break rule.
std::string bond_stiffness_unit(const RunConfig& config);
std::string break_distance_unit(const RunConfig& config);

// The plausible range of a number key given as "section.name", as the schema states it: for other
// configs that set the same quantity (a scan's k_n and b_d).
std::optional<schema::Range> config_key_range(const std::string& path);

// The resolved configuration (every key, defaults filled in) as JSON, by section.
nlohmann::json to_json(const RunConfig& config);

}  // namespace rupture::loading
