#include "heat_map.h"

#include <algorithm>
#include <cmath>

#include "sample_colours.h"

namespace shadowcts {

RgbImage count_heat_map(const ViewSamples& samples, const std::vector<std::uint32_t>& count,
                        std::uint32_t full) {
  RgbImage image{samples.width, samples.height,
                 std::vector<std::uint8_t>(samples.samples.size() * 3)};
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    std::uint8_t* px = &image.rgb[3 * i];
    const SampleClass cls = samples.samples[i].sample_class;
    if (cls == SampleClass::sky) {
      put_rgb(px, sky_colour);
    } else if (cls == SampleClass::back_facing) {
      put_rgb(px, back_facing_colour);
    } else {
      const double t = full ? std::min(1.0, double(count[i]) / full) : 0.0;
      px[0] = std::uint8_t(std::lround(255 * std::min(1.0, 3 * t)));
      px[1] = std::uint8_t(std::lround(255 * std::clamp(3 * t - 1, 0.0, 1.0)));
      px[2] = std::uint8_t(std::lround(255 * std::clamp(3 * t - 2, 0.0, 1.0)));
    }
  }
  return image;
}

}  // namespace shadowcts
