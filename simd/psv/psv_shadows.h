#pragma once
// Hard shadows with partitioned shadow volumes on oneTBB and Highway: the reference's TOP tree
// built in parallel batches (top_tree_build.h), then every regular sample located in packets whose
// node tests run in vector lanes (query_packet.h). The tree, every answer and the query counters
// are the reference's; exact_plane_tests counts this port's own exact decisions.
#include <cstdint>
#include <vector>

#include "reference/psv/psv_shadows.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/prepared_scene.h"
#include "simd/psv/top_tree_build.h"

namespace shadowcts::simd::psv {

struct SimdPsvOptions {
  ref::PsvOptions psv;        // the variant's query and stack capacity, the seed
  std::uint32_t packet = 16;  // samples per packet, 1 to max_packet
};

struct SimdPsvResult {
  std::vector<std::uint8_t> shadowed;        // per view sample
  std::vector<std::uint32_t> nodes_visited;  // per view sample (0 for non-regular ones)
  Counters counters;                         // ref::PsvResult's, in its order
  PhaseTimes phase_ms;                       // "build" and "query"
  BuildWork build_work;
};

// The build phase of ref::build_psv on oneTBB: the same light, plane tests and tree.
struct SimdPsvBuild {
  ref::PsvBuild build;
  VolumeCornerArray corners;  // per volume of build.tree
  BuildWork work;
};
SimdPsvBuild build_psv(const PreparedScene& scene, std::uint64_t seed);

// Runs on the case's thread count; the result does not depend on it.
SimdPsvResult psv_hard_shadows(const PreparedScene& scene, const SimdPsvOptions& options);

}  // namespace shadowcts::simd::psv
