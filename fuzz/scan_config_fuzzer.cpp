// Fuzzes the scan config reader (`rupture scan SCAN.toml`). It reads from a path, so each input is
// written to a file in a private temporary folder first. A rejection names that file, or the
// `set` override it refuses ("--set ...", the form run configs share).
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "fuzz_support.hpp"
#include "scan/scan.hpp"

namespace {

std::filesystem::path input_file;  // DIR/fuzz.toml, DIR made once per process

}  // namespace

// Seed: a grid scan with every [rules] key; scripts/fuzz adds the example scan configs.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rupture::fuzz::write_seeds_if_asked([] {
    return rupture::fuzz::Seeds{
        {"grid.toml",
         "[scan]\nbase = \"block.toml\"\noutput = \"scan\"\nset = [\"run.threads=1\"]\n"
         "[sample]\nseed = 3\n"
         "[grid]\nk_n = { from = 1e2, to = 1e4, count = 3 }\nb_d = { from = 0.002, to = 0.004, count = 2 }\n"
         "[rules]\ndt = \"auto\"\nramp = \"scaled\"\nramp_steps = 500\nramp_b_d = 0.004\nramp_exponent = "
         "1.0\n"
         "ramp_min_steps = 500\nramp_max_steps = 2000\nmax_strain = \"scaled\"\nmax_strain_factor = 10\n"
         "max_strain_min = 1.0\n"},
        {"points.toml",
         "[scan]\nbase = \"block.toml\"\n[[points]]\nk_n = 1e3\nb_d = 0.002\n[[points]]\n"
         "k_n = 1e4\nb_d = 0.004\n"}};
  });
  // In memory where there is a tmpfs: a disk write per input would take most of the time.
  const std::filesystem::path base =
      std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path();
  std::string dir = (base / "rupture_scan_fuzz_XXXXXX").string();
  if (mkdtemp(dir.data()) == nullptr) {
    std::perror("mkdtemp");
    std::abort();
  }
  input_file = std::filesystem::path(dir) / "fuzz.toml";
  std::atexit([] {
    std::error_code ignored;
    std::filesystem::remove_all(input_file.parent_path(), ignored);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  {
    std::ofstream out(input_file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    (void)scan::to_json(scan::load_scan_config(input_file));
  } catch (const InputError& e) {
    const std::string_view message = e.what();
    fuzz::expect_one_line(message);
    if (!message.starts_with(input_file.string()) && !message.starts_with("--set "))
      fuzz::defect("message does not start with the place it names", message);
  }
  return 0;
}
