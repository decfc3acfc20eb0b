#pragma once
// The single orthographic depth map of a directional light, fitted to the view samples.
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/shadowmap/light_view.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::shadowmap {

// Looks along -towards_light. The square window is the bounding square of the regular samples
// projected across the light direction, widened by one texel on each side so that samples on the
// border still find a texel centre on both sides of them. Casters outside the window cannot
// shadow a sample inside it (a shadow ray keeps its window position), so nothing is lost.
LightView orthographic_view(const glm::dvec3& towards_light, const ViewSamples& samples,
                            std::uint32_t resolution);

}  // namespace shadowcts::shadowmap
