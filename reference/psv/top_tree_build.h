#pragma once
// Building the TOP tree: Algorithm 2 of Mora 2016 (the construction of Gerhards et al. 2015 with
// the depth and ancestor-link additions), one triangle at a time in a seeded random order.
#include <cstdint>
#include <vector>

#include "reference/caster_reach.h"
#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"
#include "shadowcts/case.h"

namespace shadowcts::psv {

struct BuildStatistics {
  std::uint64_t casters = 0;              // caster triangles of non-zero area
  std::uint64_t culled_out_of_reach = 0;  // meets no sample's segment (caster_reach.h)
  // Of the casters that may reach a sample:
  std::uint64_t culled_front_facing = 0;   // closed meshes only
  std::uint64_t culled_flat = 0;           // the light lies in the triangle's plane: no volume
  std::uint64_t samples_out_of_reach = 0;  // regular samples no inserted triangle can reach
  std::uint64_t dropped_in_shadow = 0;     // reached a shadow leaf: inside another volume
  std::uint64_t volumes = 0;
  std::uint64_t height = 0;  // nodes on the longest root-to-leaf path
};

// The triangles inserted, in insertion order: the casters of `c` that may reach a sample and
// have a volume (non-zero area, the light not in their plane, not front-facing in a closed mesh
// that may cull — see meshes_safe_for_face_culling and culling_clear_of_segment_starts),
// permuted by a Fisher-Yates shuffle driven by std::mt19937_64(seed) (the paper's randomized
// build; the same order on every platform).
// `face_culling`: per mesh, whether its light-facing triangles may be dropped.
std::vector<std::uint32_t> insertion_order(const Case& c, const PlaneSide& planes,
                                           const std::vector<bool>& face_culling,
                                           const CasterReach& reach, std::uint64_t seed,
                                           BuildStatistics& statistics);

// Builds the tree of the triangles of `order` (indices into c.triangles, which `planes` must
// refer to). A triangle descends from the root to the positive, negative or intersection child
// by the exact sides of its three vertices; a leaf is replaced by its four-node volume, and a
// triangle that reaches a shadow leaf lies inside that volume and is dropped (its own volume is
// contained in it). Depths and wedges are updated along the path of every inserted triangle.
TopTree build_top_tree(const Case& c, const PlaneSide& planes,
                       const std::vector<std::uint32_t>& order, BuildStatistics& statistics);

// The wedge triangle `t` (light depth `depth`) adds to the intersection subtree of edge node
// `node` (see TopNode::wedge): an upper bound on |plane| over its shadow volume, per unit of light
// distance for a point light.
float triangle_wedge(const PlaneSide& planes, const TopNode& node, const Triangle& t, float depth);

// The child of `node` that `t` is filed under, from its vertices' exact sides
// (geometry::volume_location): 1 positive, -1 negative, 0 intersection (straddling, or touching an
// edge plane from its positive side).
int triangle_location(const TopTree& tree, const PlaneSide& planes, std::uint32_t node,
                      const Triangle& t);

// Nodes on the longest root-to-leaf path (0 for an empty tree).
std::uint64_t tree_height(const TopTree& tree);

}  // namespace shadowcts::psv
