#pragma once
// Clustered light assignment (Paper II), the port of reference/lightassign/clustered_assignment.h:
// the same keys, unique clusters, bounds and cones (the reference's functions, per sample and per
// cluster over oneTBB), the reference's light BVH traversed with 32 children per node in Highway
// lanes and the leaves culled by the exact sphere/box test in lanes.
#include "reference/lightassign/clustered_assignment.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd {

AlgorithmOutput assign_lights_clustered(const PreparedScene& scene,
                                        const ClusteredSettings& settings);

}  // namespace shadowcts::simd
