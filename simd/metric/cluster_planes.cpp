#include "simd/metric/cluster_planes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/triangle_area.h"

namespace shadowcts::simd::metric {
namespace {

using Corners = std::array<glm::dvec3, 3>;

Corners corners(const CasterArrays& casters, std::uint32_t t) {
  return {glm::dvec3(casters.corner(t, 0)), glm::dvec3(casters.corner(t, 1)),
          glm::dvec3(casters.corner(t, 2))};
}

bool on_plane(const Corners& plane, const glm::dvec3& v) {
  return geometry::orientation(plane[0], plane[1], plane[2], v) == 0;
}

// The supporting plane of the cluster's first triangle of non-zero area, if every vertex of the
// cluster lies on it.
std::optional<Corners> flat_cluster_plane(const CasterArrays& casters,
                                          const shadowcts::metric::Clustering& clustering,
                                          std::size_t cluster) {
  const std::uint32_t begin = clustering.cluster_begin[cluster];
  const std::uint32_t end = clustering.cluster_begin[cluster + 1];
  std::optional<Corners> plane;
  for (std::uint32_t j = begin; j < end && !plane; ++j) {
    const std::uint32_t t = clustering.triangles[j];
    if (!triangle_has_zero_area(casters.corner(t, 0), casters.corner(t, 1), casters.corner(t, 2)))
      plane = corners(casters, t);
  }
  if (!plane) return std::nullopt;
  for (std::uint32_t j = begin; j < end; ++j)
    for (const glm::dvec3& v : corners(casters, clustering.triangles[j]))
      if (!on_plane(*plane, v)) return std::nullopt;
  return plane;
}

// A rounded key of a plane: its unit normal with the first non-zero component positive, and its
// offset, each to 2^-20 (of 1, or of `extent`, the largest coordinate of the flat clusters'
// defining corners). Coplanar clusters almost always share it; the exact test decides.
using PlaneKey = std::array<std::int64_t, 4>;

double largest_coordinate(const Corners& p) {
  double extent = 0.0;
  for (const glm::dvec3& v : p)
    extent = std::max({extent, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  return extent;
}

PlaneKey plane_key(const Corners& p, double extent) {
  glm::dvec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  const double first = n.x != 0.0 ? n.x : n.y != 0.0 ? n.y : n.z;
  if (first < 0.0) n = -n;
  const double offset = glm::dot(n, p[0]) / extent;
  // Non-finite values (a normal that underflowed) all map to one key: still decided exactly.
  const auto q = [](double x) {
    return std::isfinite(x) ? std::int64_t(std::llround(x * 0x1p20)) : std::int64_t(0);
  };
  return {q(n.x), q(n.y), q(n.z), q(offset)};
}

}  // namespace

ClusterPlanes cluster_planes(const CasterArrays& casters,
                             const shadowcts::metric::Clustering& clustering) {
  const std::size_t clusters = clustering.cluster_count();
  std::vector<std::optional<Corners>> flat(clusters);
  tbb::parallel_for(std::size_t(0), clusters,
                    [&](std::size_t k) { flat[k] = flat_cluster_plane(casters, clustering, k); });

  // Flat clusters sorted by key (then index), so that the ids do not depend on the schedule.
  double extent = 0.0;
  for (const std::optional<Corners>& plane : flat)
    if (plane) extent = std::max(extent, largest_coordinate(*plane));
  std::vector<std::pair<PlaneKey, std::uint32_t>> keyed;
  for (std::size_t k = 0; k < clusters; ++k)
    if (flat[k]) keyed.emplace_back(plane_key(*flat[k], extent), std::uint32_t(k));
  std::sort(keyed.begin(), keyed.end());

  ClusterPlanes out;
  out.of_cluster.assign(clusters, no_plane);
  std::uint32_t next_id = 0;
  for (std::size_t run = 0; run < keyed.size();) {
    std::size_t run_end = run;
    while (run_end < keyed.size() && keyed[run_end].first == keyed[run].first) ++run_end;
    // The distinct planes of one key, each with the cluster that first had it.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> planes;  // (id, cluster)
    for (std::size_t j = run; j < run_end; ++j) {
      const std::uint32_t k = keyed[j].second;
      const Corners& own = *flat[k];
      // The cluster lies in another's plane iff its own defining triangle does.
      const auto same = std::find_if(planes.begin(), planes.end(), [&](const auto& p) {
        const Corners& other = *flat[p.second];
        return on_plane(other, own[0]) && on_plane(other, own[1]) && on_plane(other, own[2]);
      });
      if (same != planes.end()) {
        out.of_cluster[k] = same->first;
      } else {
        planes.emplace_back(next_id, k);
        out.of_cluster[k] = next_id++;
      }
    }
    run = run_end;
  }

  out.of_triangle.assign(casters.size(), no_plane);
  tbb::parallel_for(std::size_t(0), clusters, [&](std::size_t k) {
    if (out.of_cluster[k] == no_plane) return;
    for (std::uint32_t j = clustering.cluster_begin[k]; j < clustering.cluster_begin[k + 1]; ++j) {
      const std::uint32_t t = clustering.triangles[j];
      if (!triangle_has_zero_area(casters.corner(t, 0), casters.corner(t, 1), casters.corner(t, 2)))
        out.of_triangle[t] = out.of_cluster[k];
    }
  });
  return out;
}

}  // namespace shadowcts::simd::metric
