// sample/text_reader: the line and number reading shared by the sample file readers, so that every
// format reports errors the same way ("file:line: problem; fix"). Internal to src/sample.
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/error.hpp"
#include "core/tokens.hpp"
#include "sample/sample.hpp"

namespace rupture::sample_detail {

// Walks a text line by line; `comment` strips everything from that character on (0: none).
// `layout_fix` is the fix of an error that has no more specific one: where the layout is described.
class TextReader {
 public:
  TextReader(std::string_view text, std::string source, char comment, std::string layout_fix)
      : text_(text), source_(std::move(source)), comment_(comment), layout_fix_(std::move(layout_fix)) {}

  // Next line that is not blank after comment stripping; false at the end of the text.
  bool next(std::string_view& line) {
    while (pos_ < text_.size()) {
      auto end = text_.find('\n', pos_);
      if (end == std::string_view::npos) end = text_.size();
      std::string_view raw = text_.substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_number_;
      last_raw_ = raw;
      if (comment_ != 0) {
        const auto c = raw.find(comment_);
        if (c != std::string_view::npos) raw = raw.substr(0, c);
      }
      raw = tokens::trim(raw);
      if (!raw.empty()) {
        line = raw;
        return true;
      }
    }
    return false;
  }
  // Like next(), but a missing line is a truncated file.
  std::string_view require(std::string_view what) {
    std::string_view line;
    if (!next(line))
      throw InputError(fmt::format("{}:{}", source_, line_number_),
                       fmt::format("file ends where {} was expected: it is truncated", what),
                       "write or copy the file again");
    return line;
  }

  // The raw text of the line last returned (with its comment), for format-specific comments.
  std::string_view raw_line() const { return last_raw_; }
  std::string where() const { return fmt::format("{}:{}", source_, line_number_); }
  [[noreturn]] void fail(const std::string& problem, const std::string& fix = {}) const {
    throw InputError(where(), problem, fix.empty() ? layout_fix_ : fix);
  }

  // Numbers; `what` names the column in the error.
  double real(std::string_view word, std::string_view what) const {
    const auto value = tokens::number<double>(word);
    if (!value || !std::isfinite(*value))
      fail(fmt::format("{} '{}' is not a finite number", what, excerpt(word)),
           "write a decimal number such as 0.25 or 1e-3");
    return *value;
  }
  std::int64_t integer(std::string_view word, std::string_view what) const {
    const auto value = tokens::number<std::int64_t>(word);
    if (!value)
      fail(fmt::format("{} '{}' is not an integer", what, excerpt(word)), "write a whole number such as 12");
    return *value;
  }
  std::size_t count(std::string_view word, std::string_view what) const {
    const auto v = integer(word, what);
    if (v < 0) fail(fmt::format("{} {} is negative", what, v), "a count is 0 or more");
    return static_cast<std::size_t>(v);
  }
  double radius(std::string_view word) const {
    const double r = real(word, "radius");
    if (!(r > 0.0)) fail(fmt::format("radius {} mm is not positive", r), "every particle needs a radius > 0");
    return r;
  }
  void expect_columns(const std::vector<std::string_view>& words, std::size_t at_least,
                      std::string_view layout) const {
    if (words.size() < at_least)
      fail(fmt::format("{} columns where {} were expected ({})", words.size(), at_least, layout));
  }

 private:
  std::string_view text_;
  std::string source_;
  char comment_;
  std::string layout_fix_;
  std::size_t pos_ = 0, line_number_ = 0;
  std::string_view last_raw_;
};

// Builds a sample's particle arrays and bonds from ids, checking what every format must satisfy:
// unique ids, bonds between known and distinct particles, no bond twice. Messages show an id as
// the file writes it: the id plus `shown_id_offset` (LAMMPS atom-IDs are rupture ids + 1).
class SampleAssembler {
 public:
  explicit SampleAssembler(std::int64_t shown_id_offset = 0) : shown_(shown_id_offset) {}

  void add_particle(const TextReader& in, std::int64_t id, Vec3 position, double radius,
                    ParticleGroup group = ParticleGroup::free) {
    if (!index_of_.emplace(id, static_cast<std::uint32_t>(sample.size())).second)
      in.fail(fmt::format("particle id {} appears twice", id + shown_), "ids must be unique");
    sample.id.push_back(id);
    sample.position.push_back(position);
    sample.radius.push_back(radius);
    sample.group.push_back(group);
  }
  // rest_length < 0: take the distance between the two particles (formats that do not store it).
  void add_bond(const TextReader& in, std::int64_t id_a, std::int64_t id_b, double rest_length = -1.0) {
    const auto a = index_of_.find(id_a), b = index_of_.find(id_b);
    const std::string pair = fmt::format("bond {}-{}", id_a + shown_, id_b + shown_);
    if (a == index_of_.end() || b == index_of_.end())
      in.fail(fmt::format("{} names particle id {}, which the file does not define", pair,
                          (a == index_of_.end() ? id_a : id_b) + shown_),
              "bond only particles that the file lists");
    if (id_a == id_b)
      in.fail(fmt::format("{} joins a particle to itself", pair), "a bond joins two particles");
    const auto i = std::min(a->second, b->second), j = std::max(a->second, b->second);
    if (rest_length < 0.0) rest_length = norm(sample.position[j] - sample.position[i]);
    if (!(rest_length > 0.0))
      in.fail(fmt::format("{} has rest length {} mm", pair, rest_length),
              "give a rest length > 0, or particles at distinct positions");
    if (!bond_keys_.emplace((std::uint64_t{i} << 32) | j, 0).second)
      in.fail(fmt::format("{} appears twice", pair), "list each bonded pair once");
    sample.bonds.push_back({i, j, rest_length});
  }
  Sample finish() {
    std::sort(sample.bonds.begin(), sample.bonds.end(),
              [](const Bond& x, const Bond& y) { return x.i != y.i ? x.i < y.i : x.j < y.j; });
    return std::move(sample);
  }

  Sample sample;

 private:
  std::int64_t shown_;
  std::unordered_map<std::int64_t, std::uint32_t> index_of_;
  std::unordered_map<std::uint64_t, char> bond_keys_;
};

// Storage indices in id order: every writer emits particles in this order.
inline std::vector<std::uint32_t> id_order(const Sample& sample) {
  std::vector<std::uint32_t> order(sample.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return sample.id[a] < sample.id[b]; });
  return order;
}

// Bonds by id (smaller id first), sorted: the order every writer emits them in.
struct IdBond {
  std::int64_t a = 0, b = 0;
  double rest_length = 0.0;  // mm
};
inline std::vector<IdBond> bonds_by_id(const Sample& sample) {
  std::vector<IdBond> bonds;
  bonds.reserve(sample.bonds.size());
  for (const Bond& bond : sample.bonds)
    bonds.push_back({std::min(sample.id[bond.i], sample.id[bond.j]),
                     std::max(sample.id[bond.i], sample.id[bond.j]), bond.rest_length});
  std::sort(bonds.begin(), bonds.end(),
            [](const IdBond& x, const IdBond& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  return bonds;
}

}  // namespace rupture::sample_detail
