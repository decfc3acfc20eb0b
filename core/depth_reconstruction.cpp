#include "shadowcts/depth_reconstruction.h"

#include <cmath>

namespace shadowcts {

std::optional<glm::dvec3> world_from_depth(const GBufferFormat& format, std::uint32_t x,
                                           std::uint32_t y, std::uint32_t width,
                                           std::uint32_t height, double depth) {
  const double v[4] = {
      2.0 * (double(x) + 0.5) / double(width) - 1.0,
      double(format.row_0_ndc_y) * (1.0 - 2.0 * (double(y) + 0.5) / double(height)),
      format.depth_range == NdcDepthRange::zero_to_one ? depth : 2.0 * depth - 1.0,
      1.0,
  };
  double h[4];
  for (int r = 0; r < 4; ++r) {
    const auto& row = format.inverse_view_projection[std::size_t(r)];
    h[r] = row[0] * v[0] + row[1] * v[1] + row[2] * v[2] + row[3] * v[3];
  }
  if (!(h[3] != 0.0) || !std::isfinite(h[3])) return std::nullopt;
  const glm::dvec3 p(h[0] / h[3], h[1] / h[3], h[2] / h[3]);
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return std::nullopt;
  return p;
}

}  // namespace shadowcts
