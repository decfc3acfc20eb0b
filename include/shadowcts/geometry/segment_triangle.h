#pragma once
// Watertight occlusion test of a shadow segment or ray against one closed triangle, after the idea
// of Woop, Benthin and Wald ("Watertight Ray/Triangle Intersection", JCGT 2013): translate the
// vertices to the ray origin, shear and scale them so that the ray becomes the +z axis, and decide
// whether the origin lies in the projected triangle by the signs of its three 2D edge functions.
//
// Why it is watertight: each vertex is transformed on its own, so triangles that share a vertex see
// the same rounded vertex, and the sign of every edge function is exact for those rounded vertices
// (float products compared, with an exact double recomputation when they are equal). The test is
// therefore exact for one consistent perturbation of the mesh, and a ray cannot slip between two
// triangles through a shared edge or vertex. Triangles are closed (edges and vertices hit, on both
// sides of a shared edge), triangles of zero area never hit, and hits count for t in (0, t_max].
//
// Float's relative rounding holds only in its normal range: the edge functions are products of two
// lengths and the hit distance's numerator of three (of two for a point light, whose ray-space
// depths are dimensionless), which underflow in scenes scaled below about 2^-40 and overflow above
// about 2^42. Every float product is therefore checked to be normal (or an exact zero) and finite;
// where one is not, the double path decides, whose range covers every float scene.
#include <cfloat>
#include <cmath>
#include <type_traits>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/rounded_arithmetic.h"
#include "shadowcts/geometry/triangle_area.h"
#include "shadowcts/host_device.h"

namespace shadowcts {
SHADOWCTS_GEOMETRY_ABI_BEGIN

// The points origin + t * direction for t in (0, t_max].
struct ShadowRay {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f};
  float t_max = 0.0f;
};

// Segment from a view sample to a point light: t_max = 1 reaches the light (up to the rounding of
// light - sample).
SHADOWCTS_HD inline ShadowRay segment_to_point_light(const glm::vec3& sample,
                                                     const glm::vec3& light) {
  ShadowRay ray;
  ray.origin = sample;
  ray.direction = glm::vec3(rounded_sub(light.x, sample.x), rounded_sub(light.y, sample.y),
                            rounded_sub(light.z, sample.z));
  ray.t_max = 1.0f;
  return ray;
}

// Ray from a view sample towards a directional light (towards_light: from the scene to the light).
SHADOWCTS_HD inline ShadowRay ray_to_directional_light(const glm::vec3& sample,
                                                       const glm::vec3& towards_light) {
  ShadowRay ray;
  ray.origin = sample;
  ray.direction = towards_light;
  ray.t_max = INFINITY;
  return ray;
}

SHADOWCTS_HD inline float component(const glm::vec3& v, int axis) {
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

// A ray prepared once for many triangles: kz is the axis of the largest direction component, and
// (x, y) -= shear * z, z *= scale_z maps the direction onto (0, 0, 1).
struct RaySpace {
  glm::vec3 origin{0.0f};
  int kx = 0, ky = 1, kz = 2;
  float shear_x = 0.0f, shear_y = 0.0f, scale_z = 0.0f;
  float t_max = 0.0f;
  bool zero_direction = true;  // a zero-length direction hits nothing
};

SHADOWCTS_HD inline RaySpace make_ray_space(const ShadowRay& ray) {
  RaySpace space;
  space.origin = ray.origin;
  space.t_max = ray.t_max;
  const float ax = std::fabs(ray.direction.x), ay = std::fabs(ray.direction.y),
              az = std::fabs(ray.direction.z);
  space.kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
  space.kx = (space.kz + 1) % 3;
  space.ky = (space.kx + 1) % 3;
  const float dz = component(ray.direction, space.kz);
  if (dz == 0.0f) return space;  // all components are zero
  space.zero_direction = false;
  if (dz < 0.0f) {
    // Keep the handedness of the (x, y) plane, so a triangle's winding keeps its sign.
    const int swap = space.kx;
    space.kx = space.ky;
    space.ky = swap;
  }
  space.shear_x = rounded_div(component(ray.direction, space.kx), dz);
  space.shear_y = rounded_div(component(ray.direction, space.ky), dz);
  space.scale_z = rounded_div(1.0f, dz);
  return space;
}

struct RaySpaceVertex {
  float x, y, z;
};

SHADOWCTS_HD inline RaySpaceVertex to_ray_space(const RaySpace& space, const glm::vec3& v) {
  const float rx = rounded_sub(component(v, space.kx), component(space.origin, space.kx));
  const float ry = rounded_sub(component(v, space.ky), component(space.origin, space.ky));
  const float rz = rounded_sub(component(v, space.kz), component(space.origin, space.kz));
  return {rounded_sub(rx, rounded_mul(space.shear_x, rz)),
          rounded_sub(ry, rounded_mul(space.shear_y, rz)), rounded_mul(space.scale_z, rz)};
}

// Edge function of the directed 2D edge p -> q at the origin, as the two products whose difference
// it is: q.x * p.y - q.y * p.x. Reversing the edge swaps the products, so a shared edge gets
// exactly opposite values in its two triangles.
struct EdgeProducts {
  float first, second;
};

// A float product keeps float's relative rounding: it is finite, and normal unless a factor is
// zero (then it is an exact zero). Below the normal range its error is absolute, up to 2^-150.
SHADOWCTS_HD inline bool faithful_product(float a, float b, float product) {
  const float magnitude = std::fabs(product);
  return magnitude <= FLT_MAX && (magnitude >= FLT_MIN || a == 0.0f || b == 0.0f);
}

// rounded_mul that clears `faithful` when a float product leaves the normal range (double's range
// holds every product of float-range lengths, so double products are always faithful).
template <typename Real>
SHADOWCTS_HD inline Real checked_mul(Real a, Real b, bool& faithful) {
  const Real product = rounded_mul(a, b);
  if constexpr (std::is_same_v<Real, float>) faithful = faithful && faithful_product(a, b, product);
  return product;
}

SHADOWCTS_HD inline EdgeProducts edge_products(const RaySpaceVertex& p, const RaySpaceVertex& q,
                                               bool& faithful) {
  return {checked_mul(q.x, p.y, faithful), checked_mul(q.y, p.x, faithful)};
}

SHADOWCTS_HD inline double exact_edge_function(const RaySpaceVertex& p, const RaySpaceVertex& q) {
  // Both products are exact in double, so the one rounding of the difference keeps its sign.
  return rounded_sub(exact_product(q.x, p.y), exact_product(q.y, p.x));
}

// Given the edge functions u, v, w (weights of vertices a, b, c, all scaled by det) and the
// ray-space depths of the vertices: is the origin in the closed triangle at t in (0, t_max]?
// `faithful` is cleared when a float product left the normal range (the answer is then unsure).
template <typename Real>
SHADOWCTS_HD inline bool closed_hit_in_range(Real u, Real v, Real w, Real a_z, Real b_z, Real c_z,
                                             Real t_max, bool& faithful) {
  const Real zero = 0;
  const bool has_negative = u < zero || v < zero || w < zero;
  const bool has_positive = u > zero || v > zero || w > zero;
  if (has_negative && has_positive) return false;
  // u, v, w share a sign, so det is zero only if all three are: a triangle seen edge-on.
  const Real det = rounded_add(rounded_add(u, v), w);
  if (det == zero) return false;
  const Real t_scaled =
      rounded_add(rounded_add(checked_mul(u, a_z, faithful), checked_mul(v, b_z, faithful)),
                  checked_mul(w, c_z, faithful));
  // A sum that overflows is caught here; one whose result is subnormal is exact.
  if constexpr (std::is_same_v<Real, float>)
    faithful = faithful && std::fabs(det) <= FLT_MAX && std::fabs(t_scaled) <= FLT_MAX;
  // t = t_scaled / det, compared without dividing (an infinite t_max takes every t > 0).
  const Real t_limit = t_max == Real(INFINITY) ? t_max : checked_mul(t_max, det, faithful);
  if (det > zero) return t_scaled > zero && t_scaled <= t_limit;
  return t_scaled < zero && t_scaled >= (t_max == Real(INFINITY) ? -t_limit : t_limit);
}

SHADOWCTS_HD inline bool ray_hits_triangle(const RaySpace& space, const glm::vec3& v0,
                                           const glm::vec3& v1, const glm::vec3& v2) {
  if (space.zero_direction) return false;
  const RaySpaceVertex a = to_ray_space(space, v0);
  const RaySpaceVertex b = to_ray_space(space, v1);
  const RaySpaceVertex c = to_ray_space(space, v2);
  bool faithful = true;
  const EdgeProducts u = edge_products(b, c, faithful);
  const EdgeProducts v = edge_products(c, a, faithful);
  const EdgeProducts w = edge_products(a, b, faithful);
  bool hit = false;
  if (faithful && u.first != u.second && v.first != v.second && w.first != w.second) {
    // Distinct rounded products order like the exact ones: every sign below is exact.
    hit = closed_hit_in_range(rounded_sub(u.first, u.second), rounded_sub(v.first, v.second),
                              rounded_sub(w.first, w.second), a.z, b.z, c.z, space.t_max, faithful);
  }
  if (!faithful || u.first == u.second || v.first == v.second || w.first == w.second) {
    // An edge function that is zero in float may be a tiny nonzero value, and a product outside
    // float's normal range lost its precision: decide all in double.
    bool unused = true;
    hit = closed_hit_in_range(exact_edge_function(b, c), exact_edge_function(c, a),
                              exact_edge_function(a, b), static_cast<double>(a.z),
                              static_cast<double>(b.z), static_cast<double>(c.z),
                              static_cast<double>(space.t_max), unused);
  }
  // The rounded transform can give a collinear triangle a sliver of area; only a hit pays for the
  // exact check.
  return hit && !triangle_has_zero_area(v0, v1, v2);
}

// Whether the ray passes within the rounding of the ray-space transform of an edge of the
// triangle. The transform rounds each vertex on its own, by at most about 2^-22 of its distance
// from the ray origin (per coordinate): triangles that share vertices move together, so shared
// edges stay watertight, but where a vertex lies on another triangle's edge (a T-junction) a crack
// that narrow can open. Away from the edges (false) the answer above is that of the exact
// vertices; near one, a host caller with exact predicates can decide again.
SHADOWCTS_HD inline bool ray_near_triangle_edge(const RaySpace& space, const glm::vec3& v0,
                                                const glm::vec3& v1, const glm::vec3& v2) {
  if (space.zero_direction) return false;
  const RaySpaceVertex a = to_ray_space(space, v0);
  const RaySpaceVertex b = to_ray_space(space, v1);
  const RaySpaceVertex c = to_ray_space(space, v2);
  // Bound on a vertex's distance from the ray origin in the x, y plane and along the ray, before
  // the scale of z: its coordinates move by at most 2^-22 of it.
  const auto extent = [&](const glm::vec3& v, const RaySpaceVertex& r) {
    return double(std::fabs(r.x)) + double(std::fabs(r.y)) +
           double(
               std::fabs(rounded_sub(component(v, space.kz), component(space.origin, space.kz))));
  };
  const double na = extent(v0, a), nb = extent(v1, b), nc = extent(v2, c);
  // An edge function p.y q.x - p.x q.y moves by at most about 2^-20 n_p n_q: 2^-16 leaves room.
  return std::fabs(exact_edge_function(b, c)) <= 0x1p-16 * nb * nc ||
         std::fabs(exact_edge_function(c, a)) <= 0x1p-16 * nc * na ||
         std::fabs(exact_edge_function(a, b)) <= 0x1p-16 * na * nb;
}

// Whether some vertex of the triangle lies along the segment to a point light within its last
// sixteenth or beyond (ray-space depth >= 15/16 t_max): then a crossing may lie within rounding of
// the light, where the float segment's end (p + (L - p) rounded) and the float depths can take it
// or leave it either way, and the band cannot tell (moving p barely moves the segment's light
// end). Farther from the light a float hit beside an edge moves with p, and the band covers it.
// Never for a directional light (its ray has no end).
SHADOWCTS_HD inline bool triangle_reaches_light_end(const RaySpace& space, const glm::vec3& v0,
                                                    const glm::vec3& v1, const glm::vec3& v2) {
  if (space.zero_direction || !(space.t_max < INFINITY)) return false;
  const float reach = space.t_max * 0.9375f;
  return to_ray_space(space, v0).z >= reach || to_ray_space(space, v1).z >= reach ||
         to_ray_space(space, v2).z >= reach;
}

SHADOWCTS_HD inline bool ray_hits_triangle(const ShadowRay& ray, const glm::vec3& v0,
                                           const glm::vec3& v1, const glm::vec3& v2) {
  return ray_hits_triangle(make_ray_space(ray), v0, v1, v2);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts
