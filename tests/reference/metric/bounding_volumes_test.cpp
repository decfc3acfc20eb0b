// Every cluster's sphere or capsule and slabs contain all its vertices, checked in exact rational
// arithmetic on the stored doubles; clusters partition the casters; normal cones hold the normals.
// The one test translation unit with CGAL (its rational number type only).
#include "reference/metric/bounding_volumes.h"

#include <algorithm>
#include <numeric>

#include <CGAL/Gmpq.h>
#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "metric_test_cases.h"
#include "reference/metric/angular_distance.h"
#include "reference/metric/clustering.h"
#include "reference/metric/metric_shadows.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "tests/test_name.h"

namespace shadowcts::metric {
namespace {

using Rational = CGAL::Gmpq;

struct ExactPoint {
  Rational x, y, z;
  explicit ExactPoint(const glm::dvec3& p) : x(p.x), y(p.y), z(p.z) {}
  ExactPoint(Rational a, Rational b, Rational c) : x(a), y(b), z(c) {}
};

Rational dot(const ExactPoint& a, const ExactPoint& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
ExactPoint minus(const ExactPoint& a, const ExactPoint& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

// Exact squared distance from v to the segment [a, b] (a point when a == b).
Rational squared_distance_to_segment(const ExactPoint& v, const ExactPoint& a,
                                     const ExactPoint& b) {
  const ExactPoint ab = minus(b, a), av = minus(v, a);
  const Rational length_squared = dot(ab, ab);
  Rational t = length_squared == 0 ? Rational(0) : dot(av, ab) / length_squared;
  t = std::clamp(t, Rational(0), Rational(1));
  const ExactPoint closest(a.x + t * ab.x, a.y + t * ab.y, a.z + t * ab.z);
  const ExactPoint d = minus(v, closest);
  return dot(d, d);
}

void expect_exact_containment(const Case& c, const MetricOptions& options) {
  const ClusteredScene scene = cluster_scene(c, options);
  const Clustering& clustering = scene.clustering;
  const std::vector<int> orientations = closed_mesh_orientations(c);
  std::size_t capsules = 0;
  for (std::size_t k = 0; k < clustering.cluster_count(); ++k) {
    const ClusterVolume& volume = scene.volumes[k];
    capsules += volume.shape == VolumeShape::capsule;
    if (!options.capsules) {
      ASSERT_EQ(volume.shape, VolumeShape::sphere);
    }
    const ExactPoint a(volume.axis_begin), b(volume.axis_end), n(volume.slab_normal);
    const Rational radius_squared = Rational(volume.radius) * Rational(volume.radius);
    for (std::uint32_t i = clustering.cluster_begin[k]; i < clustering.cluster_begin[k + 1]; ++i) {
      const Triangle& t = c.triangles[clustering.triangles[i]];
      for (const glm::vec3& vertex : {t.v0, t.v1, t.v2}) {
        const ExactPoint v{glm::dvec3(vertex)};
        ASSERT_LE(squared_distance_to_segment(v, a, b), radius_squared)
            << c.name << " cluster " << k << " leaves a vertex outside its volume";
        const Rational height = dot(n, v);
        ASSERT_GE(height, Rational(volume.slab_min)) << c.name << " cluster " << k;
        ASSERT_LE(height, Rational(volume.slab_max)) << c.name << " cluster " << k;
      }
      // Outward normals (as the mesh's volume orients them) lie inside the normal cone.
      const glm::dvec3 normal =
          double(orientations[t.mesh] >= 0 ? 1 : -1) *
          glm::cross(glm::dvec3(t.v1) - glm::dvec3(t.v0), glm::dvec3(t.v2) - glm::dvec3(t.v0));
      const NormalCone& cone = scene.normal_cones[k];
      EXPECT_EQ(cone.cullable, orientations[t.mesh] != 0);
      EXPECT_LE(angle_between(cone.axis, normal), cone.half_angle + 1e-12) << c.name;
    }
  }
  if (options.capsules) {
    EXPECT_GT(capsules, 0u) << c.name;
  }
}

class BoundingVolumes : public ::testing::TestWithParam<std::string> {};

TEST_P(BoundingVolumes, ContainEveryVertexExactly) {
  const Case c = testing::load_fixture(GetParam(), 8).c;
  expect_exact_containment(c, parse_metric_variant("capsules"));
  expect_exact_containment(c, parse_metric_variant("spheres16"));
}

INSTANTIATE_TEST_SUITE_P(DefaultFixtures, BoundingVolumes,
                         ::testing::ValuesIn(testing::hard_shadow_fixtures()),
                         test_support::param_test_name);

// Stiff inputs: a sliver cluster far from the origin, collinear fans, one triangle.
TEST(BoundingVolumes, ContainStiffClustersExactly) {
  Case c;
  c.name = "stiff";
  c.meshes = {Mesh{"m", false, true}};
  const float far = 3.0e4f;
  for (int i = 0; i < 40; ++i) {
    const float x = far + float(i) * 0.37f;
    c.triangles.push_back({{x, far, far}, {x + 0.37f, far + 1e-3f, far}, {x, far, far + 2e-3f}, 0});
  }
  c.triangles.push_back({{1, 2, 3}, {1.5f, 2, 3}, {1, 2.5f, 3}, 0});
  expect_exact_containment(c, parse_metric_variant("capsules"));
  expect_exact_containment(c, parse_metric_variant("spheres"));
  expect_exact_containment(c, parse_metric_variant("capsules3"));
}

TEST(Clustering, PartitionsTheCastersIntoSmallSingleMeshClustersDeterministically) {
  const Case c = testing::load_fixture("gate_house.20k", 8).c;
  for (std::uint32_t max_triangles : {32u, 16u, 5u}) {
    ClusteringParameters parameters;
    parameters.max_triangles = max_triangles;
    parameters.seed = 3;
    const Clustering clustering = cluster_triangles(c, parameters);
    std::vector<std::uint32_t> seen = clustering.triangles;
    std::sort(seen.begin(), seen.end());
    std::vector<std::uint32_t> casters;
    for (std::size_t i = 0; i < c.triangles.size(); ++i)
      if (casts_shadow(c, i)) casters.push_back(std::uint32_t(i));
    EXPECT_EQ(seen, casters);  // every caster exactly once, nothing else
    for (std::size_t k = 0; k < clustering.cluster_count(); ++k) {
      EXPECT_GE(clustering.size(k), 1u);
      EXPECT_LE(clustering.size(k), max_triangles);
      for (std::uint32_t i = clustering.cluster_begin[k]; i < clustering.cluster_begin[k + 1]; ++i)
        EXPECT_EQ(c.triangles[clustering.triangles[i]].mesh, clustering.cluster_mesh[k]);
    }
    // Clusters should be reasonably full: hierarchical k-means does not shred chunks.
    EXPECT_LT(clustering.cluster_count(), 3 * casters.size() / max_triangles + 8);
    const Clustering again = cluster_triangles(c, parameters);
    EXPECT_EQ(again.triangles, clustering.triangles);
    EXPECT_EQ(again.cluster_begin, clustering.cluster_begin);
    parameters.seed = 4;
    EXPECT_NE(cluster_triangles(c, parameters).triangles, clustering.triangles);
  }
}

}  // namespace
}  // namespace shadowcts::metric
