// analysis/option_words: the words and ranges of the analysis options that both doors take —
// `rupture analyze`'s command line and the Python package's `rupture.analyze` keywords — in one table,
// so the two cannot drift apart (and analysis.json writes the same words).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/analysis.hpp"

namespace rupture::analysis {

// One word of an option and the value it names.
template <class Value>
struct OptionWord {
  std::string_view word;
  Value value;
};

inline constexpr std::array<OptionWord<DelayMethod>, 2> delay_method_words{
    {{"fitted-maxima", DelayMethod::fitted_maxima}, {"shift-l1", DelayMethod::shift_l1}}};
inline constexpr std::array<OptionWord<PeakForm>, 2> peak_form_words{
    {{"smooth", PeakForm::smooth}, {"corner", PeakForm::corner}}};
inline constexpr std::array<OptionWord<RowKind>, 2> row_kind_words{
    {{"instants", RowKind::instants}, {"interval-means", RowKind::interval_means}}};

// Noise replicates of the bootstrap a caller may ask for (BootstrapOptions::replicates).
inline constexpr int min_replicates = 20, max_replicates = 100'000;
// The smoothing floor is a share of the rise to the force peak (AnalysisOptions::smoothing_floor_share).
inline constexpr double max_smoothing_floor_share = 1.0;

// The value a word names; none for a word the table does not hold.
template <class Value, std::size_t N>
constexpr std::optional<Value> from_word(const std::array<OptionWord<Value>, N>& words,
                                         std::string_view word) {
  for (const auto& w : words)
    if (w.word == word) return w.value;
  return std::nullopt;
}

// A value's word (every value of the enums above has one).
template <class Value, std::size_t N>
constexpr std::string_view word_of(const std::array<OptionWord<Value>, N>& words, Value value) {
  for (const auto& w : words)
    if (w.value == value) return w.word;
  return {};
}

// The table's words, for a command line's list of allowed values.
template <class Value, std::size_t N>
std::vector<std::string> word_list(const std::array<OptionWord<Value>, N>& words) {
  std::vector<std::string> list;
  for (const auto& w : words) list.emplace_back(w.word);
  return list;
}

// Items in prose: "a", "a and b", "a, b and c" (`last` the joint before the last item).
inline std::string listed(const std::vector<std::string>& items, std::string_view last = " and ") {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) text += i + 1 == items.size() ? std::string(last) : std::string(", ");
    text += items[i];
  }
  return text;
}

// The table's words for an error's fix: "\"smooth\" or \"corner\"".
template <class Value, std::size_t N>
std::string quoted_words(const std::array<OptionWord<Value>, N>& words) {
  std::vector<std::string> quoted;
  for (const auto& w : words) quoted.push_back("\"" + std::string(w.word) + "\"");
  return listed(quoted, " or ");
}

}  // namespace rupture::analysis
