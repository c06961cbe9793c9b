// fuzz/fuzz_support: what every reader fuzzer asserts. A reader given arbitrary bytes either
// returns a value or throws InputError whose message is one line that starts with the place it
// names (the file given as the source, or the option); anything else (another exception, a crash,
// a sanitizer report, a hang) is a defect that libFuzzer records. Not part of the tool.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace rupture::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

[[noreturn]] inline void defect(std::string_view what, std::string_view message) {
  std::fprintf(stderr, "reader defect: %.*s: [", static_cast<int>(what.size()), what.data());
  std::fwrite(message.data(), 1, message.size(), stderr);
  std::fputs("]\n", stderr);
  std::abort();
}

// One line, and no control character that a terminal would act on (InputError escapes them).
inline void expect_one_line(std::string_view message) {
  for (const char c : message)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f)
      defect("message is not one printable line", message);
}

// The part of `place` before its first control character: how a message shows a name that holds one.
inline std::string_view printable_prefix(std::string_view place) {
  std::size_t n = 0;
  while (n < place.size() && static_cast<unsigned char>(place[n]) >= 0x20 && place[n] != 0x7f) ++n;
  return place.substr(0, n);
}

// Runs `read` (which parses and may throw); a rejection must name `place` first, on one line.
template <class Read>
void expect_value_or_clean_rejection(std::string_view place, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    const std::string_view message = e.what();
    expect_one_line(message);
    if (!message.starts_with(place)) defect("message does not start with the place it names", message);
  }
}

// Seed inputs that each fuzzer makes from the writers of its own format (so that they follow the
// format as it changes): with RUPTURE_FUZZ_SEEDS=DIR in the environment, the fuzzer writes them
// into DIR and exits instead of fuzzing (scripts/fuzz does this before the timed run).
using Seeds = std::vector<std::pair<std::string, std::string>>;  // file name, bytes
template <class MakeSeeds>
void write_seeds_if_asked(MakeSeeds&& make_seeds) {
  const char* dir = std::getenv("RUPTURE_FUZZ_SEEDS");
  if (dir == nullptr) return;
  for (const auto& [name, bytes] : make_seeds()) {
    std::ofstream out(std::string(dir) + "/" + name, std::ios::binary);
    out << bytes;
    if (!out) {
      std::fprintf(stderr, "cannot write seed %s into %s\n", name.c_str(), dir);
      std::exit(1);
    }
  }
  std::exit(0);
}

}  // namespace rupture::fuzz
