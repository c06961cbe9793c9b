// Bad input, reader by reader: each malformed file below, given to the `rupture` command that reads
// it, stops the command with exit code 2 and one line naming the file, the line or field, the
// problem and the fix, and leaves nothing behind (no output file, no temporary file). The table
// doubles as the list in docs/reliability.md; cases found by the fuzzers (fuzz/) are added here.
// (A scan's base config is never reached: each scan case is refused before it is read.)
// Checkpoints have no command of their own yet: their reader is checked directly (InputError is
// what the CLI turns into exit code 2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "dem/system.hpp"
#include "loading/checkpoint.hpp"
#include "sample/lattice.hpp"
#include "support/tool.hpp"

namespace rupture {
namespace {

namespace fs = std::filesystem;
using rupture::testing::run_rupture;
using rupture::testing::TempDir;
using ::testing::StartsWith;

struct BadInput {
  const char* name;      // test name
  const char* file;      // the bad file, written into a fresh folder
  std::string content;   // its bytes
  const char* args;      // `rupture` arguments; {in} is the file, {dir} the folder
  std::string expected;  // the message after "rupture: error: ", paths relative to the folder
                         // (the whole message, or its start where the rest is a long list)
};

// Good files, minimal: two particles, one bond. Each case changes one thing.
const std::string own_sample =
    "rupture-sample 1\n"
    "box 0 0 0 2 2 1\n"
    "density 0.00025\n"
    "particles 2\n"
    "0 0.5 0.5 0.5 0.5 bottom\n"
    "1 0.5 1.5 0.5 0.5 top\n"
    "bonds 1\n"
    "0 1 1\n"
    "end\n";
const std::string lammps_header =
    "LAMMPS data file from another code\n\n"
    "2 atoms\n1 bonds\n3 atom types\n1 bond types\n\n"
    "0 2 xlo xhi\n0 2 ylo yhi\n0 1 zlo zhi\n\n";
const std::string lammps_atoms =
    "Atoms # hybrid sphere bond\n\n"
    "1 2 0.5 0.5 0.5 1 0.00025 1\n"
    "2 3 0.5 1.5 0.5 1 0.00025 1\n\n";
const std::string lammps_bonds = "Bonds\n\n1 1 1 2\n";
const std::string lsm_header =
    "LSMGeometry 1.2\nBoundingBox 0 0 0 2 2 1\nPeriodicBoundaries 0 0 0\nDimension 3D\n";
const std::string lsm_particles =
    "BeginParticles\nSimple\n2\n0.5 0.5 0.5 0.5 0 1\n0.5 1.5 0.5 0.5 1 2\nEndParticles\n";
const std::string lsm_connect = "BeginConnect\n1\n0 1 0\nEndConnect\n";
const std::string scan_grid =
    "[grid]\nk_n = { from = 1e3, to = 1e4, count = 2 }\nb_d = { from = 1e-3, to = 1e-2, count = 2 }\n";
const std::string scan_config = "[scan]\nbase = \"base.toml\"\n" + scan_grid;
const std::string block_config =
    "[sample]\nlattice = \"block\"\nlattice_cells = [2, 3, 1]\nlattice_radius = 0.5\n";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos)
    ADD_FAILURE() << "fixture lacks '" << from << "'";
  else
    text.replace(at, from.size(), to);
  return text;
}

const char* const run = "run {in} -o {dir}/out";
// The example block's run with the sample from the bad file instead of its lattice.
const char* const run_sample =
    "run " RUPTURE_EXAMPLES_DIR "block.toml --set 'sample.lattice=\"\"' --set sample.file={in} -o {dir}/out";
const char* const convert_own = "sample convert {in} {dir}/out.data";
const char* const convert_foreign = "sample convert {in} {dir}/out.sample";
const char* const analyze = "analyze {in} -o {dir}/analysis.json";
const char* const fbm_curves = "fbm curves --dist file:{in} --out {dir}/curve.csv";
const char* const scan = "scan {in} -o {dir}/scan";

std::vector<BadInput> bad_inputs() {
  return {
      // --- run config (TOML) ---
      {"config_toml_syntax", "bad.toml", "[bonds\nstiffness = 1e3\n", run,
       "bad.toml:1: Error while parsing table header: expected ']', saw '\\n'; fix the TOML syntax"},
      {"config_unknown_key", "bad.toml", block_config + "[bonds]\nstifness = 1e3\n", run,
       "bad.toml: bonds.stifness: unknown key; valid keys: sample.file, "},
      {"config_wrong_type", "bad.toml", block_config + "[bonds]\nstiffness = \"soft\"\n", run,
       "bad.toml: bonds.stiffness: expects a number; write e.g. 1e3 (no quotes)"},
      {"config_out_of_range", "bad.toml", block_config + "[bonds]\nbreak_distance = -1\n", run,
       "bad.toml: bonds.break_distance: -1 is outside the plausible range [1e-09, 1000] mm; the default is "
       "0.05 "
       "(values in mm)"},
      {"config_lattice_cells", "bad.toml", replaced(block_config, "[2, 3, 1]", "[2, 3]"), run,
       "bad.toml: sample.lattice_cells: expects three whole numbers; write e.g. [4, 10, 2]"},
      {"config_missing_sample_file", "bad.toml", "[sample]\nfile = \"nowhere.sample\"\n", run,
       "bad.toml: sample.file: no such file: nowhere.sample; give a path relative to the config's folder, or "
       "an "
       "absolute one"},
      // Every number finite and plausible: inf, 1e308 and values in the wrong unit stop before the run.
      {"config_infinite_stiffness", "bad.toml", block_config + "[bonds]\nstiffness = inf\n", run,
       "bad.toml: bonds.stiffness: inf is not a finite number in the plausible range [1e-06, 1e+12] N/mm; "
       "the "
       "default is 1000 (values in N/mm)"},
      {"config_huge_speed", "bad.toml", block_config + "[loading]\nspeed = 1e308\n", run,
       "bad.toml: loading.speed: 1e+308 is outside the plausible range [1e-09, 1e+09] mm/s; the default is "
       "50 "
       "(values in mm/s)"},
      {"config_infinite_lattice_radius", "bad.toml",
       replaced(block_config, "lattice_radius = 0.5", "lattice_radius = inf"), run,
       "bad.toml: sample.lattice_radius: inf is not a finite number in the plausible range [1e-06, 1000] mm"},
      {"config_density_in_tonnes", "bad.toml", block_config + "density = 2.5e-10\n", run,
       "bad.toml: sample.density: 2.5e-10 is outside the plausible range [1e-07, 0.05] g/mm^3; the default "
       "is "
       "0.00025 (values in g/mm^3)"},
      {"config_tiny_dt", "bad.toml", block_config + "[time]\ndt = 1e-308\n", run,
       "bad.toml: time.dt: 1e-308 is outside the plausible range [1e-18, 1] s"},
      // A NUL byte used to end the TOML text silently: the keys after it were lost.
      {"config_nul_byte", "bad.toml",
       block_config + std::string("[bonds]\nstiffness = 1e3\0\nbreak_distance = 1\n", 44), run,
       "bad.toml:6: holds a NUL byte (byte 98): this is not a text file, or it is damaged"},
      // Sizes checked before anything is allocated: endless devices, binary files, huge requests.
      {"config_endless_device", "unused.toml", block_config, "run /dev/zero -o {dir}/out",
       "/dev/zero:1: holds a NUL byte (byte 1): this is not a text file, or it is damaged"},
      {"config_billion_particle_lattice", "bad.toml",
       replaced(block_config, "[2, 3, 1]", "[1000, 1000, 1000]"), run,
       "bad.toml: sample.lattice_cells: 1e+09 particles would need about 500 GB to run; use at most 5e+07 "
       "particles"},
      {"generate_huge_box", "unused.txt", "",
       "sample generate --seed 1 --width 1e4 --height 1e4 --depth 1e4 --out {dir}/s.sample",
       "--width/--height/--depth: a 1e+12 mm^3 box of particles of median radius 0.5 mm holds about 1.15e+12 "
       "particles (a run of them needs about 5.73e+05 GB); at most 5e+07 are generated"},
      {"run_into_root", "good.toml", block_config, "run {in} -o /",
       "/: is the root folder; a run writes a dozen files into its folder; give a folder of its own, e.g. -o "
       "run"},
      {"unknown_subcommand", "unused.txt", "", "simulate {in}",
       "unknown subcommand 'simulate' of rupture; the subcommands are study, fbm, sample, run, check, bench, "
       "analyze, monitor, plot, scan, report (see rupture --help)"},
      {"unknown_nested_subcommand", "unused.txt", "", "fbm theroy --dist uniform",
       "unknown subcommand 'theroy' of rupture fbm; the subcommands are theory, curves, simulate (see "
       "rupture fbm "
       "--help)"},
      {"config_override_without_value", "good.toml", block_config,
       "run {in} -o {dir}/out --set bonds.stiffness",
       "--set bonds.stiffness: expects key=value; write e.g. --set bonds.stiffness=1e4"},
      // --- rupture's own sample format ---
      {"own_sample_version", "bad.sample", replaced(own_sample, "rupture-sample 1", "rupture-sample 2"),
       convert_own,
       "bad.sample:1: format version 2 is not supported (this rupture reads version 1); convert the file "
       "with the "
       "rupture version that wrote it"},
      {"own_sample_truncated", "bad.sample", own_sample.substr(0, own_sample.find("1 0.5 1.5")), convert_own,
       "bad.sample:5: file ends where particle 2 of 2 was expected: it is truncated; write or copy the file "
       "again"},
      {"own_sample_not_a_number", "bad.sample", replaced(own_sample, "0 0.5 0.5 0.5", "0 0.5 abc 0.5"),
       convert_own,
       "bad.sample:5: y 'abc' is not a finite number; write a decimal number such as 0.25 or 1e-3"},
      {"own_sample_nul_byte", "bad.sample", replaced(own_sample, "2 2 1", std::string("2 2 1\0", 6)),
       convert_own, "bad.sample:2: holds a NUL byte (byte 33): this is not a text file, or it is damaged"},
      {"own_sample_negative_radius", "bad.sample", replaced(own_sample, "1.5 0.5 0.5", "1.5 0.5 -0.5"),
       convert_own, "bad.sample:6: radius -0.5 mm is not positive; every particle needs a radius > 0"},
      {"own_sample_unknown_group", "bad.sample", replaced(own_sample, "top", "middle"), convert_own,
       "bad.sample:6: unknown group 'middle'; use free, bottom or top"},
      {"own_sample_bond_to_unknown_id", "bad.sample", replaced(own_sample, "0 1 1\n", "0 7 1\n"), convert_own,
       "bad.sample:8: bond 0-7 names particle id 7, which the file does not define; bond only particles that "
       "the "
       "file lists"},
      {"own_sample_bond_to_itself", "bad.sample", replaced(own_sample, "0 1 1\n", "1 1 1\n"), convert_own,
       "bad.sample:8: bond 1-1 joins a particle to itself; a bond joins two particles"},
      // --- any sample a run is given: plausible numbers, distinct particles, glued layers in order ---
      {"sample_coincident_particles", "bad.sample", replaced(own_sample, "1 0.5 1.5 0.5", "1 0.5 0.5 0.5"),
       run_sample,
       "bad.sample: particles id 0 and id 1 are 0 mm apart, with radii 0.5 and 0.5 mm (a duplicate, or an "
       "export that lost precision); remove the duplicate"},
      {"sample_top_below_bottom", "bad.sample",
       replaced(replaced(own_sample, "0.5 bottom", "0.5 top"), "0.5 top\nbonds", "0.5 bottom\nbonds"),
       run_sample,
       "bad.sample: the top glued layer reaches down to y = 0.5 mm, not above the bottom layer's highest y = "
       "1.5 mm; loading pulls along +y"},
      {"sample_huge_radius", "bad.sample", replaced(own_sample, "1.5 0.5 0.5 top", "1.5 0.5 1e300 top"),
       run_sample, "bad.sample: particle id 1 has radius 1e+300 mm, outside [1e-06, 1000] mm"},
      {"sample_density_in_tonnes", "bad.sample", replaced(own_sample, "density 0.00025", "density 2.5e-10"),
       run_sample,
       "bad.sample: density 2.5e-10 g/mm^3 is outside the plausible [1e-07, 0.05] g/mm^3 (a value in t/mm^3? "
       "multiply by 1e6)"},
      {"lammps_density_in_tonnes", "bad.data",
       lammps_header +
           replaced(replaced(lammps_atoms, "0.5 1 0.00025 1", "0.5 1 2.5e-10 1"), "0.5 1 0.00025 1",
                    "0.5 1 2.5e-10 1") +
           lammps_bonds,
       run_sample,
       "bad.data: density 2.5e-10 g/mm^3 is outside the plausible [1e-07, 0.05] g/mm^3 (a value in t/mm^3? "
       "multiply by 1e6)"},
      // --- LAMMPS data files ---
      {"lammps_atom_style_without_radius", "bad.data",
       lammps_header + replaced(lammps_atoms, "hybrid sphere bond", "full") + lammps_bonds, convert_foreign,
       "bad.data:12: atom style 'full' has no particle radius; supported: 'hybrid sphere bond', 'hybrid bond "
       "sphere', 'bpm/sphere', 'sphere'"},
      {"lammps_atom_count", "bad.data",
       replaced(lammps_header, "2 atoms", "3 atoms") + lammps_atoms + lammps_bonds, convert_foreign,
       "bad.data:19: the file has 2 atom lines but its header says 3 atoms; the file is truncated or its "
       "header is "
       "wrong"},
      {"lammps_atom_id_zero", "bad.data",
       lammps_header + replaced(lammps_atoms, "1 2 0.5", "0 2 0.5") + lammps_bonds, convert_foreign,
       "bad.data:14: atom-ID 0 is not positive; LAMMPS atom-IDs start at 1"},
      {"lammps_bond_to_unknown_atom", "bad.data",
       lammps_header + lammps_atoms + replaced(lammps_bonds, "1 2", "1 9"), convert_foreign,
       "bad.data:19: bond 1-9 names particle id 9, which the file does not define; bond only particles that "
       "the "
       "file lists"},
      // --- ESyS-Particle / GenGeo LSMGeometry ---
      {"lsm_version", "bad.geo", replaced(lsm_header, "1.2", "9.9") + lsm_particles + lsm_connect,
       convert_foreign, "bad.geo:1: LSMGeometry version 9.9 is not supported; write the file as version 1.2"},
      {"lsm_two_dimensional", "bad.geo", replaced(lsm_header, "3D", "2D") + lsm_particles + lsm_connect,
       convert_foreign, "bad.geo:4: only 3D geometries can be samples; generate a 3D geometry"},
      {"lsm_truncated", "bad.geo", lsm_header + lsm_particles.substr(0, lsm_particles.find("0.5 1.5")),
       convert_foreign,
       "bad.geo:8: file ends where particle 2 of 2 was expected: it is truncated; write or copy the file "
       "again"},
      {"lsm_connection_to_unknown_id", "bad.geo",
       lsm_header + lsm_particles + replaced(lsm_connect, "0 1 0", "0 5 0"), convert_foreign,
       "bad.geo:13: bond 0-5 names particle id 5, which the file does not define; bond only particles that "
       "the "
       "file lists"},
      // --- CSV loading curves ---
      {"csv_empty", "bad.csv", "", analyze,
       "bad.csv: no header line; the first non-comment line must name the columns"},
      {"csv_missing_column", "bad.csv", "strain,energy\n0,0\n1,1\n", analyze,
       "bad.csv: no column 'force'; name the column with --force (the header has: strain, energy)"},
      {"csv_not_a_number", "bad.csv", "strain,force,elastic_energy\n0,0,0\n1,abc,0.5\n", analyze,
       "bad.csv:3: column 2 ('force'): 'abc' is not a number; use plain decimal numbers such as 1.5e-3"},
      {"csv_nul_bytes", "bad.csv", std::string(100000, '\0'), analyze,
       "bad.csv:1: holds a NUL byte (byte 1): this is not a text file, or it is damaged"},
      // A 1 MB token is quoted by its first 77 bytes.
      {"csv_huge_token", "bad.csv",
       "strain,force,elastic_energy\n0,0,0\n" + std::string(1000000, 'x') + ",1,1\n", analyze,
       "bad.csv:3: column 1 ('strain'): '" + std::string(77, 'x') +
           "...' is not a number; use plain decimal"},
      // The monitor reads line by line: the NUL is still placed by line and byte of the whole file.
      {"monitor_nul_byte", "bad.csv", std::string("strain,force,elastic_energy\n0,0,0\n1,\0,1\n", 40),
       "monitor {in}", "bad.csv:3: holds a NUL byte (byte 37): this is not a text file, or it is damaged"},
      {"csv_ragged_row", "bad.csv", "strain,force,elastic_energy\n0,0,0\n1,1\n", analyze,
       "bad.csv:3: 2 fields where the header has 3; every row needs one value per header column"},
      // --- thresholds files (fbm --dist file:PATH) ---
      {"thresholds_not_a_number", "bad.txt", "0.1\nabc\n", fbm_curves,
       "bad.txt:2: 'abc' is not a number; write one threshold (a breaking strain) per line; '#' starts a "
       "comment"},
      {"thresholds_negative", "bad.txt", "0.1\n-0.5\n", fbm_curves,
       "bad.txt:2: threshold -0.5 is negative; thresholds are breaking strains, >= 0"},
      {"thresholds_none", "bad.txt", "# nothing yet\n\n", fbm_curves,
       "bad.txt: no thresholds in the file; write one threshold (a breaking strain) per line"},
      // --- scan configs (TOML) ---
      {"scan_toml_syntax", "bad.toml", "[scan]\nbase = \"base.toml\"\n[grid\n", scan,
       "bad.toml:3: Error while parsing table header: expected ']', saw '\\n'; fix the TOML syntax"},
      {"scan_unknown_key", "bad.toml", "[scan]\nbase = \"base.toml\"\nbogus = 1\n" + scan_grid, scan,
       "bad.toml: scan.bogus: unknown key; valid keys: scan.base, scan.output, scan.set"},
      {"scan_negative_range", "bad.toml", replaced(scan_config, "from = 1e3", "from = -1e3"), scan,
       "bad.toml: grid.k_n.from: -1000 is outside the plausible range [1e-06, 1e+12] N/mm; give a value "
       "inside "
       "it (the key has no default)"},
      {"scan_unknown_ramp_rule", "bad.toml", scan_config + "[rules]\nramp = \"sideways\"\n", scan,
       "bad.toml: rules.ramp: \"sideways\" is not a valid choice; use one of \"scaled\", \"strain\", "
       "\"base\""},
      // A NUL byte used to end the scan config silently: the points after it were lost.
      {"scan_nul_byte", "bad.toml", std::string("[scan]\nbase = \"base.toml\"\n\0", 27) + scan_grid, scan,
       "bad.toml:3: holds a NUL byte (byte 27): this is not a text file, or it is damaged"},
      {"scan_no_points", "bad.toml", "[scan]\nbase = \"base.toml\"\n", scan,
       "bad.toml: no points; add a [grid] with k_n and b_d ranges, or [[points]] entries"},
      // Found by the scan-config fuzzer: a dotted key in [sample] made a table the message did not name.
      {"scan_sample_table_value", "bad.toml", scan_config + "[sample]\nx.y = 3\n", scan,
       "bad.toml: sample.x: a value that is not a string, number, boolean or array; write it as in a run "
       "config"},
      // [scan] set entries become run-config overrides: the message names the scan file, not a --set.
      {"scan_set_without_value", "bad.toml",
       "[scan]\nbase = \"" RUPTURE_EXAMPLES_DIR "block.toml\"\nset = [\"bonds.stiffness\"]\n" + scan_grid,
       scan, "bad.toml ([sample] or [scan] set): bonds.stiffness: expects key=value"},
  };
}

std::string with_paths(std::string args, const std::string& in, const std::string& dir) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{in}", in}, {"{dir}", dir}})
    for (auto at = args.find(key); at != std::string::npos; at = args.find(key, at + value.size()))
      args.replace(at, key.size(), value);
  return args;
}

std::vector<std::string> folder_listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    names.push_back(fs::relative(entry.path(), dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

// CTest lists a case by its name, not by its bytes.
void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, ExitsWithCodeTwoAndOneLineNamingPlaceAndFix) {
  const BadInput& c = GetParam();
  TempDir dir;
  {
    std::ofstream out(dir / c.file, std::ios::binary);
    out << c.content;
  }
  const auto result =
      run_rupture(with_paths(c.args, "'" + (dir / c.file).string() + "'", "'" + dir.path().string() + "'"));
  EXPECT_EQ(result.exit_code, exit_bad_input) << result.err;
  EXPECT_EQ(result.out, "");
  // One line; paths shown relative to the folder so that the expectation is fixed.
  std::string err = result.err;
  for (auto at = err.find(dir.path().string() + "/"); at != std::string::npos;
       at = err.find(dir.path().string() + "/"))
    err.erase(at, dir.path().string().size() + 1);
  ASSERT_FALSE(err.empty());
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  EXPECT_THAT(err, StartsWith(std::string("rupture: error: ") + c.expected));
  // Nothing written: the folder holds the bad file alone.
  EXPECT_EQ(folder_listing(dir.path()), std::vector<std::string>{c.file});
}

INSTANTIATE_TEST_SUITE_P(Readers, BadInputTest, ::testing::ValuesIn(bad_inputs()),
                         [](const ::testing::TestParamInfo<BadInput>& tested) { return tested.param.name; });

// --- checkpoints: the frame around the payload (the fuzzer reaches what lies behind it) ---

std::string good_checkpoint() {
  const Sample block = make_cubic_block(2, 3, 1, 0.5);
  dem::Params params;
  params.bond_stiffness = 1e3;     // N/mm
  params.break_distance = 2e-3;    // mm
  params.contact_stiffness = 1e3;  // N/mm
  params.glue_stiffness = 1e4;     // N/mm
  const dem::System system(block, params);
  loading::Checkpoint c;
  c.version = "test";
  c.engine = system.save_state();
  return loading::encode_checkpoint(c);
}

struct BadCheckpoint {
  const char* name;
  std::string bytes;
  const char* expected;
};

TEST(BadCheckpoint, EachDamageIsNamedWithTheFieldAndTheFix) {
  const std::string good = good_checkpoint();
  ASSERT_NO_THROW((void)loading::parse_checkpoint(good, "step.ckpt"));
  std::string flipped = good, foreign = good, future = good;
  flipped[good.size() / 2] ^= 0x01;
  foreign[0] = 'X';
  future[8] = char(loading::checkpoint_format_version + 1);  // the u32 version follows the 8-byte magic
  const std::vector<BadCheckpoint> cases = {
      {"empty", "", "step.ckpt: header: 0 bytes is too short for a checkpoint (truncated?); "},
      {"not a checkpoint", foreign, "step.ckpt: magic: not a rupture checkpoint; "},
      {"newer format", future,
       "step.ckpt: version: format version 4 is not one this rupture reads (1 to 3); "},
      {"truncated", good.substr(0, good.size() - 100), "step.ckpt: payload_size: says "},
      {"one bit flipped", flipped, "step.ckpt: checksum: is "},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    try {
      (void)loading::parse_checkpoint(c.bytes, "step.ckpt");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_THAT(message, StartsWith(c.expected));
      EXPECT_THAT(message, ::testing::EndsWith("; resume from an older checkpoint, or start the run again"));
    }
  }
}

}  // namespace
}  // namespace rupture
