#pragma once
// A tighter "near an edge" test than ray_near_triangle_edge (segment_triangle.h), for code that
// pays for every positive with an exact decision on the host (the brute-force kernel).
//
// The float watertight test decides the signs of the edge functions E = q.x p.y - q.y p.x of the
// rounded ray-space vertices exactly. Each ray-space coordinate x = (v_x - o_x) - s (v_z - o_z)
// differs from its exact value (exact vertices, exact segment direction L - p, exact shear s) by
// at most about 5 u n, u = 2^-24, with n = |x| + |y| + |v_z - o_z| (one rounding each for the two
// differences, the product and the shear, three for the shear's inputs L - p). Expanding E around
// the rounded coordinates, exactly:
//   |E* - E| <= 5u (n_q m_p + n_p m_q) + 25 u^2 n_p n_q,   m = |x| + |y|,
// and below float's normal range a coordinate's error is absolute, up to 2^-149 per rounding.
// Where |E| exceeds that, its sign is the exact one. The float answer of the point-in-triangle
// test can differ from the exact one only where some sign is uncertain and the other two do not
// already decide "outside" (two certain, opposite signs). The bound below keeps a factor of at
// least 50 over the error. ray_near_triangle_edge bounds the same error by 2^-16 n_p n_q: for a
// triangle small against its distance (m << n) that flags far more segments.
#include <cmath>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/segment_triangle.h"
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

SHADOWCTS_HD inline bool ray_within_rounding_of_triangle_edge(const RaySpace& space,
                                                              const glm::vec3& v0,
                                                              const glm::vec3& v1,
                                                              const glm::vec3& v2) {
  if (space.zero_direction) return false;
  const RaySpaceVertex a = to_ray_space(space, v0);
  const RaySpaceVertex b = to_ray_space(space, v1);
  const RaySpaceVertex c = to_ray_space(space, v2);
  const auto lateral = [](const RaySpaceVertex& r) {
    return double(std::fabs(r.x)) + double(std::fabs(r.y));
  };
  const auto extent = [&](const glm::vec3& v, const RaySpaceVertex& r) {
    return lateral(r) + double(std::fabs(rounded_sub(component(v, space.kz),
                                                     component(space.origin, space.kz))));
  };
  const double na = extent(v0, a), nb = extent(v1, b), nc = extent(v2, c);
  const double ma = lateral(a), mb = lateral(b), mc = lateral(c);
  const auto bound = [](double np, double mp, double nq, double mq) {
    return 0x1p-16 * (nq * mp + np * mq) + 0x1p-30 * np * nq + 0x1p-140 * (np + nq);
  };
  const double e[3] = {exact_edge_function(b, c), exact_edge_function(c, a),
                       exact_edge_function(a, b)};
  const bool near[3] = {std::fabs(e[0]) <= bound(nb, mb, nc, mc),
                        std::fabs(e[1]) <= bound(nc, mc, na, ma),
                        std::fabs(e[2]) <= bound(na, ma, nb, mb)};
  // An uncertain sign matters only if the other two do not already put the origin outside (two
  // certain, opposite signs): the origin near the extension of an edge's line is not near the
  // triangle.
  for (int i = 0; i < 3; ++i) {
    if (!near[i]) continue;
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (near[j] || near[k] || (e[j] > 0.0) == (e[k] > 0.0)) return true;
  }
  return false;
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
