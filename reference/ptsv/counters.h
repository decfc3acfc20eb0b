#pragma once
// Work counters: the papers' implementation-independent efficiency metric is the number of
// test-and-set operations, "the total number of tile/shadow frustum and sample/shadow frustum
// tests performed" (Sintorn 2011, Section 4; Sintorn 2014, Figure 6). Counted here as node (or
// tile) tests plus sample tests, with the rest of the traversal's work beside them.
#include <cstdint>

#include "shadowcts/algorithm.h"

namespace shadowcts::ptsv {

struct TraversalCounters {
  std::uint64_t node_tests = 0;             // an existing child node tested against a volume
  std::uint64_t sample_tests = 0;           // a view sample tested against a volume
  std::uint64_t nodes_visited = 0;          // TRAVERSENODE calls (Algorithm 1)
  std::uint64_t trivial_accepts = 0;        // nodes found inside a volume
  std::uint64_t trivial_rejects = 0;        // nodes outside one of the four volume planes
  std::uint64_t culling_plane_rejects = 0;  // nodes outside an extra or silhouette plane only
  std::uint64_t first_pass_jobs = 0;        // two-pass: (triangle, node) jobs the first pass emits
  std::uint64_t second_pass_jobs = 0;       // two-pass: jobs the second pass finishes

  std::uint64_t test_and_set() const { return node_tests + sample_tests; }
};

struct SetupCounts;  // reference/ptsv/triangle_setup.h

// The view-sample hierarchy's size: its nodes, its levels and the bits of its cluster keys (0 for
// the 2011 depth-buffer variant, which has no keys).
struct HierarchyShape {
  std::uint64_t nodes = 0, levels = 0, key_bits = 0;
};

// Every ptsv backend's counters, in the order they are reported: test_and_set_operations, the
// traversal's counts, the triangle setup's (shadow_volumes, front_faces_culled,
// edge_on_triangles, zero_area_triangles, culling_planes), the hierarchy's shape and
// light_on_caster_samples.
Counters to_counters(const TraversalCounters& traversal, const SetupCounts& setup,
                     const HierarchyShape& hierarchy, std::uint64_t light_on_caster_samples);

}  // namespace shadowcts::ptsv
