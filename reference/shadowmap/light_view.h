#pragma once
// The projection of one depth map: a cube-map face of a point light (perspective, 90 degrees) or
// the orthographic map of a directional light. Points go world -> view (right, up, forward) ->
// raster (texel units, texel (i, j) has its centre at (i + 0.5, j + 0.5)); the stored depth is
// the view-space forward distance.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace shadowcts::shadowmap {

struct LightView {
  bool perspective = true;
  glm::dvec3 origin{0.0};  // the point light, or the centre of the orthographic window
  glm::dvec3 right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0}, forward{0.0, 0.0, 1.0};
  // Orthographic: half the side of the square window in world units. Perspective: the face spans
  // |x| <= z and |y| <= z.
  double half_extent = 1.0;
  double near = 0.0;  // perspective only: casters closer than this along forward are clipped
  std::uint32_t resolution = 0;

  glm::dvec3 to_view(const glm::dvec3& world) const {
    const glm::dvec3 d = world - origin;
    return {d.x * right.x + d.y * right.y + d.z * right.z, d.x * up.x + d.y * up.y + d.z * up.z,
            d.x * forward.x + d.y * forward.y + d.z * forward.z};
  }

  // Raster position of a view-space point (perspective: z > 0).
  glm::dvec2 to_raster(const glm::dvec3& view) const {
    const double scale = 0.5 * double(resolution);
    const double x = perspective ? view.x / view.z : view.x / half_extent;
    const double y = perspective ? view.y / view.z : view.y / half_extent;
    return {(x + 1.0) * scale, (y + 1.0) * scale};
  }

  // The texel a view-space point reads (the nearest, clamped to the map); false at the light
  // itself (perspective, z <= 0).
  bool texel_of(const glm::dvec3& view, std::uint32_t& column, std::uint32_t& row) const {
    if (perspective && !(view.z > 0.0)) return false;
    const glm::dvec2 r = to_raster(view);
    const auto last = double(resolution - 1);
    column = std::uint32_t(std::clamp(std::floor(r.x), 0.0, last));
    row = std::uint32_t(std::clamp(std::floor(r.y), 0.0, last));
    return true;
  }

  // World-space side of one texel at view depth z, measured across the forward axis.
  double texel_size(double z) const {
    return (perspective ? 2.0 * z : 2.0 * half_extent) / double(resolution);
  }
};

}  // namespace shadowcts::shadowmap
