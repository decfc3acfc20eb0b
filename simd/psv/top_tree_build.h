#pragma once
// The TOP tree of reference/psv built on oneTBB, node for node the reference's tree: the batches
// of reference/psv/top_tree_batches.h, whose descents run here on oneTBB threads, eight per
// thread in Highway lanes (descent_lanes.h), with this port's plane tests (plane_side.h).
#include <cstdint>
#include <vector>

#include "reference/psv/top_tree.h"
#include "reference/psv/top_tree_batches.h"
#include "reference/psv/top_tree_build.h"
#include "shadowcts/case.h"
#include "simd/psv/plane_side.h"

namespace shadowcts::simd::psv {

using BuildWork = ref::BatchWork;

// ref::insertion_order with the light sides and reaches decided in parallel: the same order and
// statistics. `casts`: the prepared scene's (CasterArrays::casts, casts_shadow's answers).
std::vector<std::uint32_t> insertion_order(const Case& c, const std::vector<std::uint8_t>& casts,
                                           const ref::PlaneSide& planes,
                                           const std::vector<bool>& face_culling,
                                           const CasterReach& reach, std::uint64_t seed,
                                           ref::BuildStatistics& statistics);

// ref::build_top_tree in parallel batches: the same tree, sources and statistics. `corners`
// receives the corners of every volume, for the queries.
ref::TopTree build_top_tree(const Case& c, const PlaneSide& planes,
                            const std::vector<std::uint32_t>& order,
                            ref::BuildStatistics& statistics, VolumeCornerArray& corners,
                            BuildWork& work);

}  // namespace shadowcts::simd::psv
