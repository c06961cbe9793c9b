#include "core/error.hpp"

#include <fmt/format.h>

namespace rupture {

namespace {
// Messages quote the user's input, which may hold any byte: control characters (a newline in a
// quoted TOML key, a NUL in a binary file) are written as \xNN so that the message stays one line
// and what() is not cut short.
std::string one_line(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\t') || byte == 0x7f)
      out += fmt::format("\\x{:02x}", byte);
    else
      out += c;
  }
  return out;
}

// A safety net behind excerpt(): the problem never runs past a few lines' worth, whatever a
// caller quoted. The place stays whole (a message must start with the place it names, and a path
// is the user's own), and so does the fix, which may list every valid key.
std::string compose(const std::string& where, const std::string& problem, const std::string& fix) {
  std::string message = where.empty() ? excerpt(problem, 1000) : where + ": " + excerpt(problem, 1000);
  if (!fix.empty()) message += "; " + fix;
  return one_line(message);
}
}  // namespace

std::string excerpt(std::string_view text, std::size_t max) {
  return text.size() <= max ? std::string(text) : std::string(text.substr(0, max - 3)) + "...";
}

InputError::InputError(const std::string& where, const std::string& problem, const std::string& fix)
    : std::runtime_error(compose(where, problem, fix)) {}

}  // namespace rupture
