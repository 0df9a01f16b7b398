#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace ldm {

// 64-bit FNV-1a over raw bytes: stable across runs and machines of the same endianness,
// used for cache keys and list checksums.
class Fnv1a {
 public:
  void add_bytes(const void* data, size_t n) {
    auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ull;
    }
  }
  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    add_bytes(&value, sizeof(T));
  }
  template <typename T>
  void add_vector(const std::vector<T>& values) {
    add(uint64_t(values.size()));
    if (!values.empty()) add_bytes(values.data(), values.size() * sizeof(T));
  }
  void add_string(std::string_view s) {
    add(uint64_t(s.size()));
    add_bytes(s.data(), s.size());
  }
  uint64_t value() const { return h_; }

 private:
  uint64_t h_ = 1469598103934665603ull;
};

std::string hex64(uint64_t value);

}  // namespace ldm
