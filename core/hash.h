// FNV-1a, 64 bits (Fowler, Noll, Vo): a small, well-spread, non-cryptographic hash for identifying content that
// is checked again anyway: a scene file's bytes, a frame cache key, a rendered frame's planes. Collisions are
// not a security matter here: every use compares the full content or key it stands for where it matters.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace rtdr {

class Fnv1a64 {
 public:
  // One byte at a time, as FNV-1a is defined.
  Fnv1a64& bytes(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) h_ = (h_ ^ p[i]) * kPrime;
    return *this;
  }
  Fnv1a64& text(std::string_view s) { return bytes(s.data(), s.size()).bytes("", 1); }  // ended by a 0 byte
  // FNV-1a over 32-bit symbols instead of bytes (each value folded in whole): four times fewer steps for the
  // planes of a frame, whose values are all 4 bytes.
  Fnv1a64& words(const uint32_t* data, size_t count) {
    for (size_t i = 0; i < count; ++i) h_ = (h_ ^ data[i]) * kPrime;
    return *this;
  }
  // A float's bits, not its value: -0 and 0, and NaNs of different payloads, are told apart.
  Fnv1a64& floats(const float* data, size_t count) {
    for (size_t i = 0; i < count; ++i) h_ = (h_ ^ std::bit_cast<uint32_t>(data[i])) * kPrime;
    return *this;
  }
  uint64_t value() const { return h_; }
  // 16 lowercase hex digits.
  std::string hex() const {
    char s[17];
    std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(h_));
    return s;
  }

 private:
  static constexpr uint64_t kPrime = 0x100000001b3ULL;
  uint64_t h_ = 0xcbf29ce484222325ULL;  // the offset basis
};

}  // namespace rtdr
