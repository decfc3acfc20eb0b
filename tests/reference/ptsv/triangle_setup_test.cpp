// Triangle setup: canonical shared-edge planes, skipped triangles, front-face
// culling, and culling planes that never cut the volume.
#include "reference/ptsv/triangle_setup.h"

#include <random>

#include <gtest/gtest.h>

#include "big_shadow_case.h"
#include "reference/ptsv/node_test.h"

namespace shadowcts::ptsv {
namespace {

Case two_triangles_sharing_an_edge(bool directional) {
  Case c = ptsv_test::big_shadow_case(directional);
  c.triangles = {Triangle{{-1.0f, 2.0f, -1.0f}, {1.0f, 2.5f, 0.5f}, {-0.5f, 2.25f, 1.5f}, 1},
                 // shares edge (-1, 2, -1) - (1, 2.5, 0.5), listed in the other direction
                 Triangle{{1.0f, 2.5f, 0.5f}, {-1.0f, 2.0f, -1.0f}, {0.75f, 1.75f, -2.0f}, 1}};
  return c;
}

TEST(TriangleSetup, SharedEdgesGiveIdenticalPlanesWithOppositeSigns) {
  for (bool directional : {false, true}) {
    const Case c = two_triangles_sharing_an_edge(directional);
    SetupCounts counts;
    const auto volumes =
        set_up_shadow_volumes(c, std::vector<bool>(c.meshes.size(), false), {}, 10.0, counts);
    ASSERT_EQ(volumes.size(), 2u);
    int shared = 0;
    for (const Plane& first : volumes[0].edges)
      for (const Plane& second : volumes[1].edges)
        if (first.anchor == second.anchor &&
            (first.normal == second.normal || first.normal == -second.normal)) {
          EXPECT_EQ(first.normal, -second.normal);
          ++shared;
          // Bit-identical values with opposite signs: no point is outside both.
          std::mt19937_64 random(7);
          std::uniform_real_distribution<float> coordinate(-5.0f, 5.0f);
          for (int i = 0; i < 1000; ++i) {
            const glm::dvec3 x(coordinate(random), coordinate(random), coordinate(random));
            EXPECT_EQ(first.at(x), -second.at(x));
          }
        }
    EXPECT_EQ(shared, 1) << (directional ? "directional" : "point");
  }
}

TEST(TriangleSetup, VertexOrderDoesNotChangeTheVolume) {
  const Case c = ptsv_test::big_shadow_case(false);
  Case rotated = c, flipped = c;
  for (Triangle& t : rotated.triangles) t = Triangle{t.v1, t.v2, t.v0, t.mesh};
  for (Triangle& t : flipped.triangles) t = Triangle{t.v0, t.v2, t.v1, t.mesh};
  const std::vector<bool> none(c.meshes.size(), false);
  SetupOptions options;
  options.extra_planes = true;
  options.silhouette_planes = true;
  SetupCounts counts;
  const auto original = set_up_shadow_volumes(c, none, options, 10.0, counts);
  for (const Case* variant : {&rotated, &flipped}) {
    const auto other = set_up_shadow_volumes(*variant, none, options, 10.0, counts);
    ASSERT_EQ(other.size(), original.size());
    for (std::size_t v = 0; v < original.size(); ++v) {
      for (int e = 0; e < 3; ++e) {
        EXPECT_EQ(other[v].edges[std::size_t(e)].normal, original[v].edges[std::size_t(e)].normal);
        EXPECT_EQ(other[v].edges[std::size_t(e)].anchor, original[v].edges[std::size_t(e)].anchor);
      }
      EXPECT_EQ(other[v].triangle_plane.normal, original[v].triangle_plane.normal);
      EXPECT_EQ(other[v].extra_count, original[v].extra_count);
    }
  }
}

TEST(TriangleSetup, SkipsZeroAreaEdgeOnAndNonCasters) {
  Case c = ptsv_test::big_shadow_case(false);
  c.meshes.push_back(Mesh{"decal", false, false});
  c.triangles.push_back(Triangle{{0, 1, 0}, {1, 1, 0}, {2, 1, 0}, 1});  // collinear
  // In a plane through the point light (-8, 12, -9): edge-on.
  c.triangles.push_back(
      Triangle{{-8.0f, 1.0f, -9.0f}, {2.5f, 1.0f, -9.0f}, {0.5f, 5.0f, -9.0f}, 1});
  c.triangles.push_back(Triangle{{0, 1, 0}, {1, 1, 0}, {0, 1, 1}, 2});  // mesh casts nothing
  SetupCounts counts;
  const auto volumes =
      set_up_shadow_volumes(c, std::vector<bool>(c.meshes.size(), false), {}, 10.0, counts);
  EXPECT_EQ(counts.casters, 5u);
  EXPECT_EQ(counts.zero_area, 1u);
  EXPECT_EQ(counts.edge_on, 1u);
  EXPECT_EQ(counts.volumes, 3u);
  EXPECT_EQ(volumes.size(), 3u);
}

TEST(TriangleSetup, FrontFaceCullingOnlyForClosedMeshesClearOfTheCamera) {
  Case c = ptsv_test::big_shadow_case(false);
  ViewSamples no_samples;  // none inside any mesh: the camera's near region decides
  no_samples.width = 256;
  no_samples.height = 192;
  EXPECT_EQ(front_face_culling_meshes(c, no_samples, {}), (std::vector<bool>{false, false}));
  c.meshes[1].closed = true;
  EXPECT_EQ(front_face_culling_meshes(c, no_samples, {}), (std::vector<bool>{false, true}));
  // The caster's triangle faces... its winding decides: one of the two windings is culled.
  SetupCounts counts, flipped_counts;
  set_up_shadow_volumes(c, {false, true}, {}, 10.0, counts);
  Case flipped = c;
  for (Triangle& t : flipped.triangles) t = Triangle{t.v0, t.v2, t.v1, t.mesh};
  set_up_shadow_volumes(flipped, {false, true}, {}, 10.0, flipped_counts);
  EXPECT_EQ(counts.front_faces_culled + flipped_counts.front_faces_culled, 1u);
  // The eye inside the closed mesh's box: no culling.
  c.camera.position = {0.0f, 3.0f, 0.0f};
  c.camera.target = {0.0f, 0.0f, 1.0f};
  EXPECT_EQ(front_face_culling_meshes(c, no_samples, {}), (std::vector<bool>{false, false}));
}

// Points of the volume: L + s (Y - L), s >= 1 (point light) or Y - t d (directional), Y in the
// triangle. Every one must be on the inside of every culling plane, and of the four planes.
TEST(TriangleSetup, CullingPlanesNeverCutTheVolume) {
  for (bool directional : {false, true}) {
    Case c = ptsv_test::big_shadow_case(directional);
    std::mt19937_64 random(11);
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f);
    for (int t = 0; t < 200; ++t)
      c.triangles.push_back(
          Triangle{{coordinate(random), 3.0f + coordinate(random) / 4, coordinate(random)},
                   {coordinate(random), 3.0f + coordinate(random) / 4, coordinate(random)},
                   {coordinate(random), 3.0f + coordinate(random) / 4, coordinate(random)},
                   1});
    SetupOptions options;
    options.extra_planes = true;
    options.silhouette_planes = true;
    SetupCounts counts;
    const double bound = 100.0;
    const auto volumes =
        set_up_shadow_volumes(c, std::vector<bool>(c.meshes.size(), false), options, bound, counts);
    EXPECT_GT(counts.extra_planes, 300u);
    EXPECT_GT(counts.silhouette_planes, 200u);
    const NodeTolerances tolerances = NodeTolerances::for_bounds(bound, bound);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const ShadowVolume& v : volumes) {
      const Triangle& tri = c.triangles[v.triangle];
      for (int i = 0; i < 200; ++i) {
        double l0 = unit(random), l1 = unit(random);
        if (l0 + l1 > 1.0) {
          l0 = 1.0 - l0;
          l1 = 1.0 - l1;
        }
        const glm::dvec3 y = l0 * glm::dvec3(tri.v0) + l1 * glm::dvec3(tri.v1) +
                             (1.0 - l0 - l1) * glm::dvec3(tri.v2);
        const double stretch = unit(random) * 30.0;
        const glm::dvec3 x = directional ? y - stretch * glm::dvec3(c.light->direction)
                                         : y + stretch * (y - glm::dvec3(c.light->position));
        if (std::max({std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)}) > bound) continue;
        for (int k = 0; k < v.extra_count; ++k)
          EXPECT_LE(v.extra[std::size_t(k)].at(x), tolerances.rounding);
        for (int k = 0; k < v.silhouette_count; ++k)
          EXPECT_LE(v.silhouette[std::size_t(k)].at(x), tolerances.rounding);
        for (const Plane& plane : v.edges) EXPECT_LE(plane.at(x), 1e-9);
        EXPECT_LE(v.triangle_plane.at(x), 1e-9);
      }
    }
  }
}

}  // namespace
}  // namespace shadowcts::ptsv
