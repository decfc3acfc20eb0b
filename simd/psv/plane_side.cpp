#include "simd/psv/plane_side.h"

#include <cmath>

#include "shadowcts/geometry/expansion.h"

namespace shadowcts::simd::psv {
namespace {

// True only when p lies exactly on the line through a and b (a != b): then every plane through
// that line holds p. Decided with error-free transformations where they are exact (the
// differences exact in double, no product near underflow); false otherwise, and the exact
// predicate decides. The grid lines of a tessellated surface pass through many vertices: edge
// planes through the light and such a line hold them all.
bool surely_on_line(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& p) {
  double u[3], w[3];
  for (int i = 0; i < 3; ++i) {
    double error_u = 0.0, error_w = 0.0;
    geometry::two_sum(b[i], -a[i], u[i], error_u);
    geometry::two_sum(p[i], -a[i], w[i], error_w);
    if (error_u != 0.0 || error_w != 0.0) return false;
  }
  // u x w = 0: each pair of products equal, compared as exact (product, error) pairs.
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    double p1 = 0.0, e1 = 0.0, p2 = 0.0, e2 = 0.0;
    geometry::two_product(u[i], w[j], p1, e1);
    geometry::two_product(u[j], w[i], p2, e2);
    const auto too_small = [](double x) { return x != 0.0 && std::fabs(x) < 0x1p-900; };
    if (too_small(p1) || too_small(p2) || p1 != p2 || e1 != e2) return false;
  }
  return true;
}

}  // namespace

int PlaneSide::near_side(const ref::TopTree& tree, std::uint32_t node, const VolumeCorners& corners,
                         const glm::dvec3& p) const {
  const std::uint32_t k = node % ref::nodes_per_volume;
  const auto at = [&](std::uint32_t i) { return glm::dvec3(corners[i]) == p; };
  if (k == ref::capping_plane) {
    if (at(0) || at(1) || at(2)) return 0;
  } else if (at(k) || at((k + 1) % 3) ||
             surely_on_line(glm::dvec3(corners[k]), glm::dvec3(corners[(k + 1) % 3]), p)) {
    // An edge plane holds its edge (and the light): a neighbour sharing the edge's vertices, or
    // further vertices on the edge's line, the common cases of a tessellated surface, need no
    // exact predicate.
    return 0;
  }
  // The reference's side(), its exact test on the corners (already in the cache, where the
  // triangle is not) and counted per thread.
  const ref::TopNode& n = tree.nodes[node];
  const double v = exact_.value(n, p);
  const double bound = exact_.error_bound(n, k == ref::capping_plane, p);
  if (v > bound) return 1;
  if (v < -bound) return -1;
  ++exact_tests_.local();
  const glm::dvec3 vertices[3] = {glm::dvec3(corners[0]), glm::dvec3(corners[1]),
                                  glm::dvec3(corners[2])};
  return exact_.exact_side(tree.sources[ref::volume_of(node)], k, vertices, p);
}

std::uint64_t PlaneSide::exact_tests() const {
  std::uint64_t tests = 0;
  for (const std::uint64_t n : exact_tests_) tests += n;
  return tests;
}

}  // namespace shadowcts::simd::psv
