// core/hash: FNV-1a 64, the one content hash rupture stores (checkpoint checksums, sample
// fingerprints, the prefix of a growing output file, the engine's state hash in tests). Not
// cryptographic: it detects damage and change, not tampering.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>
#include <vector>

namespace rupture {

struct Fnv1a {
  std::uint64_t hash = 0xcbf29ce484222325ULL;

  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ULL;
  }
  void add(std::string_view text) { add(text.data(), text.size()); }
  template <class T>
  void add_value(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(&value, sizeof value);
  }
  template <class T>
  void add_vector(const std::vector<T>& values) {
    add(values.data(), values.size() * sizeof(T));
  }
};

}  // namespace rupture
