#pragma once
// Which clusters lie in one plane, exactly, and which caster triangles lie in such a plane: the
// simd `metric`'s shortcut for the triangles that cannot shadow a sample by the receiver
// half-space rule (DESIGN.md). A caster triangle T that lies in the supporting plane of the
// sample's receiver r meets the sample's segment only in that plane, never strictly on the
// light's side of it, so it never blocks. On a tessellated floor the clusters a floor sample
// visits are mostly floor clusters in its receiver's plane (some 60 % of the cluster visits on the
// 1M-triangle fixtures with a floor); their triangles need no test. Light-independent: part of the
// per-model precomputation.
#include <cstdint>
#include <vector>

#include "reference/metric/clustering.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd::metric {

inline constexpr std::uint32_t no_plane = ~0u;

struct ClusterPlanes {
  // Per cluster: the id of the plane that holds every vertex of its triangles (decided with exact
  // orientation predicates), or no_plane. Two clusters have the same id only if they lie in the
  // same plane; two coplanar clusters may still have different ids (the ids come from a rounded
  // key), which only leaves the shortcut unused.
  std::vector<std::uint32_t> of_cluster;
  // Per caster triangle (CasterArrays index): its cluster's plane where that cluster has one and
  // the triangle's area is not zero (so that the plane is its own supporting plane), else
  // no_plane.
  std::vector<std::uint32_t> of_triangle;
};

// Deterministic for any thread count (on the caller's oneTBB arena).
ClusterPlanes cluster_planes(const CasterArrays& casters,
                             const shadowcts::metric::Clustering& clustering);

}  // namespace shadowcts::simd::metric
