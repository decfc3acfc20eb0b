#pragma once
// Work counters: the papers' implementation-independent efficiency metric is the number of
// test-and-set operations, "the total number of tile/shadow frustum and sample/shadow frustum
// tests performed" (Sintorn 2011, Section 4; Sintorn 2014, Figure 6). Counted here as node (or
// tile) tests plus sample tests, with the rest of the traversal's work beside them.
#include <cstdint>

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

}  // namespace shadowcts::ptsv
