#include "simd/softtile/softtile_gather.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

namespace shadowcts::simd::softtile {

namespace ref = shadowcts::softtile;

ref::Gathered gather(const Case& c, const ViewSamples& samples) {
  const ref::GatherFrame frame = ref::gather_frame(c, samples);
  ref::Gathered out;
  out.sun = frame.sun;
  out.light_space = frame.light_space;
  if (!frame.any_sample) return out;
  // Where the clusters start: a scan of the mesh ids (a cluster ends where its mesh does).
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < c.triangles.size(); i = ref::cluster_end(c, i)) starts.push_back(i);
  starts.push_back(c.triangles.size());
  // Blocks of whole clusters of about 2^14 triangles (1.2 MB), fixed by the case (not the threads),
  // each gathered into its own list and then joined in block order. A block's list is reserved once
  // for every triangle of its clusters: grown, it was copied into fresh pages, and each fresh
  // 4 KiB page is a fault (huge_pages.h). Blocks of a huge page or more measured slower.
  constexpr std::size_t block_triangles = std::size_t(1) << 14;
  const std::size_t clusters = starts.size() - 1;
  std::vector<std::size_t> block_start{0};  // in clusters
  for (std::size_t k = 0; k < clusters; ++k)
    if (starts[k + 1] - starts[block_start.back()] >= block_triangles || k + 1 == clusters)
      block_start.push_back(k + 1);
  struct Part {
    ref::GatheredTriangles triangles;
    std::vector<ref::GatheredCluster> clusters;
    ref::GatherCounts counts;
    std::size_t triangle_offset = 0, cluster_offset = 0;
  };
  std::vector<Part> parts(block_start.size() - 1);
  tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t b) {
    Part& part = parts[b];
    const std::size_t first = block_start[b], last = block_start[b + 1];
    part.triangles.reserve(starts[last] - starts[first]);
    for (std::size_t k = first; k < last; ++k) {
      const ref::GatheredCluster cluster =
          ref::gather_cluster(c, frame, starts[k], starts[k + 1], part.triangles, part.counts);
      if (cluster.count > 0) part.clusters.push_back(cluster);
    }
  });
  std::size_t triangles = 0, kept_clusters = 0;
  for (Part& part : parts) {
    part.triangle_offset = triangles;
    part.cluster_offset = kept_clusters;
    triangles += part.triangles.size();
    kept_clusters += part.clusters.size();
    out += part.counts;
  }
  out.triangles.resize(triangles);
  out.clusters.resize(kept_clusters);
  tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t b) {
    const Part& part = parts[b];
    std::copy(part.triangles.begin(), part.triangles.end(),
              out.triangles.begin() + std::ptrdiff_t(part.triangle_offset));
    for (std::size_t k = 0; k < part.clusters.size(); ++k) {
      ref::GatheredCluster cluster = part.clusters[k];
      cluster.first += std::uint32_t(part.triangle_offset);
      out.clusters[part.cluster_offset + k] = cluster;
    }
  });
  return out;
}

}  // namespace shadowcts::simd::softtile
