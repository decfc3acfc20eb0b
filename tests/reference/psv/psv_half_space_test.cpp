// The receiver half-space rule (DESIGN.md, "Cases and ground truth") in every psv query, on
// hand-built cases where float samples lie within an ulp of their receiver's plane beside shared
// edges: a coplanar neighbour or the next face of a convex closed mesh meets their segments only
// on the far side of the receiver's plane and must not shadow them, while a wall standing on the
// floor meets them above it and must. The expected masks come from an exact construction: every
// caster against every sample's segment with the shared exact predicates, with the rule, checked
// against the exact oracle; the same construction without the rule shows that the cases reach the
// rule (some segments do meet a neighbour).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "reference/psv/psv_algorithm.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts::psv {
namespace {

using glm::dvec3;
using testing::HandBuiltCase;

dvec3 exact(const glm::vec3& v) {
  return dvec3(v);
}

// Whether the closed triangle t meets the segment from p to the point light (the ray towards the
// directional light) in one point; a segment in t's plane is left out, as the rule leaves it out.
bool meets(const HardShadowLight& light, const dvec3& p, const Triangle& t) {
  const dvec3 v[3] = {exact(t.v0), exact(t.v1), exact(t.v2)};
  const int at_p = geometry::orientation(v[0], v[1], v[2], p);
  int around[3];
  if (light.directional) {
    const int towards = geometry::orientation_towards(v[0], v[1], v[2], light.direction);
    if (towards == 0 || at_p == towards) return false;  // parallel, or moving away from the plane
    for (int k = 0; k < 3; ++k)
      around[k] = geometry::orientation_towards(p, v[k], v[(k + 1) % 3], light.direction);
  } else {
    const int at_light = geometry::orientation(v[0], v[1], v[2], light.position);
    if (at_p * at_light > 0 || (at_p == 0 && at_light == 0)) return false;
    for (int k = 0; k < 3; ++k)
      around[k] = geometry::orientation(p, light.position, v[k], v[(k + 1) % 3]);
  }
  // The line through p towards the light passes through the closed triangle.
  const bool positive = around[0] > 0 || around[1] > 0 || around[2] > 0;
  const bool negative = around[0] < 0 || around[1] < 0 || around[2] < 0;
  return !(positive && negative);
}

struct Expected {
  std::vector<std::uint8_t> with_rule;     // the ground truth
  std::vector<std::uint8_t> without_rule;  // every caster meeting the closed segment counts
};

Expected exact_masks(const HandBuiltCase& h) {
  const HardShadowLight light = hard_shadow_light(h.c);
  Expected e;
  for (const ViewSample& s : h.samples.samples) {
    const dvec3 p = exact(s.position);
    const Triangle& r = h.c.triangles[s.receiver];
    const geometry::ReceiverHalfSpace half_space =
        geometry::receiver_half_space(exact(r.v0), exact(r.v1), exact(r.v2), light.directional,
                                      light.directional ? light.direction : light.position);
    bool with_rule = false, without_rule = false;
    for (std::size_t i = 0; i < h.c.triangles.size(); ++i) {
      if (i == s.receiver || !casts_shadow(h.c, i)) continue;
      const Triangle& t = h.c.triangles[i];
      if (!meets(light, p, t)) continue;
      without_rule = true;
      with_rule = with_rule ||
                  geometry::caster_counts(half_space, p, exact(t.v0), exact(t.v1), exact(t.v2));
    }
    e.with_rule.push_back(with_rule);
    e.without_rule.push_back(without_rule);
  }
  EXPECT_EQ(exact_hard_shadow_oracle(h.c, h.samples).shadowed, e.with_rule);
  return e;
}

std::uint64_t count(const std::vector<std::uint8_t>& mask) {
  std::uint64_t n = 0;
  for (const std::uint8_t m : mask) n += m;
  return n;
}

// Samples where a mask differs from the expected one, and the first of them.
std::string differences(const std::vector<std::uint8_t>& mask,
                        const std::vector<std::uint8_t>& expected, const HandBuiltCase& h) {
  std::uint64_t n = 0;
  std::string first;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] == expected[i]) continue;
    if (n++ == 0) {
      const glm::vec3& p = h.samples.samples[i].position;
      char text[160];
      std::snprintf(text, sizeof text, "; first: sample %zu at (%a, %a, %a), receiver %u, got %d",
                    i, double(p.x), double(p.y), double(p.z), h.samples.samples[i].receiver,
                    int(mask[i]));
      first = text;
    }
  }
  return n == 0 ? std::string() : std::to_string(n) + " samples differ" + first;
}

// Every registered variant, and the two stack paths the variants do not reach on small trees: a
// stack of one that overflows into the stackless query, and a hybrid that switches at once.
void expect_every_query_gives(const HandBuiltCase& h, const std::vector<std::uint8_t>& expected) {
  const auto algorithm = make_psv();
  for (const std::string& variant : algorithm->info().variants)
    EXPECT_EQ(differences(algorithm->run(h.c, h.samples, variant).shadowed, expected, h), "")
        << variant;
  for (const QueryKind query : {QueryKind::stack, QueryKind::hybrid}) {
    PsvOptions options;
    options.query = query;
    options.stack_capacity = 1;
    EXPECT_EQ(differences(psv_hard_shadows(h.c, h.samples, options).shadowed, expected, h), "")
        << (query == QueryKind::stack ? "stack of 1" : "hybrid of 1");
  }
}

float ulps(float x, int n) {
  for (; n > 0; --n) x = std::nextafter(x, INFINITY);
  for (; n < 0; ++n) x = std::nextafter(x, -INFINITY);
  return x;
}

// Whether q lies in the closed triangle t, seen along the triangle's normal (exact).
bool inside(const Triangle& t, const glm::vec3& q) {
  const dvec3 v[3] = {exact(t.v0), exact(t.v1), exact(t.v2)};
  const dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);  // any vector off the plane will do
  bool positive = false, negative = false;
  for (int k = 0; k < 3; ++k) {
    const int s = geometry::orientation_towards(v[k], v[(k + 1) % 3], exact(q), n);
    positive = positive || s > 0;
    negative = negative || s < 0;
  }
  return !(positive && negative);
}

// Samples beside every edge of the triangles [first, last) that the predicate `receives` accepts:
// at a quarter, half and three quarters of the edge, moved by -2..2 ulps along both in-plane axes
// and by `normal_ulps` along the axis `normal_axis` (the triangles lie in planes normal to an
// axis); each kept where it lies in its triangle seen along the normal.
template <typename Receives>
void add_samples_beside_edges(HandBuiltCase& h, std::uint32_t first, std::uint32_t last,
                              int normal_axis, const std::vector<int>& normal_ulps,
                              Receives receives) {
  for (std::uint32_t r = first; r < last; ++r) {
    const Triangle t = h.c.triangles[r];
    if (!receives(t)) continue;
    const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
    for (int k = 0; k < 3; ++k)
      for (const float u : {0.25f, 0.5f, 0.75f}) {
        const glm::vec3 on_edge = v[k] + u * (v[(k + 1) % 3] - v[k]);  // dyadic: exact
        const int a = (normal_axis + 1) % 3, b = (normal_axis + 2) % 3;
        for (int da = -2; da <= 2; ++da)
          for (int db = -2; db <= 2; ++db) {
            glm::vec3 q = on_edge;
            q[a] = ulps(q[a], da);
            q[b] = ulps(q[b], db);
            if (!inside(t, q)) continue;
            for (const int dn : normal_ulps) {
              glm::vec3 sample = q;
              sample[normal_axis] = ulps(q[normal_axis], dn);
              h.add_sample(sample, r);
            }
          }
      }
  }
}

// A floor at y = 1 on [-4, 4]^2 in 2 x 4 x 4 caster triangles (cells of 2, split on a diagonal).
std::uint32_t add_tessellated_floor(HandBuiltCase& h) {
  const std::uint32_t first = std::uint32_t(h.c.triangles.size());
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) {
      const float x = -4.0f + 2.0f * float(i), z = -4.0f + 2.0f * float(k);
      const glm::vec3 a{x, 1, z}, b{x + 2, 1, z}, c{x + 2, 1, z + 2}, d{x, 1, z + 2};
      h.add_triangle(a, b, c, testing::caster_ground_mesh);
      h.add_triangle(a, c, d, testing::caster_ground_mesh);
    }
  return first;
}

// The floor triangle under (x, z), or the first of two on a shared edge.
std::uint32_t floor_receiver(const HandBuiltCase& h, std::uint32_t first, const glm::vec3& p) {
  for (std::uint32_t r = first; r < first + 32; ++r)
    if (inside(h.c.triangles[r], {p.x, 1.0f, p.z})) return r;
  ADD_FAILURE() << "no floor under " << p.x << ", " << p.z;
  return first;
}

// A closed box [lo, hi], every face in n x n cells of two triangles, wound outwards.
void add_box(HandBuiltCase& h, const glm::vec3& lo, const glm::vec3& hi, int n,
             std::uint32_t mesh) {
  for (int axis = 0; axis < 3; ++axis)
    for (const bool high : {false, true}) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      // On the high side e_a x e_b points along +axis; on the low side swap the in-plane axes.
      const int u_axis = high ? a : b, v_axis = high ? b : a;
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
          const auto corner = [&](int di, int dk) {
            glm::vec3 p;
            p[axis] = high ? hi[axis] : lo[axis];
            p[u_axis] = lo[u_axis] + (hi[u_axis] - lo[u_axis]) * float(i + di) / float(n);
            p[v_axis] = lo[v_axis] + (hi[v_axis] - lo[v_axis]) * float(k + dk) / float(n);
            return p;
          };
          h.add_triangle(corner(0, 0), corner(1, 0), corner(1, 1), mesh);
          h.add_triangle(corner(0, 0), corner(1, 1), corner(0, 1), mesh);
        }
    }
}

ShadowLight light_for(bool directional, const glm::vec3& point, const glm::vec3& direction) {
  return directional ? testing::directional_light(direction) : testing::point_light(point);
}

class PsvHalfSpace : public ::testing::TestWithParam<bool> {};  // directional light

// (1) and (4): samples on, one and two ulps below a tessellated floor beside its shared edges,
// under a low light: the coplanar neighbours' volumes reach under the receiver there, yet no
// sample is shadowed.
TEST_P(PsvHalfSpace, TessellatedFloorNeverShadowsItself) {
  auto h = testing::make_hand_built_case(
      light_for(GetParam(), {6.0f, 1.25f, 2.5f}, {1.0f, 0.0625f, 0.5f}));
  const std::uint32_t floor = add_tessellated_floor(h);
  add_samples_beside_edges(h, floor, floor + 32, 1, {-2, -1, 0},
                           [](const Triangle&) { return true; });
  const Expected e = exact_masks(h);
  EXPECT_EQ(count(e.with_rule), 0u);
  EXPECT_GT(count(e.without_rule), h.samples.samples.size() / 50);  // the rule is reached
  expect_every_query_gives(h, e.with_rule);
}

// (2): samples beside every edge of the lit faces of a closed box (four triangles per face), on
// the surface and one ulp inside or outside it: no face shadows the lit side.
TEST_P(PsvHalfSpace, ConvexClosedMeshLitSideIsLit) {
  const bool directional = GetParam();
  auto h = testing::make_hand_built_case(
      light_for(directional, {4.0f, 6.0f, 3.0f}, {0.75f, 1.0f, 0.5f}));
  h.c.meshes.push_back(Mesh{"box", true, true});
  const std::uint32_t box_mesh = std::uint32_t(h.c.meshes.size() - 1);
  const std::uint32_t first = std::uint32_t(h.c.triangles.size());
  add_box(h, {-1, 1, -1}, {1, 3, 1}, 2, box_mesh);
  const HardShadowLight light = hard_shadow_light(h.c);
  const std::uint32_t last = std::uint32_t(h.c.triangles.size());
  for (int axis = 0; axis < 3; ++axis)
    add_samples_beside_edges(h, first, last, axis, {-1, 0, 1}, [&](const Triangle& t) {
      // A lit face normal to this axis.
      const glm::vec3 n = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
      if (n[axis] == 0.0f) return false;
      const dvec3 v0 = exact(t.v0), v1 = exact(t.v1), v2 = exact(t.v2);
      return (light.directional ? geometry::orientation_towards(v0, v1, v2, light.direction)
                                : geometry::orientation(v0, v1, v2, light.position)) > 0;
    });
  const Expected e = exact_masks(h);
  EXPECT_EQ(count(e.with_rule), 0u);
  EXPECT_GT(count(e.without_rule), 0u);
  expect_every_query_gives(h, e.with_rule);
}

// (3): a wall standing on the tessellated floor shadows the floor behind it, samples one ulp
// below the floor included, while the floor in front stays lit. Within a few ulps of its base
// a segment from below the floor may pass under the wall and cross the floor's plane in front of
// it: the exact construction decides those.
TEST_P(PsvHalfSpace, WallStandingOnTheFloorShadowsTheFloorBehindIt) {
  auto h = testing::make_hand_built_case(
      light_for(GetParam(), {-6.0f, 3.0f, 0.25f}, {-1.0f, 0.25f, 0.0625f}));
  const std::uint32_t floor = add_tessellated_floor(h);
  h.add_triangle({0.5f, 1, -2}, {0.5f, 1, 2}, {0.5f, 2, 2});
  h.add_triangle({0.5f, 1, -2}, {0.5f, 2, 2}, {0.5f, 2, -2});
  std::vector<std::size_t> behind, in_front;
  for (const float z : {-1.5f, -0.375f, 0.0f, 0.625f, 1.875f})
    for (const int dy : {-1, 0, 1}) {
      const float y = ulps(1.0f, dy);
      for (const int dx : {-3, -2, -1, 0, 1, 2, 3}) {
        const glm::vec3 p{ulps(0.5f, dx), y, z};
        const std::size_t i = h.add_sample(p, floor_receiver(h, floor, p));
        if (dx < 0) in_front.push_back(i);
      }
      for (const float x : {0.5f + 0x1p-16f, 0.75f, 1.5f}) {
        const glm::vec3 p{x, y, z};
        behind.push_back(h.add_sample(p, floor_receiver(h, floor, p)));
      }
      for (const float x : {0.5f - 0x1p-16f, -0.25f, -1.5f}) {
        const glm::vec3 p{x, y, z};
        in_front.push_back(h.add_sample(p, floor_receiver(h, floor, p)));
      }
    }
  const Expected e = exact_masks(h);
  for (const std::size_t i : behind) EXPECT_EQ(e.with_rule[i], 1) << i;
  for (const std::size_t i : in_front) EXPECT_EQ(e.with_rule[i], 0) << i;
  expect_every_query_gives(h, e.with_rule);
}

// (3) with a closed box instead of a wall, and no sample in its bounding box, so that psv culls
// the faces turned towards the light: the segments of samples one ulp below the floor at its
// base pass under the box's bottom face (in the floor's plane: it does not count) and leave the
// box through culled faces above the floor.
TEST_P(PsvHalfSpace, ClosedBoxStandingOnTheFloorShadowsItsBase) {
  auto h = testing::make_hand_built_case(
      light_for(GetParam(), {-8.0f, 3.0f, 0.25f}, {-1.0f, 0.25f, 0.0625f}));
  h.c.meshes.push_back(Mesh{"box", true, true});
  const std::uint32_t floor = add_tessellated_floor(h);
  add_box(h, {-1.5f, 1, -1}, {0.5f, 2, 1}, 1, std::uint32_t(h.c.meshes.size() - 1));
  std::vector<std::size_t> behind_base;
  for (const float z : {-0.75f, 0.0f, 0.625f})
    for (const int dx : {1, 2, 3})
      for (const int dy : {-2, -1}) {
        const glm::vec3 p{ulps(0.5f, dx), ulps(1.0f, dy), z};
        behind_base.push_back(h.add_sample(p, floor_receiver(h, floor, p)));
      }
  const Expected e = exact_masks(h);
  for (const std::size_t i : behind_base) EXPECT_EQ(e.with_rule[i], 1) << i;
  expect_every_query_gives(h, e.with_rule);
  // Away from the box's base the faces turned towards the light are still culled.
  h.samples.samples.clear();
  h.add_sample({0.75f, 1.0f, 0.0f}, floor_receiver(h, floor, {0.75f, 1.0f, 0.0f}));
  const PsvResult far = psv_hard_shadows(h.c, h.samples, PsvOptions{});
  EXPECT_EQ(far.shadowed, std::vector<std::uint8_t>{1});
  EXPECT_EQ(far.counters[1].first, "triangles_culled_front_facing");
  EXPECT_GT(far.counters[1].second, 0u);
}

INSTANTIATE_TEST_SUITE_P(Lights, PsvHalfSpace, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& light) {
                           return light.param ? "directional" : "point";
                         });

}  // namespace
}  // namespace shadowcts::psv
