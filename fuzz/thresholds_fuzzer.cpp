// Fuzzes the `--dist` spec and the thresholds file behind `file:`: the first line of the input is
// the spec, the rest is the content of whatever file it names.
#include <optional>

#include "fbm/distribution.hpp"
#include "fuzz_support.hpp"

// Seeds: each spec form, and a thresholds file with comments.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rupture::fuzz::write_seeds_if_asked([] {
    return rupture::fuzz::Seeds{
        {"uniform", "uniform:a=0.2,b=1\n"},
        {"powerlaw", "powerlaw:alpha=2\n"},
        {"weibull", "weibull:k=2,lambda=1.5\n"},
        {"file", "file:t.txt\n# breaking strains\n0.1\n0.25  # trailing\n\n1e-1\n0.7\n"}};
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace rupture;
  const std::string_view text = fuzz::as_text(data, size);
  const auto newline = text.find('\n');
  // A command-line word holds no NUL: the spec ends at the first one.
  const std::string_view first_line = text.substr(0, newline);
  const std::string_view spec = first_line.substr(0, first_line.find('\0'));
  const std::string file =
      newline == std::string_view::npos ? std::string() : std::string(text.substr(newline + 1));
  std::optional<std::string> file_read;  // the path, once the spec named a file
  try {
    (void)fbm::parse_distribution_spec(spec, [&](const std::string& path) {
      file_read = path;
      return file;
    });
  } catch (const InputError& e) {
    // A spec error names --dist; an error in the file names the file.
    const std::string_view message = e.what();
    fuzz::expect_one_line(message);
    if (!message.starts_with("--dist") &&
        !(file_read && message.starts_with(fuzz::printable_prefix(*file_read))))
      fuzz::defect("message does not start with the place it names", message);
  }
  return 0;
}
