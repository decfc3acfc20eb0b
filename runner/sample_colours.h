#pragma once
// The colours every image of a run shares for samples that are not compared, so masks, heat maps
// and the report's legends agree.
#include <cstdint>

namespace shadowcts {

struct Rgb {
  std::uint8_t r, g, b;
};

inline constexpr Rgb sky_colour{110, 150, 200};
inline constexpr Rgb back_facing_colour{45, 50, 70};  // unlit by orientation / not compared

inline void put_rgb(std::uint8_t* pixel, Rgb c) {
  pixel[0] = c.r;
  pixel[1] = c.g;
  pixel[2] = c.b;
}

}  // namespace shadowcts
