// The shared host/device segment/triangle test, run on the host: watertightness on shared edges
// and vertices, closed triangles, zero-area triangles, segment end limits, directional rays, and
// agreement with a double-precision reference away from edges.
#include "shadowcts/geometry/segment_triangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace shadowcts {
namespace {

struct TestTriangle {
  glm::vec3 a, b, c;
};

bool hits(const ShadowRay& ray, const TestTriangle& t) {
  return ray_hits_triangle(ray, t.a, t.b, t.c);
}

int hit_count(const ShadowRay& ray, const std::vector<TestTriangle>& mesh) {
  const RaySpace space = make_ray_space(ray);
  int count = 0;
  for (const TestTriangle& t : mesh) count += ray_hits_triangle(space, t.a, t.b, t.c) ? 1 : 0;
  return count;
}

ShadowRay ray_through(const glm::vec3& origin, const glm::vec3& target, float t_max) {
  ShadowRay ray;
  ray.origin = origin;
  ray.direction = target - origin;  // rounded in float: the ray passes near target, not through it
  ray.t_max = t_max;
  return ray;
}

glm::vec3 lerp_in_float(const glm::vec3& a, const glm::vec3& b, float s) {
  return a + s * (b - a);
}

// A fan of triangles around `centre` through the ring vertices, all with dyadic coordinates.
std::vector<TestTriangle> fan(const glm::vec3& centre, const std::vector<glm::vec3>& ring) {
  std::vector<TestTriangle> triangles;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    triangles.push_back({centre, ring[i], ring[(i + 1) % ring.size()]});
  }
  return triangles;
}

// An irregular octagon fan; `height` lifts the centre into a shallow pyramid.
std::vector<glm::vec3> irregular_ring(const glm::vec3& offset, float scale) {
  const std::array<glm::vec3, 8> unit = {
      glm::vec3(1.0f, 0.125f, 0.0f),       glm::vec3(0.75f, 0.6875f, 0.0625f),
      glm::vec3(-0.0625f, 1.125f, 0.0f),   glm::vec3(-0.8125f, 0.5625f, -0.0625f),
      glm::vec3(-1.0625f, -0.1875f, 0.0f), glm::vec3(-0.5f, -0.875f, 0.03125f),
      glm::vec3(0.125f, -0.9375f, 0.0f),   glm::vec3(0.6875f, -0.625f, -0.03125f)};
  std::vector<glm::vec3> ring;
  for (const glm::vec3& v : unit) ring.push_back(offset + scale * v);
  return ring;
}

// Rays aimed at points of the interior edges (computed in float, so up to rounding off the edge)
// and at the centre vertex, from both sides of the fan: every one must hit the fan.
void expect_fan_is_watertight(const glm::vec3& offset, float scale, float centre_height) {
  const std::vector<glm::vec3> ring = irregular_ring(offset, scale);
  const glm::vec3 centre = offset + scale * glm::vec3(0.0625f, -0.03125f, centre_height);
  const std::vector<TestTriangle> triangles = fan(centre, ring);
  std::mt19937_64 random(0x5eed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> along(0.0f, 0.98f);
  std::uniform_int_distribution<std::size_t> edge(0, ring.size() - 1);
  int leaks = 0, rays = 0;
  for (int i = 0; i < 60000; ++i) {
    // Origins well above or below the fan, so that no fan edge is a silhouette edge.
    const float side = i % 2 == 0 ? 1.0f : -1.0f;
    const glm::vec3 origin = offset + scale * glm::vec3(0.5f * unit(random), 0.5f * unit(random),
                                                        side * (3.0f + 2.0f * unit(random)));
    const glm::vec3 target =
        i % 16 == 0 ? centre : lerp_in_float(centre, ring[edge(random)], along(random));
    ++rays;
    if (hit_count(ray_through(origin, target, 2.0f), triangles) == 0) ++leaks;
  }
  EXPECT_EQ(leaks, 0) << "of " << rays << " rays through shared edges and the shared vertex";
}

TEST(SegmentTriangle, PlanarFanIsWatertightOnSharedEdgesAndVertex) {
  expect_fan_is_watertight(glm::vec3(0.0f), 1.0f, 0.0f);
}

TEST(SegmentTriangle, PyramidFanIsWatertightOnSharedEdgesAndVertex) {
  expect_fan_is_watertight(glm::vec3(0.0f), 1.0f, 0.25f);
}

TEST(SegmentTriangle, FarFromOriginFanIsWatertight) {
  // Large coordinates make every rounding step coarse relative to the fan.
  expect_fan_is_watertight(glm::vec3(1536.0f, -3072.5f, 768.25f), 0.75f, 0.125f);
}

// A closed octahedron with irregular dyadic vertices: a ray leaving from inside must cross it,
// however close to an edge or vertex it passes.
TEST(SegmentTriangle, RaysFromInsideClosedOctahedronAlwaysHit) {
  const std::array<glm::vec3, 6> v = {
      glm::vec3(1.25f, 0.125f, -0.0625f),   glm::vec3(-0.875f, 0.0625f, 0.125f),
      glm::vec3(0.0625f, 1.125f, -0.125f),  glm::vec3(0.125f, -0.9375f, 0.0625f),
      glm::vec3(-0.0625f, 0.125f, 1.0625f), glm::vec3(0.0625f, -0.125f, -0.8125f)};
  std::vector<TestTriangle> octahedron;
  const std::array<int, 2> x_axis = {0, 1}, y_axis = {2, 3}, z_axis = {4, 5};
  for (int x : x_axis)
    for (int y : y_axis)
      for (int z : z_axis) octahedron.push_back({v[x], v[y], v[z]});
  std::vector<std::array<int, 2>> edges;
  for (int x : x_axis)
    for (int y : y_axis) edges.push_back({x, y});
  for (int y : y_axis)
    for (int z : z_axis) edges.push_back({y, z});
  for (int z : z_axis)
    for (int x : x_axis) edges.push_back({z, x});

  std::mt19937_64 random(7);
  std::uniform_real_distribution<float> inside(-0.125f, 0.125f);
  std::uniform_real_distribution<float> along(0.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick_edge(0, edges.size() - 1);
  std::uniform_int_distribution<std::size_t> pick_vertex(0, v.size() - 1);
  int leaks = 0;
  for (int i = 0; i < 60000; ++i) {
    const glm::vec3 origin(inside(random), inside(random), inside(random));
    const std::array<int, 2> e = edges[pick_edge(random)];
    const glm::vec3 target =
        i % 8 == 0 ? v[pick_vertex(random)] : lerp_in_float(v[e[0]], v[e[1]], along(random));
    if (hit_count(ray_through(origin, target, INFINITY), octahedron) == 0) ++leaks;
  }
  EXPECT_EQ(leaks, 0);
}

// Exact dyadic constructions: a ray that meets a shared edge or vertex exactly hits every triangle
// that contains the point, because triangles are closed.
TEST(SegmentTriangle, ExactHitOnSharedEdgeHitsBothTriangles) {
  const glm::vec3 p00(0.0f), p10(2.0f, 0.0f, 0.0f), p11(2.0f, 2.0f, 0.0f), p01(0.0f, 2.0f, 0.0f);
  const TestTriangle lower{p00, p10, p11}, upper{p00, p11, p01};
  const std::array<glm::vec3, 4> edge_points = {glm::vec3(0.75f, 0.75f, 0.0f),
                                                glm::vec3(1.5f, 1.5f, 0.0f),
                                                glm::vec3(0.015625f, 0.015625f, 0.0f), p11};
  const std::array<glm::vec3, 4> offsets = {
      glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.5f, -0.25f, 1.0f), glm::vec3(-0.125f, 0.375f, -2.0f),
      glm::vec3(1.0f, 0.5f, 0.25f)};
  for (const glm::vec3& point : edge_points) {
    for (const glm::vec3& offset : offsets) {
      // origin - t * offset reaches the point exactly at t = 1.
      const ShadowRay ray{point + offset, -offset, 4.0f};
      EXPECT_TRUE(hits(ray, lower)) << point.x << " " << offset.x;
      EXPECT_TRUE(hits(ray, upper)) << point.x << " " << offset.x;
    }
  }
}

TEST(SegmentTriangle, ExactHitOnSharedVertexHitsEveryFanTriangle) {
  const glm::vec3 centre(0.25f, -0.5f, 0.0f);
  const std::vector<TestTriangle> triangles =
      fan(centre, irregular_ring(glm::vec3(0.25f, -0.5f, 0.0f), 1.0f));
  for (const glm::vec3& offset : {glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.25f, 0.125f, 0.5f),
                                  glm::vec3(-0.5f, 0.25f, -1.0f)}) {
    const ShadowRay ray{centre + offset, -offset, 1.0f};
    EXPECT_EQ(hit_count(ray, triangles), static_cast<int>(triangles.size()));
  }
}

TEST(SegmentTriangle, EdgesAndVerticesAreClosedAndOneUlpOutsideMisses) {
  const TestTriangle t{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
  const glm::vec3 down(0.0f, 0.0f, -2.0f);
  auto hits_at = [&](float x, float y) { return hits(ShadowRay{{x, y, 1.0f}, down, 1.0f}, t); };
  EXPECT_TRUE(hits_at(0.0f, 0.0f));
  EXPECT_TRUE(hits_at(1.0f, 0.0f));
  EXPECT_TRUE(hits_at(0.0f, 1.0f));
  EXPECT_TRUE(hits_at(0.5f, 0.5f));   // hypotenuse
  EXPECT_TRUE(hits_at(0.25f, 0.0f));  // bottom edge
  EXPECT_TRUE(hits_at(0.0f, 0.75f));  // left edge
  EXPECT_FALSE(hits_at(0.25f, -std::numeric_limits<float>::denorm_min()));
  EXPECT_FALSE(hits_at(-std::numeric_limits<float>::denorm_min(), 0.75f));
  EXPECT_FALSE(hits_at(std::nextafter(0.5f, 1.0f), 0.5f));
  EXPECT_FALSE(hits_at(std::nextafter(1.0f, 2.0f), 0.0f));
}

TEST(SegmentTriangle, EdgeFunctionBelowFloatResolutionIsDecidedExactly) {
  // The vertical ray through the origin passes 2^-25 off the shared edge a-b: the two products of
  // its edge function are -1 and -(1 + 2^-24 - 2^-47), equal in float. Exactly one of the two
  // triangles on either side of the edge contains the ray.
  const glm::vec3 a(1.0f + 0x1p-23f, 1.0f, 0.0f), b(-1.0f, -(1.0f - 0x1p-24f), 0.0f);
  const glm::vec3 above(-1.0f, 1.0f, 0.0f), below(1.0f, -1.0f, 0.0f);
  for (const float z : {1.0f, -1.0f}) {
    const ShadowRay ray{{0.0f, 0.0f, z}, {0.0f, 0.0f, -2.0f * z}, 1.0f};
    EXPECT_NE(ray_hits_triangle(ray, a, b, above), ray_hits_triangle(ray, a, b, below)) << z;
    EXPECT_NE(ray_hits_triangle(ray, b, a, above), ray_hits_triangle(ray, b, a, below)) << z;
  }
}

TEST(SegmentTriangle, BothWindingsHit) {
  const glm::vec3 a(0.0f), b(1.0f, 0.0f, 0.0f), c(0.0f, 1.0f, 0.0f);
  for (const float z : {1.0f, -1.0f}) {
    const ShadowRay ray{{0.25f, 0.25f, z}, {0.0f, 0.0f, -2.0f * z}, 1.0f};
    EXPECT_TRUE(ray_hits_triangle(ray, a, b, c));
    EXPECT_TRUE(ray_hits_triangle(ray, a, c, b));
  }
}

TEST(SegmentTriangle, ZeroAreaTrianglesNeverHit) {
  const glm::vec3 a(-0.5f, 0.25f, 0.125f), b(1.5f, 0.75f, -0.375f);
  const glm::vec3 midpoint = 0.5f * (a + b);  // exact: dyadic
  const glm::vec3 beyond = a + 3.0f * (b - a);
  const std::vector<TestTriangle> degenerate = {{a, b, midpoint}, {a, midpoint, b}, {a, b, beyond},
                                                {a, a, b},        {a, b, b},        {a, a, a}};
  std::mt19937_64 random(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> along(0.0f, 1.0f);
  for (const TestTriangle& t : degenerate) {
    int false_hits = 0;
    for (int i = 0; i < 5000; ++i) {
      const glm::vec3 origin(4.0f * unit(random), 4.0f * unit(random), 4.0f * unit(random));
      const glm::vec3 target = i % 10 == 0 ? a : lerp_in_float(a, b, along(random));
      false_hits += hits(ray_through(origin, target, 2.0f), t) ? 1 : 0;
    }
    EXPECT_EQ(false_hits, 0);
  }
  // Exactly through the segment: the edge functions are exactly zero.
  const ShadowRay exact{midpoint + glm::vec3(0.0f, 0.0f, 1.0f), {0.0f, 0.0f, -2.0f}, 1.0f};
  for (const TestTriangle& t : degenerate) EXPECT_FALSE(hits(exact, t));
}

TEST(SegmentTriangle, RandomCollinearFloatTrianglesNeverHit) {
  // Collinear by construction with exact float arithmetic: small integers times a power of two.
  std::mt19937_64 random(13);
  std::uniform_int_distribution<int> coordinate(-4096, 4096);
  std::uniform_int_distribution<int> step(-64, 64);
  std::uniform_int_distribution<int> multiple(-8, 8);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::uniform_real_distribution<float> along(0.0f, 1.0f);
  const float grid = 1.0f / 1024.0f;
  int false_hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 a =
        grid * glm::vec3(coordinate(random), coordinate(random), coordinate(random));
    const glm::vec3 d = grid * glm::vec3(step(random), step(random), step(random));
    const glm::vec3 b = a + static_cast<float>(multiple(random)) * d;
    const glm::vec3 c = a + static_cast<float>(multiple(random)) * d;
    ASSERT_TRUE(triangle_has_zero_area(a, b, c));
    const glm::vec3 origin = a + glm::vec3(unit(random), unit(random), unit(random));
    false_hits += hits(ray_through(origin, lerp_in_float(b, c, along(random)), 2.0f), {a, b, c});
  }
  EXPECT_EQ(false_hits, 0);
}

TEST(SegmentTriangle, SegmentEndsAtTheLight) {
  // Triangle in the plane z = 0, sample below it, point light above or below it.
  const TestTriangle t{glm::vec3(-1.0f, -1.0f, 0.0f), glm::vec3(1.0f, -1.0f, 0.0f),
                       glm::vec3(0.0f, 1.0f, 0.0f)};
  const glm::vec3 sample(0.125f, 0.0625f, -1.0f);
  auto shadowed_by = [&](const glm::vec3& from, float light_z) {
    return hits(segment_to_point_light(from, glm::vec3(0.25f, -0.125f, light_z)), t);
  };
  const float tiny = std::ldexp(1.0f, -20);
  EXPECT_TRUE(shadowed_by(sample, 1.0f));
  EXPECT_TRUE(shadowed_by(sample, tiny));    // light just behind the triangle
  EXPECT_TRUE(shadowed_by(sample, 0.0f));    // light on the triangle: t = 1 is included
  EXPECT_FALSE(shadowed_by(sample, -tiny));  // light just in front of the triangle
  EXPECT_FALSE(shadowed_by(sample, -0.5f));
  // The sample itself on the triangle: t = 0 is excluded.
  EXPECT_FALSE(shadowed_by(glm::vec3(0.125f, 0.0625f, 0.0f), 1.0f));
  EXPECT_TRUE(shadowed_by(glm::vec3(0.125f, 0.0625f, -tiny), 1.0f));
  // Light on the far side, triangle behind the sample.
  EXPECT_FALSE(
      hits(segment_to_point_light(glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 0.0f, 5.0f)), t));
  // A zero-length segment hits nothing.
  EXPECT_FALSE(hits(segment_to_point_light(sample, sample), t));
}

TEST(SegmentTriangle, DirectionalRaysReachAnyDistanceAhead) {
  const glm::vec3 towards_light = glm::normalize(glm::vec3(0.25f, -0.5f, 1.0f));
  const glm::vec3 sample(0.0f);
  auto triangle_around = [&](float t) {
    const glm::vec3 centre = sample + t * towards_light;
    return TestTriangle{centre + glm::vec3(-1.0f, -1.0f, 0.0f) * std::max(1.0f, t * 1e-3f),
                        centre + glm::vec3(1.0f, -1.0f, 0.0f) * std::max(1.0f, t * 1e-3f),
                        centre + glm::vec3(0.0f, 1.0f, 0.0f) * std::max(1.0f, t * 1e-3f)};
  };
  const ShadowRay ray = ray_to_directional_light(sample, towards_light);
  EXPECT_TRUE(std::isinf(ray.t_max));
  for (const float t : {0.5f, 10.0f, 1e4f, 1e7f}) {
    EXPECT_TRUE(hits(ray, triangle_around(t))) << t;
    EXPECT_FALSE(hits(ray, triangle_around(-t))) << t;
  }
}

// Straightforward double-precision reference (Möller-Trumbore), trusted only where the ray is far
// from the triangle's edges and from both ends of the segment.
struct ReferenceAnswer {
  bool decisive;
  bool hit;
};

// `t_unit`: the length of t = 1 in scene units where t is a distance (a unit-length direction in a
// scene scaled by t_unit); t along a segment is a fraction.
ReferenceAnswer reference_hit(const ShadowRay& ray, const TestTriangle& t, double t_unit = 1.0) {
  const glm::dvec3 o(ray.origin), d(ray.direction), a(t.a), b(t.b), c(t.c);
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  const double margin = 1e-3;
  if (std::abs(det) < margin * glm::length(d) * glm::length(glm::cross(e1, e2))) {
    return {false, false};  // grazing
  }
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  const double w = 1.0 - u - v;
  const double t_hit = glm::dot(e2, q) / det;
  const double edge_distance = std::min({u, v, w});
  if (std::abs(edge_distance) < margin || std::abs(t_hit) < margin * t_unit) return {false, false};
  if (!std::isinf(ray.t_max) && std::abs(t_hit - ray.t_max) < margin) return {false, false};
  return {true, edge_distance > 0.0 && t_hit > 0.0 && t_hit <= ray.t_max};
}

// Positions scaled by 2^k (exact for these coordinates at every k used).
glm::vec3 scaled(const glm::vec3& v, int k) {
  return {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
}

void expect_matches_reference(bool directional, int k = 0) {
  SCOPED_TRACE("scaled by 2^" + std::to_string(k));
  std::mt19937_64 random(directional ? 17 : 19);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int decisive = 0, hits_seen = 0, mismatches = 0;
  for (int i = 0; i < 40000; ++i) {
    const TestTriangle t{{unit(random), unit(random), unit(random)},
                         {unit(random), unit(random), unit(random)},
                         {unit(random), unit(random), unit(random)}};
    const glm::vec3 sample(2.0f * unit(random), 2.0f * unit(random), 2.0f * unit(random));
    // Aim near the triangle so that hits are common.
    const glm::vec3 target =
        (t.a + t.b + t.c) / 3.0f + glm::vec3(unit(random), unit(random), unit(random)) * 0.5f;
    // The light before, near or beyond the triangle.
    const glm::vec3 light = sample + (1.25f + unit(random)) * (target - sample);
    const TestTriangle scaled_triangle{scaled(t.a, k), scaled(t.b, k), scaled(t.c, k)};
    const ShadowRay ray =
        directional ? ray_to_directional_light(scaled(sample, k), glm::normalize(target - sample))
                    : segment_to_point_light(scaled(sample, k), scaled(light, k));
    const ReferenceAnswer expected =
        reference_hit(ray, scaled_triangle, directional ? std::ldexp(1.0, k) : 1.0);
    if (!expected.decisive) continue;
    ++decisive;
    hits_seen += expected.hit ? 1 : 0;
    mismatches += hits(ray, scaled_triangle) != expected.hit ? 1 : 0;
  }
  EXPECT_EQ(mismatches, 0);
  // The comparison must exercise both answers in quantity.
  EXPECT_GT(decisive, 20000);
  EXPECT_GT(hits_seen, 3000);
  EXPECT_GT(decisive - hits_seen, 3000);
}

TEST(SegmentTriangle, MatchesDoubleReferenceAwayFromEdgesForSegments) {
  expect_matches_reference(false);
}

TEST(SegmentTriangle, MatchesDoubleReferenceAwayFromEdgesForDirectionalRays) {
  expect_matches_reference(true);
}

// Float products of two or three lengths leave float's normal range in tiny and huge scenes
// (underflow below about 2^-40, overflow above about 2^42): the test must notice and decide in
// double, so that its answers do not depend on the scale.
TEST(SegmentTriangle, MatchesDoubleReferenceAtTinyAndHugeScales) {
  for (const int k : {-100, -60, -47, 47, 60, 100}) {
    expect_matches_reference(false, k);
    expect_matches_reference(true, k);
  }
}

// Found by fuzz_degenerate through the metric algorithm: a directional ray at a scene scale of
// about 2^-49 whose hit distance (a product of three lengths, ~2^-147) underflowed to zero in
// float, so the blocker was missed (a leak). The same ray hits at every scale.
TEST(SegmentTriangle, DirectionalHitAtTwoToTheMinus49IsNotLostToUnderflow) {
  const glm::vec3 direction(0.7071067690849304f, 0.7071067690849304f, 0.0f);
  const TestTriangle blocker{{-0x1.2p-50f, -0x1.54p-50f, -0x1.34p-50f},
                             {-0x1.24p-50f, -0x1.dcp-50f, -0x1.04p-50f},
                             {0x1.e8p-51f, -0x1p-56f, 0x1.a4p-50f}};
  const glm::vec3 sample(-0x1.7p-50f, -0x1.b4p-50f, -0x1.04p-50f);
  for (const int k : {-60, -20, 0, 20, 49, 90, 150}) {
    const TestTriangle t{scaled(blocker.a, k), scaled(blocker.b, k), scaled(blocker.c, k)};
    EXPECT_TRUE(hits(ray_to_directional_light(scaled(sample, k), direction), t)) << "2^" << k;
  }
}

}  // namespace
}  // namespace shadowcts
