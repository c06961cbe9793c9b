// core/error: the one typed error for bad input, and the process exit codes.
// Owns: how a user-facing failure is described (file, place, problem, fix). Not: logging.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace rupture {

// Exit codes shared by every subcommand (documented in README.md).
enum ExitCode : int {
  exit_ok = 0,
  exit_failure = 1,    // the computation failed (instability, I/O error while running)
  exit_bad_input = 2,  // malformed command line, config, sample or data file
  exit_rejected = 4,   // analysed, but the curve failed the acceptance rules
};

// Bad input from the user: a one-line message naming where the problem is and how to fix it.
// `where` is "file:line" or "file: key" or "--option"; `fix` says what to do instead.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& where, const std::string& problem, const std::string& fix = {});
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// At most `max` bytes of the user's input, for quoting it in a message ("..." marks a cut): a 10 MB
// token in a file must not become a 10 MB error line.
std::string excerpt(std::string_view text, std::size_t max = 80);

// A failure of the computation itself (not the user's input): I/O failure, numerical blow-up.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rupture
