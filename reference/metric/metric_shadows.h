#pragma once
// The whole reference `metric` pipeline for one case (Deves et al. 2018, section 3): clustering
// and bounding volumes (a preprocess per mesh), then per light the light-space elements of the
// clusters that do not face away from it, the ternary metric tree, and one traversal per sample.
#include <cstdint>
#include <string>
#include <vector>

#include "reference/metric/bounding_volumes.h"
#include "reference/metric/clustering.h"
#include "reference/metric/counters.h"
#include "reference/metric/light_space_elements.h"
#include "reference/metric/metric_tree.h"
#include "reference/metric/normal_cones.h"
#include "shadowcts/algorithm.h"

namespace shadowcts::metric {

enum class TreeBuild { insertion, median };

struct MetricOptions {
  std::uint32_t max_triangles = 32;
  bool capsules = true;
  TreeBuild build = TreeBuild::insertion;
  bool normal_cone_culling = true;
};

// Variant names: "capsules", "spheres" or "median" (capsules, median build), each optionally
// followed by max_triangles, e.g. "capsules16". Throws std::invalid_argument otherwise.
MetricOptions parse_metric_variant(const std::string& variant);

// The light-independent preprocess.
struct ClusteredScene {
  Clustering clustering;
  std::vector<ClusterVolume> volumes;
  std::vector<NormalCone> normal_cones;
};

ClusteredScene cluster_scene(const Case& c, const MetricOptions& options);

// The per-light structure.
struct LightStructure {
  LightFrame frame;
  std::vector<LightSpaceElement> elements;
  MetricTree tree;
  std::uint64_t clusters_culled_facing_away = 0;
};

LightStructure build_light_structure(const Case& c, const ClusteredScene& scene,
                                     const MetricOptions& options);

struct MetricRun {
  AlgorithmOutput output;
  MetricCounters counters;
  double clustering_seconds = 0.0;  // clustering and bounding volumes
  double build_seconds = 0.0;       // elements and tree
  double traversal_seconds = 0.0;
  // Bytes of the per-cluster data (volume, normal cone, triangle range, element, tree node).
  std::size_t bytes_per_cluster = 0;
};

// Runs on c.parameters.threads threads (0: all); deterministic for c.parameters.seed and any
// thread count. Needs a point or directional light.
MetricRun run_metric(const Case& c, const ViewSamples& samples, const MetricOptions& options);

}  // namespace shadowcts::metric
