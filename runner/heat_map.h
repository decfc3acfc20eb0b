#pragma once
// Per-sample counts (work counters, light-list lengths) as heat-map images.
#include <cstdint>
#include <vector>

#include "shadowcts/image_file.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Black at 0, through red and orange to white at `full` and above; sky and back-facing samples
// keep the colours of the shadow masks.
RgbImage count_heat_map(const ViewSamples& samples, const std::vector<std::uint32_t>& count,
                        std::uint32_t full);

}  // namespace shadowcts
