#pragma once
// Reference `ptsv`: per-triangle shadow volumes traversed through the view-sample cluster
// hierarchy (Sintorn, Kämpe, Olsson, Assarsson 2014), with the 2011 hierarchical-depth-buffer
// PTSV (Sintorn, Olsson, Assarsson 2011) as a variant. Variants, cumulative as in the paper's
// Figure 8:
//   twopass          explicit bounds + extra culling planes + two-pass traversal (the default:
//                    the complete 2014 algorithm)
//   implicit         node bounds from the cluster keys, the four volume planes only (Baseline)
//   implicit+planes  ... plus the per-vertex culling planes (Additional planes)
//   explicit         tight boxes of each node's samples, four planes
//   explicit+planes  explicit bounds + culling planes (Explicit bounds)
//   hdb2011          the 2011 algorithm: 2D depth-buffer tiles, silhouette-edge culling
// Every variant gives the same shadow mask (the per-sample plane test decides; node tests only
// skip work), so they differ in their counters and time.
#include <cstdint>
#include <memory>
#include <vector>

#include "reference/ptsv/counters.h"
#include "reference/ptsv/traversal.h"
#include "reference/ptsv/triangle_setup.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {

namespace ptsv {

// What a variant name means, for every backend of ptsv.
struct VariantConfig {
  bool depth_buffer_2011;
  NodeBounds bounds;
  bool extra_planes;
  bool two_pass;
  bool implicit_cells() const { return bounds == NodeBounds::implicit_cells; }
};

// The view-sample hierarchy's size: its nodes, its levels and the bits of its cluster keys (0 for
// the 2011 depth-buffer variant, which has no keys).
struct HierarchyShape {
  std::uint64_t nodes = 0, levels = 0, key_bits = 0;
};

// Every ptsv backend's counters, in the order they are reported: test_and_set_operations, the
// traversal's counts, the triangle setup's (shadow_volumes, front_faces_culled,
// edge_on_triangles, zero_area_triangles, culling_planes), the hierarchy's shape and
// light_on_caster_samples. (Host code: counters.h is shared with the device kernels.)
Counters to_counters(const TraversalCounters& traversal, const SetupCounts& setup,
                     const HierarchyShape& hierarchy, std::uint64_t light_on_caster_samples);

}  // namespace ptsv

// The variants above, in that order; the ports register some of them.
std::vector<AlgorithmVariant<ptsv::VariantConfig>> ptsv_variants();

// id "ptsv", backend "reference".
std::unique_ptr<Algorithm> make_ptsv();

}  // namespace shadowcts
