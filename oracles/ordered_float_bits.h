#pragma once
#include <cstdint>
#include <cstring>

namespace shadowcts {

// A float's bits, mapped so that their unsigned order is the numeric order (-0 taken as +0):
// sort keys for floats.
inline std::uint32_t ordered_float_bits(float v) {
  v += 0.0f;  // -0 becomes +0
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}

}  // namespace shadowcts
