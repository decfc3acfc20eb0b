#pragma once
// Clustering of the caster triangles (Deves et al. 2018, section 4): per mesh, triangles sorted
// along the Morton curve of their representative points and cut into chunks of 512, then each
// chunk split by hierarchical k-means with k-means++ seeding until a cluster holds at most
// max_triangles triangles.
//
// Element distance: the squared Euclidean distance between the centres of the triangles'
// axis-aligned bounding boxes, the representative points Meister and Bittner (2016) cluster by;
// the k-means centres are means of those points.
//
// Only triangles that can cast a shadow (caster mesh, non-zero area) are clustered: the others
// never block a shadow segment, so no cluster needs to hold them.
#include <cstdint>
#include <vector>

#include "shadowcts/case.h"

namespace shadowcts::metric {

struct ClusteringParameters {
  std::uint32_t max_triangles = 32;
  std::uint32_t chunk_size = 512;  // the paper's first, Morton-order level
  std::uint32_t branching = 8;     // k of each k-means split (fewer when fewer are needed)
  std::uint32_t kmeans_iterations = 8;
  std::uint64_t seed = 1;
};

struct Clustering {
  // Case triangle indices, cluster after cluster; cluster k holds
  // triangles[cluster_begin[k] .. cluster_begin[k + 1]).
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint32_t> cluster_begin{0};
  std::vector<std::uint32_t> cluster_mesh;  // each cluster's triangles come from one mesh

  std::size_t cluster_count() const { return cluster_mesh.size(); }
  std::uint32_t size(std::size_t k) const { return cluster_begin[k + 1] - cluster_begin[k]; }
};

// Deterministic for parameters.seed and independent of the thread count (chunks are clustered in
// parallel with seeds derived from their position).
Clustering cluster_triangles(const Case& c, const ClusteringParameters& parameters);

}  // namespace shadowcts::metric
