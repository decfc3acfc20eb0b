#pragma once
// The one configuration of the hard-shadow definition that no shadow volume expresses: a point
// light lying on a caster triangle. Triangles are closed and the segment includes L, so such a
// triangle meets every shadow segment and shadows every sample it does not receive. Its shadow
// volume is degenerate (the light lies in its plane), and the papers drop it as edge-on; the
// reference implementations apply this rule after their traversal instead.
#include <cstdint>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Caster triangles of non-zero area that contain the point light (exact predicates), in index
// order; empty for a directional light or none.
std::vector<std::uint32_t> casters_containing_light(const Case& c);

// Marks shadowed every regular sample whose receiver is not the only caster containing the
// light. Returns how many samples it changed.
std::uint64_t shadow_samples_by_light_on_caster(const Case& c, const ViewSamples& samples,
                                                std::vector<std::uint8_t>& shadowed);

}  // namespace shadowcts
