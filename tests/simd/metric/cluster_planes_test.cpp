// simd/metric/cluster_planes: which clusters lie in one plane, decided exactly, on hand-built
// clusters whose answers are known: a floor split in two, a floor with one vertex the smallest
// float step above it, a plane parallel to the floor within the rounded key, a tilted plane in two
// clusters, and zero-area triangles.
#include <array>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "simd/metric/cluster_planes.h"

namespace shadowcts::simd::metric {
namespace {

using Corners = std::array<glm::vec3, 3>;

struct Clusters {
  CasterArrays casters;
  shadowcts::metric::Clustering clustering;

  void add(const std::vector<Corners>& triangles) {
    for (const Corners& t : triangles) {
      clustering.triangles.push_back(std::uint32_t(casters.size()));
      for (int k = 0; k < 3; ++k) {
        casters.x[k].push_back(t[k].x);
        casters.y[k].push_back(t[k].y);
        casters.z[k].push_back(t[k].z);
      }
      casters.mesh.push_back(0);
      casters.casts.push_back(1);
    }
    clustering.cluster_begin.push_back(std::uint32_t(clustering.triangles.size()));
    clustering.cluster_mesh.push_back(0);
  }
};

constexpr float step = 0x1p-149f;  // the smallest float above 0

Clusters hand_built_clusters() {
  Clusters c;
  // 0 and 1: the floor z = 0; cluster 1 also holds a zero-area triangle in it.
  c.add({{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}, {{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}}});
  c.add({{{{2, 0, 0}, {3, 0, 0}, {2, 1, 0}}}, {{{2, 0, 0}, {3, 0, 0}, {4, 0, 0}}}});
  // 2: the floor with one vertex the smallest step above it.
  c.add({{{{5, 0, 0}, {6, 0, 0}, {5, 1, 0}}}, {{{6, 0, 0}, {6, 1, step}, {5, 1, 0}}}});
  // 3: the plane z = 2^-30, parallel to the floor and under the key's resolution from it.
  c.add({{{{0, 0, 0x1p-30f}, {1, 0, 0x1p-30f}, {0, 1, 0x1p-30f}}}});
  // 4 and 5: the tilted plane x + y + z = 3, in two clusters of different triangles.
  c.add({{{{3, 0, 0}, {0, 3, 0}, {0, 0, 3}}}, {{{1, 1, 1}, {2, 1, 0}, {0, 2, 1}}}});
  c.add({{{{1, 2, 0}, {0, 1, 2}, {2, 0, 1}}}});
  // 6: zero-area triangles only (no plane to lie in).
  c.add({{{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}, {{{7, 7, 7}, {7, 7, 7}, {7, 7, 7}}}});
  // 7: a wall x = 0, standing on the floor.
  c.add({{{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}}}});
  return c;
}

TEST(ClusterPlanes, SameIdExactlyForClustersInOnePlane) {
  const Clusters c = hand_built_clusters();
  const ClusterPlanes planes = cluster_planes(c.casters, c.clustering);
  ASSERT_EQ(planes.of_cluster.size(), 8u);
  const std::vector<std::uint32_t>& id = planes.of_cluster;
  EXPECT_NE(id[0], no_plane);
  EXPECT_EQ(id[1], id[0]) << "two parts of the floor";
  EXPECT_EQ(id[2], no_plane) << "one vertex a float step above the floor";
  EXPECT_NE(id[3], no_plane);
  EXPECT_NE(id[3], id[0]) << "z = 2^-30 is not the floor";
  EXPECT_NE(id[4], no_plane);
  EXPECT_EQ(id[5], id[4]) << "the tilted plane in two clusters";
  EXPECT_NE(id[4], id[0]);
  EXPECT_NE(id[4], id[3]);
  EXPECT_EQ(id[6], no_plane) << "zero-area triangles only";
  EXPECT_NE(id[7], no_plane);
  EXPECT_NE(id[7], id[0]) << "the wall";
  EXPECT_NE(id[7], id[3]);
  EXPECT_NE(id[7], id[4]);
}

TEST(ClusterPlanes, TrianglesTakeTheirClustersPlaneUnlessTheirAreaIsZero) {
  const Clusters c = hand_built_clusters();
  const ClusterPlanes planes = cluster_planes(c.casters, c.clustering);
  ASSERT_EQ(planes.of_triangle.size(), c.casters.size());
  for (std::size_t k = 0; k < c.clustering.cluster_count(); ++k)
    for (std::uint32_t j = c.clustering.cluster_begin[k]; j < c.clustering.cluster_begin[k + 1];
         ++j) {
      const std::uint32_t t = c.clustering.triangles[j];
      const bool zero_area = (k == 1 && j == 3) || k == 6;
      EXPECT_EQ(planes.of_triangle[t], zero_area ? no_plane : planes.of_cluster[k])
          << "triangle " << t << " of cluster " << k;
    }
}

TEST(ClusterPlanes, SameIdsForAnyThreadCount) {
  // Many clusters of a few planes, so that the ids come from a sort over parallel results.
  Clusters c;
  for (int k = 0; k < 200; ++k) {
    const float z = float(k % 5);
    const float x = float(k);
    c.add({{{{x, 0, z}, {x + 1, 0, z}, {x, 1, z}}}, {{{x + 1, 0, z}, {x + 1, 1, z}, {x, 1, z}}}});
  }
  std::vector<std::uint32_t> ids[2];
  for (int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    ids[threads - 1] = cluster_planes(c.casters, c.clustering).of_cluster;
  }
  EXPECT_EQ(ids[0], ids[1]);
  for (int k = 0; k < 200; ++k) EXPECT_EQ(ids[0][k], ids[0][k % 5]) << "cluster " << k;
  for (int k = 1; k < 5; ++k) EXPECT_NE(ids[0][k], ids[0][0]) << "plane z = " << k;
}

}  // namespace
}  // namespace shadowcts::simd::metric
