#pragma once
// The plane tests of the simd psv: the reference's float planes and exact fallback
// (reference/psv/plane_side.h), with one error bound per node instead of one per point, and the
// defining points of a plane (a triangle's own vertices) answered without an exact predicate.
#include <array>
#include <bit>
#include <cstdint>

#include <tbb/enumerable_thread_specific.h>
#include <glm/vec3.hpp>

#include "reference/psv/plane_side.h"
#include "reference/psv/top_tree.h"
#include "shadowcts/geometry/volume_location.h"
#include "shadowcts/huge_pages.h"

namespace shadowcts::simd::psv {

namespace ref = shadowcts::psv;

// The vertices of a volume's triangle, stored per volume beside the tree: its planes' defining
// points (edge plane k holds vertices k and k + 1 mod 3), read without a visit to the triangle.
using VolumeCorners = std::array<glm::vec3, 3>;
// Per volume of a tree, in huge pages: the descents read it at random.
using VolumeCornerArray = HugePageVector<VolumeCorners>;

class PlaneSide {
 public:
  explicit PlaneSide(const ref::PlaneSide& exact) : exact_(exact) {}

  const ref::PlaneSide& exact() const { return exact_; }
  // The exact predicates this object's tests took (near_side), on every thread.
  std::uint64_t exact_tests() const;

  // A bound on |plane value - exact value| for every point whose coordinates are at most the
  // scene bound M in magnitude: the reference's per-point bound taken at (M, M, M). Rounding to
  // nearest is monotone and that bound only grows with |p|, so it covers every such point. A few
  // operations on the node's own floats: cheaper than one more memory access per node.
  double node_bound(const ref::TopNode& node, bool capping) const {
    const double m = exact_.filter().scene_bound;
    return geometry::plane_error_bound(exact_.filter(), node.plane.data(), capping,
                                       glm::dvec3(m, m, m));
  }

  // ref::triangle_location of the triangle with vertices `t` at `node`: 1 positive, -1 on the
  // closed negative side, 0 straddling or touching an edge plane from the positive side.
  // The three plane values first, without a branch; exact tests only for the vertices the bound
  // leaves open, and none once the triangle is known to straddle.
  int triangle_location(const ref::TopTree& tree, std::uint32_t node, const VolumeCorners& corners,
                        const glm::dvec3 (&t)[3]) const {
    const ref::TopNode& n = tree.nodes[node];
    const double bound = node_bound(n, ref::is_capping_node(node));
    unsigned positive = 0, negative = 0;
    for (unsigned k = 0; k < 3; ++k) {
      const double v = geometry::plane_value(n.plane.data(), t[k]);
      positive |= unsigned(v > bound) << k;
      negative |= unsigned(v < -bound) << k;
    }
    for (unsigned open = 7u & ~(positive | negative); open != 0 && !(positive && negative);
         open &= open - 1) {
      const unsigned k = unsigned(std::countr_zero(open));
      const int side = near_side(tree, node, corners, t[k]);
      positive |= unsigned(side > 0) << k;
      negative |= unsigned(side < 0) << k;
    }
    // A vertex with neither bit lies on the plane (when the triangle does not straddle it).
    return geometry::volume_location(positive != 0, negative != 0, (positive | negative) != 7u,
                                     ref::is_capping_node(node));
  }

  // Exact sign of the plane of `node` at p (1 outside, 0 on it, -1 inside), for a p with
  // float-valued coordinates. `bound` is node_bound of the node, `corners` its volume's.
  int side(const ref::TopTree& tree, std::uint32_t node, double bound, const VolumeCorners& corners,
           const glm::dvec3& p) const {
    const double v = geometry::plane_value(tree.nodes[node].plane.data(), p);
    if (v > bound) return 1;
    if (v < -bound) return -1;
    return near_side(tree, node, corners, p);
  }

 private:
  // Within the per-node bound: a defining point of the plane lies on it; otherwise the
  // reference's tighter per-point filter, then its exact predicate on `corners`.
  int near_side(const ref::TopTree& tree, std::uint32_t node, const VolumeCorners& corners,
                const glm::dvec3& p) const;

  const ref::PlaneSide& exact_;
  // Per thread: one shared counter cost a contended atomic per exact test.
  mutable tbb::enumerable_thread_specific<std::uint64_t> exact_tests_{0};
};

}  // namespace shadowcts::simd::psv
