// Fuzzes the run configuration reader (TOML with the key schema and range checks). Lines after a
// line "%%" are `--set key=value` overrides, so those are fuzzed too.
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "loading/config.hpp"

// Seeds: the reference document (every key at its default) and one with overrides; scripts/fuzz
// adds the example configs.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rupture::fuzz::write_seeds_if_asked([] {
    const std::string reference = rupture::loading::config_reference();
    return rupture::fuzz::Seeds{
        {"reference.toml", reference},
        {"overrides.toml", reference + "\n%%\nbonds.stiffness=1e4\noutput.folder=\"x\"\n"}};
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  const std::string_view text = fuzz::as_text(data, size);
  const auto split = text.find("\n%%\n");
  const std::string toml(text.substr(0, split));
  std::vector<std::string> overrides;
  if (split != std::string_view::npos) {
    std::string_view rest = text.substr(split + 4);
    while (!rest.empty()) {
      const auto newline = rest.find('\n');
      overrides.emplace_back(rest.substr(0, newline));
      rest = newline == std::string_view::npos ? std::string_view{} : rest.substr(newline + 1);
    }
  }
  // Override errors name the option (--set ...), everything else the file.
  try {
    (void)loading::parse_config(toml, "fuzz.toml", overrides);
  } catch (const InputError& e) {
    const std::string_view message = e.what();
    fuzz::expect_one_line(message);
    if (!message.starts_with("fuzz.toml") && !message.starts_with("--set "))
      fuzz::defect("message does not start with the place it names", message);
  }
  return 0;
}
