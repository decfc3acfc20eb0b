#pragma once
// Doubles rounded to float in a chosen direction, for float copies of double bounds that must
// still hold: std::nextafter's answers by the bit pattern, without a library call per value.
#include <bit>
#include <cstdint>

namespace shadowcts {

// The float next to f towards -infinity (down) or +infinity, for f not NaN and not already the
// infinity it goes towards. Floats of one sign are ordered as their bits.
inline float next_float(float f, bool down) {
  if (f == 0.0f) return down ? -0x1p-149f : 0x1p-149f;
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>((f > 0.0f) == down ? bits - 1 : bits + 1);
}

// The largest float <= x and the smallest float >= x (x not NaN).
inline float float_below(double x) {
  const float f = float(x);
  return double(f) > x ? next_float(f, true) : f;
}
inline float float_above(double x) {
  const float f = float(x);
  return double(f) < x ? next_float(f, false) : f;
}

}  // namespace shadowcts
