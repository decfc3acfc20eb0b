#include "reference/metric/clustering.h"

#include <algorithm>
#include <array>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "reference/metric/seeded_random.h"
#include "shadowcts/geometry/morton.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::metric {
namespace {

// Centre of the triangle's axis-aligned bounding box (Meister and Bittner 2016).
glm::dvec3 representative_point(const Triangle& t) {
  const glm::dvec3 lo = glm::min(glm::min(glm::dvec3(t.v0), glm::dvec3(t.v1)), glm::dvec3(t.v2));
  const glm::dvec3 hi = glm::max(glm::max(glm::dvec3(t.v0), glm::dvec3(t.v1)), glm::dvec3(t.v2));
  return 0.5 * (lo + hi);
}

double squared_distance(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 d = a - b;
  return glm::dot(d, d);
}

std::uint32_t nearest_centre(const glm::dvec3& point, const std::vector<glm::dvec3>& centres) {
  std::uint32_t best = 0;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::uint32_t k = 0; k < centres.size(); ++k) {
    const double d = squared_distance(point, centres[k]);
    if (d < best_distance) {  // ties go to the lowest index: deterministic
      best_distance = d;
      best = k;
    }
  }
  return best;
}

// k-means++ seeding (Arthur and Vassilvitskii 2007): each new centre is drawn with probability
// proportional to its squared distance to the nearest centre chosen so far, which spreads the
// centres apart (the paper: "chosen ... in order to maximize its distance to the others").
// Returns fewer than k centres when the points have fewer distinct positions.
std::vector<glm::dvec3> seed_centres(const std::vector<glm::dvec3>& points, std::uint32_t k,
                                     std::mt19937_64& rng) {
  std::vector<glm::dvec3> centres{points[uniform_index(rng, points.size())]};
  std::vector<double> nearest(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    nearest[i] = squared_distance(points[i], centres[0]);
  while (centres.size() < k) {
    double total = 0.0;
    for (double d : nearest) total += d;
    if (!(total > 0.0)) break;
    const double target = uniform_unit(rng) * total;
    std::size_t chosen = points.size();
    double cumulative = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (nearest[i] == 0.0) continue;
      chosen = i;  // the last candidate absorbs the rounding of the cumulative sum
      cumulative += nearest[i];
      if (cumulative > target) break;
    }
    centres.push_back(points[chosen]);
    for (std::size_t i = 0; i < points.size(); ++i)
      nearest[i] = std::min(nearest[i], squared_distance(points[i], centres.back()));
  }
  return centres;
}

// Lloyd iterations from k-means++ centres; returns each point's label.
std::vector<std::uint32_t> k_means(const std::vector<glm::dvec3>& points, std::uint32_t k,
                                   std::uint32_t iterations, std::mt19937_64& rng) {
  std::vector<glm::dvec3> centres = seed_centres(points, k, rng);
  std::vector<std::uint32_t> labels(points.size(), 0);
  for (std::uint32_t iteration = 0; iteration < iterations; ++iteration) {
    bool changed = iteration == 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::uint32_t label = nearest_centre(points[i], centres);
      changed |= label != labels[i];
      labels[i] = label;
    }
    if (!changed) break;
    std::vector<glm::dvec3> sums(centres.size(), glm::dvec3(0.0));
    std::vector<std::uint32_t> counts(centres.size(), 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      sums[labels[i]] += points[i];
      ++counts[labels[i]];
    }
    for (std::size_t j = 0; j < centres.size(); ++j)
      if (counts[j] > 0) centres[j] = sums[j] / double(counts[j]);
  }
  return labels;
}

struct ChunkClusters {
  std::vector<std::uint32_t> triangles;     // reordered chunk triangles
  std::vector<std::uint32_t> cluster_size;  // consecutive clusters
};

// Hierarchical k-means of one chunk; clusters come out in depth-first order.
ChunkClusters cluster_chunk(const std::vector<std::uint32_t>& chunk,
                            const std::vector<glm::dvec3>& points_of_chunk,
                            const ClusteringParameters& parameters, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint32_t> ids = chunk;
  std::vector<glm::dvec3> points = points_of_chunk;
  ChunkClusters result;
  std::vector<std::pair<std::size_t, std::size_t>> ranges{{0, ids.size()}};
  while (!ranges.empty()) {
    const auto [begin, end] = ranges.back();
    ranges.pop_back();
    const std::size_t n = end - begin;
    if (n <= parameters.max_triangles) {
      result.cluster_size.push_back(std::uint32_t(n));
      continue;
    }
    const auto wanted =
        std::uint32_t((n + parameters.max_triangles - 1) / parameters.max_triangles);
    const std::uint32_t k = std::clamp<std::uint32_t>(wanted, 2, parameters.branching);
    const std::vector<glm::dvec3> range_points(points.begin() + std::ptrdiff_t(begin),
                                               points.begin() + std::ptrdiff_t(end));
    const std::vector<std::uint32_t> labels =
        k_means(range_points, k, parameters.kmeans_iterations, rng);
    // Stable regrouping by label keeps the Morton order inside each group.
    std::vector<std::size_t> group_begin(k + 1, 0);
    for (std::uint32_t label : labels) ++group_begin[label + 1];
    for (std::uint32_t j = 0; j < k; ++j) group_begin[j + 1] += group_begin[j];
    std::vector<std::uint32_t> grouped_ids(n);
    std::vector<glm::dvec3> grouped_points(n);
    std::vector<std::size_t> cursor(group_begin.begin(), group_begin.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t to = cursor[labels[i]]++;
      grouped_ids[to] = ids[begin + i];
      grouped_points[to] = points[begin + i];
    }
    std::copy(grouped_ids.begin(), grouped_ids.end(), ids.begin() + std::ptrdiff_t(begin));
    std::copy(grouped_points.begin(), grouped_points.end(), points.begin() + std::ptrdiff_t(begin));
    std::vector<std::pair<std::size_t, std::size_t>> groups;
    for (std::uint32_t j = 0; j < k; ++j)
      if (group_begin[j + 1] > group_begin[j])
        groups.push_back({begin + group_begin[j], begin + group_begin[j + 1]});
    // Coincident representative points cannot be separated by distance: halve in Morton order so
    // that the recursion always progresses.
    if (groups.size() < 2) groups = {{begin, begin + n / 2}, {begin + n / 2, end}};
    // Pushed in reverse so that the groups are finished in order.
    for (auto g = groups.rbegin(); g != groups.rend(); ++g) ranges.push_back(*g);
  }
  result.triangles = std::move(ids);
  return result;
}

}  // namespace

Clustering cluster_triangles(const Case& c, const ClusteringParameters& parameters) {
  if (parameters.max_triangles == 0 || parameters.chunk_size == 0 || parameters.branching < 2)
    throw std::invalid_argument(
        "metric clustering: max_triangles, chunk_size >= 1, branching >= 2");
  std::vector<std::vector<std::uint32_t>> mesh_triangles(c.meshes.size());
  for (std::size_t i = 0; i < c.triangles.size(); ++i)
    if (casts_shadow(c, i)) mesh_triangles[c.triangles[i].mesh].push_back(std::uint32_t(i));

  struct Chunk {
    std::uint32_t mesh;
    std::vector<std::uint32_t> triangles;
    std::vector<glm::dvec3> points;
  };
  std::vector<Chunk> chunks;
  for (std::uint32_t mesh = 0; mesh < mesh_triangles.size(); ++mesh) {
    const std::vector<std::uint32_t>& ids = mesh_triangles[mesh];
    if (ids.empty()) continue;
    std::vector<glm::dvec3> points(ids.size());
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      points[i] = representative_point(c.triangles[ids[i]]);
      lo = glm::min(lo, points[i]);
      hi = glm::max(hi, points[i]);
    }
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
      order[i] = {geometry::morton_code_in_box(points[i], lo, hi - lo), std::uint32_t(i)};
    std::sort(order.begin(), order.end());  // ties broken by position: deterministic
    for (std::size_t start = 0; start < order.size(); start += parameters.chunk_size) {
      Chunk chunk;
      chunk.mesh = mesh;
      const std::size_t stop = std::min(order.size(), start + parameters.chunk_size);
      for (std::size_t i = start; i < stop; ++i) {
        chunk.triangles.push_back(ids[order[i].second]);
        chunk.points.push_back(points[order[i].second]);
      }
      chunks.push_back(std::move(chunk));
    }
  }

  std::vector<ChunkClusters> clustered(chunks.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks.size()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        clustered[i] = cluster_chunk(chunks[i].triangles, chunks[i].points,
                                                     parameters, mix_seed(parameters.seed, i));
                    });

  Clustering clustering;
  for (std::size_t i = 0; i < chunks.size(); ++i) {
    clustering.triangles.insert(clustering.triangles.end(), clustered[i].triangles.begin(),
                                clustered[i].triangles.end());
    for (std::uint32_t size : clustered[i].cluster_size) {
      clustering.cluster_begin.push_back(clustering.cluster_begin.back() + size);
      clustering.cluster_mesh.push_back(chunks[i].mesh);
    }
  }
  return clustering;
}

}  // namespace shadowcts::metric
