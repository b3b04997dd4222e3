// A 64-bit FNV-1a hash (Fowler, Noll, Vo) of bytes fed in order: the identity of a scene and its
// options for checkpoints, and the checksum of their contents. Not cryptographic: it detects
// accidents (another scene, a torn or flipped file), not forgery.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>

namespace rad {

class Fingerprint {
 public:
  Fingerprint& bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
    return *this;
  }
  template <typename T>
  Fingerprint& add(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    return bytes(&v, sizeof v);
  }
  Fingerprint& add(std::string_view s) { return add(uint64_t(s.size())).bytes(s.data(), s.size()); }
  uint64_t value() const { return h_; }

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace rad
