#pragma once
// The descents of a batch of the simd psv build (top_tree_build.cpp), one descent per Highway
// lane, dispatched to the best target at run time.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "reference/psv/top_tree.h"
#include "reference/psv/top_tree_batches.h"
#include "shadowcts/case.h"
#include "simd/psv/plane_side.h"

namespace shadowcts::simd::psv {

// Descends the triangles scene[triangles[i]], i in [first, last), from the root of `tree` (which
// does not change during the call) into out[i]: the reference's descents, each to its empty child
// or shadow leaf. `corners` holds the corners of every volume of the tree.
void descend_in_lanes(const ref::TopTree& tree, const VolumeCornerArray& corners,
                      const PlaneSide& planes, const std::vector<Triangle>& scene,
                      const std::uint32_t* triangles, std::size_t first, std::size_t last,
                      ref::Descent* out);

}  // namespace shadowcts::simd::psv
