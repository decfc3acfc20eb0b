#pragma once
// World positions from a depth buffer and the inverse view-projection matrix, computed in double
// and rounded to float32 once: the float32 result is the sample position every oracle and
// algorithm reads.
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

#include "shadowcts/gbuffer_format.h"

namespace shadowcts {

// The point pixel (x, y) of a width x height image shows at depth-buffer value `depth`, with
// row 0 at the top of the image and the sample at the pixel centre: x_ndc = 2 (x + 0.5) / width
// - 1, y_ndc = row_0_ndc_y (1 - 2 (y + 0.5) / height), z_ndc by depth_range; then
// (M v).xyz / (M v).w in double. nullopt when w is zero or the point is not finite in double.
std::optional<glm::dvec3> world_from_depth(const GBufferFormat& format, std::uint32_t x,
                                           std::uint32_t y, std::uint32_t width,
                                           std::uint32_t height, double depth);

}  // namespace shadowcts
