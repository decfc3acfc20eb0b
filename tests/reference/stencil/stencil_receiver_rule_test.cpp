// The receiver half-space rule in the stencil count (reference/stencil/receiver_rule.h): float
// samples just below their receiver's plane beside a coplanar neighbour or the next face of a
// convex closed mesh are lit, while walls and a closed box standing on a floor shadow it.
// Hand-built samples are checked to be ones the rule decides (a caster meets their closed segment,
// but not strictly on the light's side), then both variants are compared with the exact oracle on
// every sample, robust or not.
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "oracles/exact_segment_triangle.h"
#include "reference/stencil/receiver_rule.h"
#include "reference/stencil/silhouette.h"
#include "reference/stencil/stencil_algorithm.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {
namespace {

using namespace stencil;

ShadowLight point_light(const glm::vec3& position) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = position;
  return light;
}

ShadowLight directional_light(const glm::vec3& direction) {
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = direction;
  return light;
}

Case base_case(const ShadowLight& light, const glm::vec3& eye) {
  Case c;
  c.name = "stencil_receiver_rule";
  c.source = "stencil_receiver_rule_test.cpp";
  c.light = light;
  c.camera.position = eye;
  c.camera.target = {0.0f, 0.0f, 0.0f};
  c.camera.near_plane = 0.01f;
  c.camera.far_plane = 1000.0f;
  return c;
}

std::uint32_t add_mesh(Case& c, const char* name, bool closed) {
  c.meshes.push_back(Mesh{name, closed, true});
  return std::uint32_t(c.meshes.size() - 1);
}

// An n x n grid of squares on [-half, half]^2 in the plane y = slope_x x + slope_z z, two
// triangles each, normals upwards. The grid's vertices lie exactly on the plane (the caller picks
// slopes and sizes that make them floats), so neighbours are exactly coplanar.
void add_floor(Case& c, float half, int n, float slope_x, float slope_z) {
  const std::uint32_t m = add_mesh(c, "floor", false);
  const auto vertex = [&](int i, int j) {
    const float x = -half + 2.0f * half * float(i) / float(n);
    const float z = -half + 2.0f * half * float(j) / float(n);
    return glm::vec3(x, slope_x * x + slope_z * z, z);
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const glm::vec3 a = vertex(i, j), b = vertex(i, j + 1), d = vertex(i + 1, j + 1),
                      e = vertex(i + 1, j);
      c.triangles.push_back({a, b, d, m});
      c.triangles.push_back({a, d, e, m});
    }
}

// A closed axis-aligned box with outward-facing triangles.
void add_box(Case& c, const glm::vec3& lo, const glm::vec3& hi) {
  const std::uint32_t m = add_mesh(c, "box", true);
  const glm::vec3 centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  for (int axis = 0; axis < 3; ++axis)
    for (const float sign : {1.0f, -1.0f}) {
      glm::vec3 u(0.0f), v(0.0f), n(0.0f);
      n[axis] = sign * half[axis];
      u[(axis + 1) % 3] = half[(axis + 1) % 3];
      v[(axis + 2) % 3] = half[(axis + 2) % 3];
      if (sign < 0) std::swap(u, v);  // keep u x v pointing out
      const glm::vec3 p00 = centre + n - u - v, p10 = centre + n + u - v, p11 = centre + n + u + v,
                      p01 = centre + n - u + v;
      c.triangles.push_back({p00, p10, p11, m});
      c.triangles.push_back({p00, p11, p01, m});
    }
}

// A sphere of radius 2 around `centre`: an octahedron subdivided twice (128 triangles), its
// vertices pushed out to the sphere and rounded to floats once, shared by index (closed).
void add_geodesic_sphere(Case& c, const glm::vec3& centre) {
  const std::uint32_t m = add_mesh(c, "sphere", true);
  std::vector<glm::dvec3> points = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  std::vector<glm::uvec3> faces = {{0, 2, 4}, {4, 2, 1}, {1, 2, 5}, {5, 2, 0},
                                   {4, 3, 0}, {1, 3, 4}, {5, 3, 1}, {0, 3, 5}};
  for (int level = 0; level < 2; ++level) {
    std::map<std::pair<unsigned, unsigned>, unsigned> middle;
    const auto mid = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      points.push_back(glm::normalize(points[a] + points[b]));
      return middle[key] = unsigned(points.size() - 1);
    };
    std::vector<glm::uvec3> finer;
    for (const glm::uvec3& f : faces) {
      const unsigned ab = mid(f.x, f.y), bc = mid(f.y, f.z), ca = mid(f.z, f.x);
      finer.insert(finer.end(), {{f.x, ab, ca}, {ab, f.y, bc}, {ca, bc, f.z}, {ab, bc, ca}});
    }
    faces = finer;
  }
  std::vector<glm::vec3> vertices;
  for (const glm::dvec3& p : points) vertices.push_back(centre + glm::vec3(2.0 * p));
  for (const glm::uvec3& f : faces)
    c.triangles.push_back({vertices[f.x], vertices[f.y], vertices[f.z], m});
}

geometry::ReceiverHalfSpace half_space(const Case& c, std::uint32_t receiver) {
  const HardShadowLight light = hard_shadow_light(c);
  const Triangle& r = c.triangles[receiver];
  return geometry::receiver_half_space(glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2),
                                       light.directional,
                                       light.directional ? light.direction : light.position);
}

glm::vec3 unit_normal(const Triangle& t) {
  return glm::vec3(glm::normalize(
      glm::cross(glm::dvec3(t.v1) - glm::dvec3(t.v0), glm::dvec3(t.v2) - glm::dvec3(t.v0))));
}

// Triangles i < j of the mesh that share an edge, with the edge.
struct SharedEdge {
  std::uint32_t i, j;
  glm::vec3 a, b;
};

std::vector<SharedEdge> shared_edges(const Case& c, std::uint32_t mesh) {
  std::vector<SharedEdge> edges;
  for (std::uint32_t i = 0; i < c.triangles.size(); ++i)
    for (std::uint32_t j = i + 1; j < c.triangles.size(); ++j) {
      if (c.triangles[i].mesh != mesh || c.triangles[j].mesh != mesh) continue;
      const glm::vec3 vi[3] = {c.triangles[i].v0, c.triangles[i].v1, c.triangles[i].v2};
      const glm::vec3 vj[3] = {c.triangles[j].v0, c.triangles[j].v1, c.triangles[j].v2};
      std::vector<glm::vec3> common;
      for (const glm::vec3& x : vi)
        for (const glm::vec3& y : vj)
          if (x == y) common.push_back(x);
      if (common.size() == 2) edges.push_back({i, j, common[0], common[1]});
    }
  return edges;
}

// Points along the shared edges, rounded to floats and then moved by whole ulps along `inwards`
// (one coordinate axis, signed) until they lie strictly behind the receiver's plane, away from
// the light: the first such float. Kept only where the neighbour meets the closed segment (ray)
// to the light, so that it would shadow the sample without the rule. Each becomes a sample with
// the receiver's normal, for both receivers of each edge.
ViewSamples samples_below_beside_edges(Case& c, std::uint32_t mesh, int axis, float direction) {
  const HardShadowLight light = hard_shadow_light(c);
  const ExactShadowPredicate predicate(light, 2.0 * c.scale());
  ViewSamples samples;
  for (const SharedEdge& e : shared_edges(c, mesh))
    for (const double t : {0.3183, 0.5, 0.7071})
      for (const auto& [receiver, neighbour] : {std::pair{e.i, e.j}, std::pair{e.j, e.i}}) {
        const geometry::ReceiverHalfSpace h = half_space(c, receiver);
        if (h.light_side == 0) continue;
        glm::vec3 p = glm::vec3(glm::dvec3(e.a) + t * (glm::dvec3(e.b) - glm::dvec3(e.a)));
        int steps = 0;
        while (geometry::light_side_of(h, glm::dvec3(p)) >= 0 && steps++ < 64)
          p[axis] = std::nextafter(p[axis], direction * INFINITY);
        if (geometry::light_side_of(h, glm::dvec3(p)) >= 0) continue;
        MovedPoint moved;
        moved.base = glm::dvec3(p);
        if (!predicate.blocks(c.triangles[neighbour], moved)) continue;
        ViewSample s;
        s.position = p;
        s.normal = unit_normal(c.triangles[receiver]);
        s.receiver = receiver;
        s.pixel_x = std::uint32_t(samples.samples.size());
        s.sample_class = SampleClass::regular;  // re-derived by the caller
        samples.samples.push_back(s);
      }
  samples.width = std::uint32_t(samples.samples.size());
  samples.height = 1;
  c.camera.width = samples.width;
  c.camera.height = 1;
  return samples;
}

std::uint64_t counter(const AlgorithmOutput& output, const std::string& name) {
  for (const auto& [key, value] : output.counters)
    if (key == name) return value;
  ADD_FAILURE() << "no counter " << name;
  return 0;
}

// Both variants give the exact answer on every regular sample; returns the truth. The eye must
// be outside every shadow volume (z-pass assumes it).
HardShadowTruth expect_exact_on_every_sample(const Case& c, ViewSamples& samples,
                                             std::uint64_t* rule_samples = nullptr) {
  validate(c);
  classify_samples(c, samples, c.name);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  const auto stencil = make_stencil();
  for (const char* variant : {"zfail", "zpass"}) {
    EXPECT_FALSE(stencil->unsupported_reason(c, samples, variant));
    const AlgorithmOutput output = stencil->run(c, samples, variant);
    const HardShadowComparison h = compare_hard_shadows(output.shadowed, truth);
    EXPECT_EQ(h.leaks, 0u) << variant;
    EXPECT_EQ(h.false_shadows, 0u) << variant;
    EXPECT_EQ(h.ambiguous_disagreements, 0u) << variant;
    if (rule_samples) *rule_samples = counter(output, "rule_samples");
  }
  return truth;
}

// The hand-built samples: all regular and all lit, although their neighbour meets their closed
// segment (samples_below_beside_edges).
void expect_all_lit(const Case& c, ViewSamples& samples, std::size_t at_least) {
  ASSERT_GE(samples.samples.size(), at_least);
  std::uint64_t asked = 0;
  const HardShadowTruth truth = expect_exact_on_every_sample(c, samples, &asked);
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    ASSERT_EQ(samples.samples[i].sample_class, SampleClass::regular) << i;
    EXPECT_EQ(truth.shadowed[i], 0) << i;
  }
  // Without the rule the count calls almost all of them shadowed (not all: where the segment
  // meets the neighbour only on its boundary, the count's perturbation may leave it out).
  EXPECT_GE(10 * asked, 9 * samples.samples.size());
}

// (1) A tessellated tilted floor (exactly planar), its samples one ulp below the plane beside a
// coplanar neighbour that meets their segment to the point light; also scaled by 2^-60 and 2^60
// (exactly: every predicate keeps its sign), where the reject box's bounds must still hold.
Case scaled_floor_case(const ShadowLight& light, float scale) {
  ShadowLight scaled = light;
  if (scaled.kind == ShadowLightKind::point) scaled.position *= scale;
  Case c = base_case(scaled, scale * glm::vec3(0.375f, 12.0f, 9.125f));
  c.camera.near_plane *= scale;
  c.camera.far_plane *= scale;
  add_floor(c, 4.0f * scale, 8, 0.5f, 0.25f);
  return c;
}

TEST(StencilReceiverRule, SamplesBelowATessellatedFloorBesideACoplanarNeighbourAreLit) {
  for (const float scale : {1.0f, 0x1p-60f, 0x1p60f}) {
    Case c = scaled_floor_case(point_light({1.25f, 9.5f, -0.75f}), scale);
    ViewSamples samples = samples_below_beside_edges(c, 0, 1, -1.0f);
    expect_all_lit(c, samples, 100);
  }
}

// (4) The same under a directional light.
TEST(StencilReceiverRule, SamplesBelowATessellatedFloorAreLitUnderADirectionalLight) {
  for (const float scale : {1.0f, 0x1p-60f, 0x1p60f}) {
    Case c = scaled_floor_case(directional_light({0.3125f, 1.0f, -0.1875f}), scale);
    ViewSamples samples = samples_below_beside_edges(c, 0, 1, -1.0f);
    expect_all_lit(c, samples, 100);
  }
}

// (2) A convex closed mesh (the silhouette path: one volume for its front caps): samples one ulp
// inside it beside an edge whose next face meets their segment, below the receiver's plane.
TEST(StencilReceiverRule, SamplesJustInsideAConvexClosedMeshBesideAnEdgeAreLit) {
  for (const ShadowLight& light :
       {point_light({6.5f, 13.0f, 4.25f}), directional_light({0.4375f, 1.0f, 0.3125f})}) {
    Case c = base_case(light, {-3.25f, 9.0f, 10.5f});
    add_geodesic_sphere(c, {0.0f, 3.0f, 0.0f});
    // Exactly convex: every vertex lies strictly inside every other face's plane.
    for (const Triangle& t : c.triangles)
      for (const Triangle& u : c.triangles)
        for (const glm::vec3& v : {u.v0, u.v1, u.v2})
          if (v != t.v0 && v != t.v1 && v != t.v2) {
            ASSERT_LT(geometry::orientation(glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2),
                                            glm::dvec3(v)),
                      0);
          }
    ASSERT_EQ(find_occluders(c, hard_shadow_light(c)).closed_meshes, 1u);
    // Inwards is downwards on the upper half: keep the edges of faces that face the light there.
    ViewSamples below = samples_below_beside_edges(c, 0, 1, -1.0f);
    ViewSamples samples;
    for (const ViewSample& s : below.samples)
      if (s.position.y > 3.5f && facing_sign(c.triangles[s.receiver], hard_shadow_light(c)) > 0) {
        samples.samples.push_back(s);
        samples.samples.back().pixel_x = std::uint32_t(samples.samples.size() - 1);
      }
    samples.width = c.camera.width = std::uint32_t(samples.samples.size());
    samples.height = c.camera.height = 1;
    expect_all_lit(c, samples, 20);
  }
}

// (2) The same mesh seen through the camera: rendered samples (float positions on and off the
// faces' planes) match the exact answer everywhere, and the lit side has no false shadows.
TEST(StencilReceiverRule, ARenderedConvexClosedMeshMatchesTheExactAnswer) {
  Case c = base_case(point_light({6.5f, 13.0f, 4.25f}), {-3.25f, 9.0f, 10.5f});
  c.camera.target = {0.0f, 3.0f, 0.0f};
  c.camera.vertical_fov_degrees = 30.0f;
  c.camera.width = c.camera.height = 96;
  add_geodesic_sphere(c, {0.0f, 3.0f, 0.0f});
  ViewSamples samples = generate_view_samples(c);
  const HardShadowTruth truth = expect_exact_on_every_sample(c, samples);
  std::size_t regular = 0, shadowed = 0;
  for (std::size_t i = 0; i < samples.samples.size(); ++i)
    if (samples.samples[i].sample_class == SampleClass::regular) {
      ++regular;
      shadowed += truth.shadowed[i];
    }
  EXPECT_GT(regular, 1000u);
  EXPECT_EQ(shadowed, 0u);  // a convex mesh never shadows its own lit side
}

// (3) A wall (open) and a closed box standing on a tessellated floor, and a ramp through it:
// rendered samples, and samples one ulp below the floor (or on it) right behind the wall's and the
// box's base and under the ramp (shadowed: the segment meets them strictly above the floor), right
// in front of the box's lit face and before the ramp (lit).
TEST(StencilReceiverRule, AWallAClosedBoxAndARampStandingOnTheFloorShadowIt) {
  for (const ShadowLight& light :
       {point_light({-8.0f, 6.0f, 0.5f}), directional_light({-1.0f, 0.75f, 0.0625f})}) {
    Case c = base_case(light, {2.5f, 7.0f, 9.0f});
    add_floor(c, 8.0f, 8, 0.0f, 0.0f);
    const std::uint32_t wall = add_mesh(c, "wall", false);
    c.triangles.push_back({{1, 0, -1}, {1, 0, 1}, {1, 2, 1}, wall});
    c.triangles.push_back({{1, 0, -1}, {1, 2, 1}, {1, 2, -1}, wall});
    add_box(c, {-3.0f, 0.0f, -1.0f}, {-1.5f, 1.5f, 1.0f});
    // A ramp leaning away from the light that dips through the floor (it crosses y = 0 at
    // x = 2 + 2 / 7), beside the wall's shadow: its box holds the floor samples under it, and it
    // straddles their plane.
    const std::uint32_t ramp = add_mesh(c, "ramp", false);
    c.triangles.push_back({{2, -0.5f, 3}, {2, -0.5f, 5}, {4, 3, 4}, ramp});
    ASSERT_EQ(find_occluders(c, hard_shadow_light(c)).closed_meshes, 1u);

    c.camera.width = c.camera.height = 64;
    ViewSamples rendered = generate_view_samples(c);
    const HardShadowTruth truth = expect_exact_on_every_sample(c, rendered);
    std::size_t robust_shadowed = 0, robust_lit = 0;
    for (BandClass b : truth.band) {
      robust_shadowed += b == BandClass::robust_shadowed;
      robust_lit += b == BandClass::robust_lit;
    }
    EXPECT_GT(robust_shadowed, 100u);
    EXPECT_GT(robust_lit, 100u);

    // Receivers: the floor triangle under each point (the floor's cells are 2 x 2).
    const auto floor_triangle = [&](float x, float z) {
      for (std::uint32_t i = 0; i < 128; ++i) {  // the floor
        const Triangle& t = c.triangles[i];
        const glm::dvec3 a(t.v0), b(t.v1), d(t.v2), up(0, 1, 0), q(x, 0, z);
        const int s0 = geometry::orientation(a, b, a + up, q),
                  s1 = geometry::orientation(b, d, b + up, q),
                  s2 = geometry::orientation(d, a, d + up, q);
        if ((s0 <= 0 && s1 <= 0 && s2 <= 0) || (s0 >= 0 && s1 >= 0 && s2 >= 0)) return i;
      }
      return std::uint32_t(0);
    };
    const float below = -0x1p-149f;  // one ulp below the floor's plane y = 0
    const std::pair<glm::vec3, int> hand[] = {
        {{std::nextafter(1.0f, 2.0f), below, 0.125f}, 1},    // behind the wall's base
        {{std::nextafter(1.0f, 2.0f), 0.0f, -0.375f}, 1},    // the same, on the plane
        {{std::nextafter(-1.5f, 0.0f), below, 0.25f}, 1},    // behind the box's back face
        {{std::nextafter(-3.0f, -4.0f), below, 0.25f}, 0},   // before the box's lit face
        {{std::nextafter(-3.0f, -4.0f), 0.0f, -0.625f}, 0},  // the same, on the plane
        {{3.0f, below, 4.125f}, 1},                          // under the ramp
        {{3.0f, 0.0f, 3.75f}, 1},                            // the same, on the plane
        {{2.25f, below, 4.0f}, 0}};  // before the ramp, which is below the floor there
    ViewSamples samples;
    for (const auto& [position, expected] : hand) {
      ViewSample s;
      s.position = position;
      s.normal = {0, 1, 0};
      s.receiver = floor_triangle(position.x, position.z);
      s.pixel_x = std::uint32_t(samples.samples.size());
      s.sample_class = SampleClass::regular;  // re-derived below
      samples.samples.push_back(s);
    }
    samples.width = c.camera.width = std::uint32_t(samples.samples.size());
    samples.height = c.camera.height = 1;
    const HardShadowTruth hand_truth = expect_exact_on_every_sample(c, samples);
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      ASSERT_EQ(samples.samples[i].sample_class, SampleClass::regular) << i;
      EXPECT_EQ(hand_truth.shadowed[i], hand[i].second) << i;
    }
  }
}

// The reject box holds the part of the segment (ray) that is not strictly on the light's side:
// its end where the segment crosses the receiver's plane.
TEST(StencilReceiverRule, TheRejectBoxReachesThePlaneCrossing) {
  const glm::dvec3 a(0, 0, 0), b(0, 0, 1), d(1, 0, 0);  // the plane y = 0, light side y > 0
  const glm::dvec3 light(3, 1, 0);
  const geometry::ReceiverHalfSpace h = geometry::receiver_half_space(a, b, d, false, light);
  ASSERT_EQ(geometry::light_side_of(h, {0, 1, 0}), 1);
  const glm::dvec3 p(0, -0x1p-20, 0);  // the crossing is at x = 3 * 2^-20 / (1 + 2^-20)
  const RejectBox box = reject_box(h, p);
  ASSERT_TRUE(box.bounded);
  EXPECT_LE(box.lo.x, 0.0);
  EXPECT_GE(box.hi.x, 3.0 * 0x1p-20 / (1.0 + 0x1p-20));
  EXPECT_LE(box.hi.x, 4.0 * 0x1p-20);  // and not much more
  EXPECT_LE(box.lo.y, p.y);
  EXPECT_GE(box.hi.y, 0.0);
  // Directional: the ray p + t d crosses y = 0 at t = 2^-20 / 0.5.
  const glm::dvec3 towards(1, 0.5, 0);
  const RejectBox ray = reject_box(geometry::receiver_half_space(a, b, d, true, towards), p);
  ASSERT_TRUE(ray.bounded);
  EXPECT_GE(ray.hi.x, 2.0 * 0x1p-20);
  EXPECT_LE(ray.hi.x, 3.0 * 0x1p-20);
  // A light direction within rounding of the plane: no finite bound.
  EXPECT_FALSE(
      reject_box(geometry::receiver_half_space(a, b, d, true, {1, 0x1p-1074, 0}), p).bounded);
}

}  // namespace
}  // namespace shadowcts
