// The receiver half-space rule (DESIGN.md) in every ptsv variant, on hand-built samples:
// (1) one float ulp below (and on, and above) a tessellated floor beside its edges and vertices,
//     where a coplanar neighbour's closed volume holds the sample: lit;
// (2) beside the edges of a tessellated convex closed box, on its lit faces: lit, while the box
//     still shadows a floor behind it;
// (3) a wall standing on a floor whose samples all lie one ulp below it: shadowed behind the wall;
// (4) (1) with a directional light;
// (5) a light grazing the floor and a caster below the floor's plane: the rule rejects the caster
//     for whole nodes that its volume holds, so they must be refined instead of accepted;
// (6) a closed mesh sunk into the floor under a low light: front-face culling must keep the faces
//     of a mesh within a sample's reject reach.
// Each answer is the hand-derived one and the exact oracle's, for every regular sample.
#include "reference/ptsv/receiver_rule.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "ptsv_test_support.h"
#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/node_test.h"
#include "reference/ptsv/triangle_setup.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts::ptsv {
namespace {

constexpr float floor_z = 8.0f;
const float below_floor = std::nextafter(floor_z, 0.0f);  // 8 - 2^-21
const float above_floor = std::nextafter(floor_z, 16.0f);

// A 2n x 2n grid of unit cells on z = floor_z around the origin, each split along its diagonal,
// facing +z: mesh `mesh`.
void add_floor(Case& c, int n, std::uint32_t mesh) {
  for (int i = -n; i < n; ++i)
    for (int j = -n; j < n; ++j) {
      const float x0 = float(i), x1 = float(i + 1), y0 = float(j), y1 = float(j + 1);
      c.triangles.push_back({{x0, y0, floor_z}, {x1, y0, floor_z}, {x1, y1, floor_z}, mesh});
      c.triangles.push_back({{x0, y0, floor_z}, {x1, y1, floor_z}, {x0, y1, floor_z}, mesh});
    }
}

// The first triangle of `mesh` whose projection along `axis` holds q (chosen in its interior).
std::uint32_t triangle_at(const Case& c, std::uint32_t mesh, int axis, const glm::dvec3& q) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    const Triangle& t = c.triangles[i];
    if (t.mesh != mesh || double(t.v0[axis]) != q[axis] || double(t.v1[axis]) != q[axis] ||
        double(t.v2[axis]) != q[axis])
      continue;
    const glm::dvec3 a(t.v0), b(t.v1), d(t.v2);
    const auto side = [&](const glm::dvec3& p0, const glm::dvec3& p1) {
      return (p1[u] - p0[u]) * (q[v] - p0[v]) - (p1[v] - p0[v]) * (q[u] - p0[u]);
    };
    const double s0 = side(a, b), s1 = side(b, d), s2 = side(d, a);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return std::uint32_t(i);
  }
  ADD_FAILURE() << "no triangle at (" << q.x << ", " << q.y << ", " << q.z << ")";
  return 0;
}

ShadowLight point_light(const glm::vec3& position) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = position;
  return light;
}

ShadowLight directional_light(const glm::vec3& towards_light) {
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = towards_light;
  return light;
}

// One sample at p (normal, receiver) seen by a 1x1 camera from `eye`: its pixel's wedge is the
// whole frustum, so every variant holds the hand-placed position.
ViewSamples single_sample(Case& c, const glm::vec3& p, const glm::vec3& normal,
                          std::uint32_t receiver, const glm::vec3& eye) {
  c.camera.position = eye;
  c.camera.target = p;
  c.camera.width = c.camera.height = 1;
  c.camera.near_plane = 0.01f;
  c.camera.far_plane = 100.0f;
  ViewSamples samples;
  samples.width = samples.height = 1;
  ViewSample s;
  s.position = p;
  s.normal = normal;
  s.receiver = receiver;
  s.sample_class = SampleClass::regular;  // re-derived
  samples.samples = {s};
  validate(c);
  classify_samples(c, samples, c.name);
  return samples;
}

// How many casters other than the sample's receiver hold it in their closed shadow volume:
// without the rule each of them would shadow it.
int volumes_holding(const Case& c, const ViewSample& s) {
  SetupCounts counts;
  const std::vector<ShadowVolume> volumes =
      set_up_shadow_volumes(c, std::vector<bool>(c.meshes.size(), false), {}, c.scale(), counts);
  int n = 0;
  for (const ShadowVolume& v : volumes) n += sample_in_volume(v, s) ? 1 : 0;
  return n;
}

// Every variant against the exact oracle on every regular sample, and against `expected` where it
// is 0 or 1 (-1: not derived by hand). Returns the oracle's mask.
std::vector<std::uint8_t> expect_every_variant(const Case& c, const ViewSamples& samples,
                                               const std::vector<int>& expected,
                                               const std::string& what) {
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  const auto algorithm = make_ptsv();
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (samples.samples[i].sample_class != SampleClass::regular || expected[i] < 0) continue;
    EXPECT_EQ(int(truth.shadowed[i]), expected[i]) << what << ": oracle, sample " << i;
  }
  for (const std::string& variant : algorithm->info().variants) {
    const auto why = algorithm->unsupported_reason(c, samples, variant);
    EXPECT_FALSE(why.has_value()) << what << " " << variant << ": " << why.value_or("");
    if (why) continue;
    const AlgorithmOutput out = algorithm->run(c, samples, variant);
    std::size_t wrong = 0, first = 0;
    for (std::size_t i = 0; i < samples.samples.size(); ++i) {
      if (samples.samples[i].sample_class != SampleClass::regular) {
        EXPECT_EQ(out.shadowed[i], 0) << what << " " << variant << ", sample " << i;
        continue;
      }
      const bool bad = out.shadowed[i] != truth.shadowed[i] ||
                       (expected[i] >= 0 && int(out.shadowed[i]) != expected[i]);
      if (bad && wrong++ == 0) first = i;
    }
    EXPECT_EQ(wrong, 0u) << what << " " << variant << ": first wrong sample " << first;
  }
  return truth.shadowed;
}

struct FloorEdge {
  const char* name;
  glm::vec2 point;            // on an edge or a vertex of the grid
  glm::vec2 receiver_inside;  // a point inside the receiver, away from the light
  glm::vec3 light;            // point light; its direction from the point for the directional case
};

const FloorEdge floor_edges[] = {
    {"vertical_edge", {0.0f, 0.5f}, {-0.25f, 0.5f}, {6.0f, 0.5f, 12.0f}},
    {"diagonal_edge", {0.5f, 0.5f}, {0.25f, 0.75f}, {6.5f, -5.5f, 12.0f}},
    {"horizontal_edge", {-1.5f, 2.0f}, {-1.25f, 2.125f}, {-1.5f, -4.0f, 11.0f}},
    {"vertex", {1.0f, 1.0f}, {0.75f, 0.875f}, {4.0f, 5.0f, 10.0f}},
};

void expect_floor_beside_edges_lit(bool directional) {
  for (const FloorEdge& e : floor_edges)
    for (const float z : {below_floor, floor_z, above_floor}) {
      Case c;
      c.name = std::string("floor_") + e.name;
      c.source = "receiver_rule_test.cpp";
      c.meshes = {Mesh{"floor", false, true}};
      add_floor(c, 3, 0);
      const glm::vec3 p(e.point, z);
      c.light = directional ? directional_light(glm::normalize(e.light - p)) : point_light(e.light);
      const std::uint32_t r =
          triangle_at(c, 0, 2, glm::dvec3(e.receiver_inside.x, e.receiver_inside.y, floor_z));
      const ViewSamples samples =
          single_sample(c, p, {0.0f, 0.0f, 1.0f}, r, p + glm::vec3(-3.0f, -2.0f, 6.0f));
      ASSERT_EQ(samples.samples[0].sample_class, SampleClass::regular) << c.name;
      const std::string what =
          c.name + (directional ? " directional" : " point") + " z=" + std::to_string(z);
      // On or below the plane a neighbour's closed volume holds the sample: only the rule
      // keeps it lit.
      if (z <= floor_z) {
        EXPECT_GE(volumes_holding(c, samples.samples[0]), 1) << what;
      }
      expect_every_variant(c, samples, {0}, what);
    }
}

TEST(PtsvReceiverRule, FloorSampleOneUlpBelowBesideACoplanarNeighbourIsLit) {
  expect_floor_beside_edges_lit(false);
}

TEST(PtsvReceiverRule, FloorSampleOneUlpBelowBesideACoplanarNeighbourIsLitByADirectionalLight) {
  expect_floor_beside_edges_lit(true);
}

// The box [-2, 2]^3, each face a 2 x 2 grid of squares split along a diagonal, facing outwards:
// mesh `mesh`, closed.
void add_box(Case& c, std::uint32_t mesh) {
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-2.0f, 2.0f}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = -2; i < 2; i += 2)
        for (int j = -2; j < 2; j += 2) {
          glm::vec3 q[4];
          const float us[4] = {float(i), float(i + 2), float(i + 2), float(i)};
          const float vs[4] = {float(j), float(j), float(j + 2), float(j + 2)};
          for (int k = 0; k < 4; ++k) {
            q[k][axis] = side;
            q[k][u] = us[k];
            q[k][v] = vs[k];
          }
          // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
          if (side > 0) {
            c.triangles.push_back({q[0], q[1], q[2], mesh});
            c.triangles.push_back({q[0], q[2], q[3], mesh});
          } else {
            c.triangles.push_back({q[0], q[2], q[1], mesh});
            c.triangles.push_back({q[0], q[3], q[2], mesh});
          }
        }
    }
}

TEST(PtsvReceiverRule, SamplesBesideTheEdgesOfAConvexClosedMeshAreLitOnItsLitSide) {
  const float in = std::nextafter(2.0f, 0.0f);  // one ulp inside a face plane
  struct BoxSample {
    const char* name;
    glm::vec3 position;
    int receiver_axis;         // the receiver's face: +axis
    glm::dvec3 receiver_near;  // a point inside the receiver
  };
  const BoxSample box_samples[] = {
      {"crease_x_z_on_x_plane", {2.0f, 0.5f, in}, 2, {1.5f, 0.5f, 2.0f}},
      {"crease_x_z_inside_both", {in, 0.5f, in}, 0, {2.0f, 0.5f, 1.5f}},
      {"crease_z_x", {in, -0.75f, 2.0f}, 0, {2.0f, -0.75f, 1.5f}},
      {"crease_y_z", {-1.0f, 2.0f, in}, 2, {-1.0f, 1.5f, 2.0f}},
      {"corner", {in, in, in}, 1, {1.5f, 2.0f, 1.0f}},
      {"face_diagonal", {1.0f, 1.0f, in}, 2, {0.5f, 1.5f, 2.0f}},
      {"face_grid_line", {0.0f, -1.0f, in}, 2, {-0.5f, -1.0f, 2.0f}},
  };
  for (const bool directional : {false, true})
    for (const BoxSample& b : box_samples) {
      Case c;
      c.name = std::string("box_") + b.name;
      c.source = "receiver_rule_test.cpp";
      c.meshes = {Mesh{"box", true, true}};
      add_box(c, 0);
      const glm::vec3 light(10.0f, 8.0f, 12.0f);  // lights the +x, +y and +z faces
      c.light = directional ? directional_light(glm::normalize(light)) : point_light(light);
      const std::uint32_t r = triangle_at(c, 0, b.receiver_axis, b.receiver_near);
      glm::vec3 normal(0.0f);
      normal[b.receiver_axis] = 1.0f;
      const ViewSamples samples =
          single_sample(c, b.position, normal, r, b.position + 5.0f * normal + glm::vec3(1.0f));
      ASSERT_EQ(samples.samples[0].sample_class, SampleClass::regular) << c.name;
      const std::string what = c.name + (directional ? " directional" : " point");
      EXPECT_GE(volumes_holding(c, samples.samples[0]), 1) << what;
      expect_every_variant(c, samples, {0}, what);
    }
}

TEST(PtsvReceiverRule, TheConvexClosedMeshStillShadowsTheFloorBehindIt) {
  for (const bool directional : {false, true}) {
    Case c;
    c.name = "box_over_floor";
    c.source = "receiver_rule_test.cpp";
    c.meshes = {Mesh{"box", true, true}, Mesh{"floor", false, true}};
    add_box(c, 0);
    for (Triangle& t : c.triangles)
      for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) v->z += 12.0f;  // the box at z in [10, 14]
    add_floor(c, 4, 1);
    const glm::vec3 light(10.0f, 8.0f, 24.0f);
    c.light = directional ? directional_light(glm::normalize(light)) : point_light(light);
    // Straight below the box, one ulp below the floor: behind the box for either light.
    const glm::vec3 p(-0.25f, -0.5f, below_floor);
    const std::uint32_t r = triangle_at(c, 1, 2, glm::dvec3(-0.2, -0.55, floor_z));
    const ViewSamples samples =
        single_sample(c, p, {0.0f, 0.0f, 1.0f}, r, p + glm::vec3(-3.0f, -2.0f, 1.0f));
    ASSERT_EQ(samples.samples[0].sample_class, SampleClass::regular);
    expect_every_variant(c, samples, {1}, directional ? "directional" : "point");
  }
}

// A floor of 16 x 16 cells seen from above, with every floor sample moved one ulp below it (as
// rounding leaves about half of them), and the given casters in mesh 1.
struct FloorScene {
  Case c;
  ViewSamples samples;
  FloorScene(const ShadowLight& light, const std::vector<Triangle>& casters, const char* name) {
    c.name = name;
    c.source = "receiver_rule_test.cpp";
    c.meshes = {Mesh{"floor", false, true}, Mesh{"casters", false, true}};
    add_floor(c, 8, 0);
    for (const Triangle& t : casters) c.triangles.push_back(t);
    c.light = light;
    c.camera.position = {-12.0f, -9.0f, 22.0f};
    c.camera.target = {0.0f, 0.0f, 8.0f};
    c.camera.width = 64;
    c.camera.height = 48;
    c.camera.near_plane = 0.5f;
    c.camera.far_plane = 60.0f;
    validate(c);
    samples = generate_view_samples(c);
    for (ViewSample& s : samples.samples)
      if (s.sample_class != SampleClass::sky && c.triangles[s.receiver].mesh == 0)
        s.position.z = below_floor;
    classify_samples(c, samples, c.name);
  }
  bool on_floor(std::size_t i) const {
    const ViewSample& s = samples.samples[i];
    return s.sample_class == SampleClass::regular && c.triangles[s.receiver].mesh == 0;
  }
};

TEST(PtsvReceiverRule, AWallStandingOnTheFloorShadowsTheFloorBehindIt) {
  // The wall x = 2, y in [-3, 3], z in [8, 11]: its bottom edge lies in the floor's plane.
  const std::vector<Triangle> wall = {{{2, -3, 8}, {2, 3, 8}, {2, 3, 11}, 1},
                                      {{2, -3, 8}, {2, 3, 11}, {2, -3, 11}, 1}};
  const glm::dvec3 light(7.0, 0.25, 13.0);
  const FloorScene s(point_light(glm::vec3(light)), wall, "wall_on_floor");
  // By hand, in double, where the segment clears the wall's outline by 10^-3: it meets the plane
  // x = 2 at a point of the wall, or (from x > 2) never.
  std::vector<int> expected(s.samples.samples.size(), -1);
  int shadowed = 0, lit = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (!s.on_floor(i)) continue;
    const glm::dvec3 p(s.samples.samples[i].position);
    if (p.x > 2.001) {
      expected[i] = 0;
    } else if (p.x < 1.999) {
      const glm::dvec3 hit = p + (2.0 - p.x) / (light.x - p.x) * (light - p);
      const double margin = std::min({hit.y + 3.0, 3.0 - hit.y, hit.z - 8.0, 11.0 - hit.z});
      if (std::fabs(margin) > 1e-3) expected[i] = margin > 0.0 ? 1 : 0;
    }
    shadowed += expected[i] == 1;
    lit += expected[i] == 0;
  }
  EXPECT_GT(shadowed, 100);
  EXPECT_GT(lit, 100);
  expect_every_variant(s.c, s.samples, expected, s.c.name);
  // Whole nodes of below-plane samples are still accepted where the rule cannot reject.
  const auto algorithm = make_ptsv();
  for (const std::string variant : {"explicit", "explicit+planes", "twopass"})
    EXPECT_GT(ptsv_test::counter(algorithm->run(s.c, s.samples, variant), "trivial_accepts"), 0u)
        << variant;
}

// (5): a basement wall x = 6, y in [-4, 4], z in [4, 8] (its top edge in the floor's plane, no
// point strictly above it) and a light just above the floor's plane: the segments of the samples
// one ulp below the floor stay below the plane past the wall and meet it, so the wall's volume
// holds whole nodes of them, but the rule never counts it.
TEST(PtsvReceiverRule, AGrazingLightDoesNotLetANodeBeAcceptedForSamplesTheRuleProtects) {
  const std::vector<Triangle> basement = {{{6, -4, 4}, {6, 4, 4}, {6, 4, 8}, 1},
                                          {{6, -4, 4}, {6, 4, 8}, {6, -4, 8}, 1}};
  for (const bool directional : {false, true}) {
    // Point: the segment crosses the floor's plane 1/9 of the way to the light, x > 14; the
    // directional ray 32 units on.
    const ShadowLight light = directional ? directional_light({1.0f, 0.0f, 0x1p-26f})
                                          : point_light({200.0f, 0.0f, floor_z + 0x1p-18f});
    const FloorScene s(light, basement, directional ? "grazing_directional" : "grazing_point");
    std::vector<int> expected(s.samples.samples.size(), -1);
    for (std::size_t i = 0; i < expected.size(); ++i)
      if (s.on_floor(i)) expected[i] = 0;

    // The wall's volume holds samples behind it; without the rule they would be shadowed.
    SetupCounts counts;
    const std::vector<ShadowVolume> volumes = set_up_shadow_volumes(
        s.c, std::vector<bool>(s.c.meshes.size(), false), {}, s.c.scale(), counts);
    const ShadowVolume* wall = nullptr;
    int held = 0;
    for (const ShadowVolume& v : volumes) {
      if (s.c.triangles[v.triangle].mesh != 1) continue;
      int n = 0;
      for (std::size_t i = 0; i < expected.size(); ++i)
        n += s.on_floor(i) && sample_in_volume(v, s.samples.samples[i]) ? 1 : 0;
      if (n > held) {
        held = n;
        wall = &v;
      }
    }
    ASSERT_NE(wall, nullptr);
    EXPECT_GT(held, 50);
    expect_every_variant(s.c, s.samples, expected, s.c.name);

    // Node by node (explicit bounds): the four planes accept nodes of those samples, and their
    // reject reach turns each into a refinement.
    const ReceiverRule rule(s.c, s.samples);
    const ViewFrame frame = make_view_frame(s.c.camera, s.samples.width, s.samples.height);
    const ClusterKeyLayout layout =
        make_cluster_key_layout(s.c.camera, s.samples.width, s.samples.height).layout;
    const ClusterKeys keys = assign_cluster_keys(layout, frame, s.samples, false);
    ASSERT_TRUE(keys.problem.empty()) << keys.problem;
    const ClusterHierarchy h(layout, keys.key, s.samples, rule.reject_reach());
    const NodeTolerances tolerances = NodeTolerances::for_bounds(s.c.scale(), s.c.scale());
    int accepted_without_rule = 0;
    for (int l = 1; l <= h.leaf_level(); ++l)
      for (std::size_t n = 0; n < h.level(l).index.size(); ++n) {
        TraversalCounters counters;
        const WorldBox& box = h.level(l).bounds[n];
        const NodeVerdict without_rule = classify_node(*wall, box, tolerances, CullingPlanes::none,
                                                       counters, [] { return 0.0; });
        const NodeVerdict with_rule =
            classify_node(*wall, box, tolerances, CullingPlanes::none, counters,
                          [&] { return h.level(l).reject_reach[n]; });
        if (without_rule != NodeVerdict::accept) continue;
        ++accepted_without_rule;
        EXPECT_EQ(with_rule, NodeVerdict::refine) << "level " << l << " node " << n;
      }
    EXPECT_GT(accepted_without_rule, 0) << s.c.name;
  }
}

// (6): the box [-2, 2]^2 x [6, 10] sunk into the floor and a light low above the floor's plane.
// The segment of a floor sample at x in (-5.2, -2), one ulp below the floor, enters the box below
// the floor's plane (the rule rejects that face, turned away from the light) and leaves it above
// (that face counts). Front-face culling would drop the face that counts; within the samples'
// reject reach the box keeps it.
TEST(PtsvReceiverRule, AClosedMeshWithinASamplesReachKeepsItsFrontFaces) {
  std::vector<Triangle> box;
  {
    Case b;
    add_box(b, 1);
    for (Triangle t : b.triangles) {
      for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) v->z += 8.0f;
      box.push_back(t);
    }
  }
  const glm::dvec3 light(200.0, 0.0, double(floor_z) + 0x1p-15);
  FloorScene s(point_light(glm::vec3(light)), box, "sunk_box");
  s.c.meshes[1].closed = true;
  classify_samples(s.c, s.samples, s.c.name);
  std::vector<int> expected(s.samples.samples.size(), -1);
  int entering_below = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (!s.on_floor(i)) continue;
    const glm::dvec3 p(s.samples.samples[i].position);
    if (p.x > 2.01) expected[i] = 0;
    if (p.x < -2.01 && std::fabs(p.y) < 1.99) expected[i] = 1;
    entering_below += expected[i] == 1 && p.x > -5.0;
  }
  EXPECT_GT(entering_below, 20);
  expect_every_variant(s.c, s.samples, expected, s.c.name);
  const auto algorithm = make_ptsv();
  EXPECT_EQ(ptsv_test::counter(algorithm->run(s.c, s.samples, "explicit"), "front_faces_culled"),
            0u);
}

TEST(PtsvReceiverRule, RejectReachBoundsTheCrossingOfTheReceiversPlane) {
  const glm::dvec3 a(-1, 0, floor_z), b(1, 0, floor_z), d(0, 1, floor_z);
  const glm::dvec3 light(200.0, 0.0, double(floor_z) + 0x1p-18);
  const geometry::ReceiverHalfSpace h = geometry::receiver_half_space(a, b, d, false, light);
  const glm::dvec3 p(0.0, 0.25, double(below_floor));
  // f(p) = -2^-21, f(L) = 2^-18: the segment crosses at 1/9 of its length.
  const double crossing = glm::length(light - p) / 9.0;
  const double reach = reject_reach(h, p);
  EXPECT_GE(reach, crossing);
  EXPECT_LE(reach, 1.2 * crossing);
  EXPECT_EQ(reject_reach(h, glm::dvec3(0.0, 0.25, floor_z)), 0.0);
  EXPECT_EQ(reject_reach(h, glm::dvec3(0.0, 0.25, double(above_floor))), 0.0);
  EXPECT_EQ(reject_reach(geometry::ReceiverHalfSpace{}, p), 0.0);  // no receiver plane
  const geometry::ReceiverHalfSpace grazing =
      geometry::receiver_half_space(a, b, d, false, glm::dvec3(200.0, 0.0, floor_z));
  EXPECT_TRUE(std::isinf(reject_reach(grazing, p)));
  // Directional: the ray (1, 0, 2^-26) crosses 32 units along x.
  const glm::dvec3 towards(1.0, 0.0, 0x1p-26);
  const geometry::ReceiverHalfSpace hd = geometry::receiver_half_space(a, b, d, true, towards);
  const double along = 32.0 * glm::length(towards);
  EXPECT_GE(reject_reach(hd, p), along);
  EXPECT_LE(reject_reach(hd, p), 1.001 * along);
}

}  // namespace
}  // namespace shadowcts::ptsv
