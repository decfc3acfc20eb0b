#include "reference/shadowmap/bias.h"

#include <algorithm>
#include <cmath>

namespace shadowcts::shadowmap {

double depth_bias(const DepthBias& bias, double texel_size, double cos_theta) {
  const double c = std::clamp(cos_theta, 0.0, 1.0);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - c * c));
  // tan(theta) = sin / cos, clamped without dividing by a zero cosine.
  const double tan_theta = sin_theta < bias.max_tan * c ? sin_theta / c : bias.max_tan;
  return texel_size * (bias.constant_texels + bias.slope_texels * tan_theta);
}

}  // namespace shadowcts::shadowmap
