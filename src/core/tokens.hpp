// core/tokens: the one tokenizer of the text tables rupture reads (curve CSVs, scan results, sample
// files, threshold files, ASCII VTK arrays): blanks, trimming, splitting a line into words or comma
// fields, and numbers that must fill their whole token. It throws nothing: each reader names the
// file, line and column of a bad token itself.
#pragma once

#include <charconv>
#include <optional>
#include <string_view>
#include <vector>

namespace rupture::tokens {

// Space, tab, and line ends (the CR of a CRLF file; a newline where a token list spans lines).
constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

constexpr std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

// The words of `line` (separated by runs of blanks) into `out`, views into `line`.
inline void split_words(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && is_blank(line[k])) ++k;
    const std::size_t start = k;
    while (k < line.size() && !is_blank(line[k])) ++k;
    if (k > start) out.push_back(line.substr(start, k - start));
  }
}
inline std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  split_words(line, out);
  return out;
}

// The comma-separated fields of `line`, each trimmed (an empty field stays, as an empty view).
inline void split_commas(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return;
    start = comma + 1;
  }
}

// The number a whole token spells (a leading '+' allowed), or nullopt. Doubles may come out
// infinite or NaN ("inf", "nan"): the reader decides whether it takes them.
template <class T>
std::optional<T> number(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  T value{};
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, value);
  if (error != std::errc() || stop != end) return std::nullopt;
  return value;
}

}  // namespace rupture::tokens
