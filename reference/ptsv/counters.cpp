#include "reference/ptsv/counters.h"

#include "reference/ptsv/triangle_setup.h"

namespace shadowcts::ptsv {

Counters to_counters(const TraversalCounters& traversal, const SetupCounts& setup,
                     const HierarchyShape& hierarchy, std::uint64_t light_on_caster_samples) {
  return {{"test_and_set_operations", traversal.test_and_set()},
          {"node_tests", traversal.node_tests},
          {"sample_tests", traversal.sample_tests},
          {"nodes_visited", traversal.nodes_visited},
          {"trivial_accepts", traversal.trivial_accepts},
          {"trivial_rejects", traversal.trivial_rejects},
          {"culling_plane_rejects", traversal.culling_plane_rejects},
          {"first_pass_jobs", traversal.first_pass_jobs},
          {"second_pass_jobs", traversal.second_pass_jobs},
          {"shadow_volumes", setup.volumes},
          {"front_faces_culled", setup.front_faces_culled},
          {"edge_on_triangles", setup.edge_on},
          {"zero_area_triangles", setup.zero_area},
          {"culling_planes", setup.extra_planes + setup.silhouette_planes},
          {"hierarchy_nodes", hierarchy.nodes},
          {"hierarchy_levels", hierarchy.levels},
          {"key_bits", hierarchy.key_bits},
          {"light_on_caster_samples", light_on_caster_samples}};
}

}  // namespace shadowcts::ptsv
