#pragma once
// The light depths of the simd psv build's new volumes (ref::triangle_light_depth) in Highway
// lanes, dispatched to the best target at run time.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "reference/psv/top_tree_batches.h"
#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::simd::psv {

namespace ref = shadowcts::psv;

// volumes[i].depth = ref::triangle_light_depth(light, scene[triangles[i]]) for every i in
// [first, last) whose descent was not dropped, bit for bit: a point light's in lanes, with the
// reference's operations in the reference's order.
void triangle_light_depths(const HardShadowLight& light, const std::vector<Triangle>& scene,
                           const std::uint32_t* triangles, const ref::Descent* descents,
                           std::size_t first, std::size_t last, ref::BatchVolume* volumes);

}  // namespace shadowcts::simd::psv
