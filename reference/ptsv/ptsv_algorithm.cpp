#include "reference/ptsv/ptsv_algorithm.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "reference/light_on_caster.h"
#include "reference/ptsv/cluster_keys.h"
#include "reference/ptsv/counters.h"
#include "reference/ptsv/hdb2011.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/node_test.h"
#include "reference/ptsv/receiver_rule.h"
#include "reference/ptsv/traversal.h"
#include "reference/ptsv/triangle_setup.h"
#include "reference/ptsv/two_pass.h"
#include "reference/ptsv/view_frame.h"
#include "shadowcts/errors.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

using namespace ptsv;

double max_abs(const glm::dvec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// The largest |coordinate| of an implicit cell the traversal may test (the root's children
// contain all deeper cells).
double implicit_corner_bound(const ClusterHierarchy& h, const ViewFrame& frame) {
  double bound = 0.0;
  const int level = std::min(1, h.leaf_level());
  for (std::uint32_t index : h.level(level).index)
    for (const glm::dvec3& corner :
         cell_corners(frame, implicit_node_cell(h.layout(), level, index)))
      bound = std::max(bound, max_abs(corner));
  return bound;
}

class Ptsv final : public VariantTableAlgorithm<VariantConfig> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // Why the variant's structures cannot hold these samples.
  std::optional<std::string> input_problem(const Case& c, const ViewSamples& samples,
                                           const Variant& variant) const override {
    const std::string problem = structure_problem(c, samples, variant.config);
    if (!problem.empty()) return problem;
    return std::nullopt;
  }

  // build: cluster keys and the hierarchy (hdb2011: the hierarchical depth buffer); query: the
  // per-triangle work, shadow-volume setup and traversal (one kernel in the paper).
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const VariantConfig& config = variant.config;
    hard_shadow_light(c);  // throws InputError without a point or directional light
    check_receivers(c, samples);
    if (samples.width == 0 || samples.height == 0 ||
        samples.samples.size() != std::size_t(samples.width) * samples.height)
      throw InputError(c.source, "view samples", "not one sample per pixel");
    PhaseClock clock;
    const ViewFrame frame = make_view_frame(c.camera, samples.width, samples.height);
    const double bound = scene_bound(c, samples);
    const ReceiverRule rule(c, samples);
    clock.lap(build_phase);

    SetupOptions setup;
    setup.extra_planes = !config.depth_buffer_2011 && config.extra_planes;
    setup.silhouette_planes = config.depth_buffer_2011;
    SetupCounts setup_counts;
    const std::vector<ShadowVolume> volumes = set_up_shadow_volumes(
        c, front_face_culling_meshes(c, samples, rule.reject_reach()), setup, bound, setup_counts);
    clock.lap(query_phase);

    AlgorithmOutput output;
    output.shadowed.assign(samples.samples.size(), 0);
    TraversalCounters counters;
    HierarchyShape shape;
    if (config.depth_buffer_2011) {
      HierarchicalDepthBuffer buffer(frame, samples, &rule);
      if (!buffer.problem().empty()) throw InputError(c.source, "view samples", buffer.problem());
      const NodeTolerances tolerances =
          NodeTolerances::for_bounds(std::max(bound, buffer.corner_bound()), bound);
      clock.lap(build_phase);
      phase_progress::begin(volumes.size(), "shadow volumes");
      {
        phase_progress::Batch done;
        for (const ShadowVolume& volume : volumes) {
          buffer.traverse(volume, tolerances, output.shadowed, counters);
          done.add();
        }
      }
      buffer.merge(output.shadowed);
      clock.lap(query_phase);
      for (int l = 0; l < buffer.level_count(); ++l)
        for (std::uint8_t occupied : buffer.level(l).occupied) shape.nodes += occupied;
      shape.levels = std::uint64_t(buffer.level_count());
    } else {
      const KeyLayoutResult layout =
          make_cluster_key_layout(c.camera, samples.width, samples.height);
      if (!layout.problem.empty()) throw InputError(c.source, "camera", layout.problem);
      const ClusterKeys keys = assign_cluster_keys(layout.layout, frame, samples,
                                                   config.bounds == NodeBounds::implicit_cells);
      if (!keys.problem.empty()) throw InputError(c.source, "view samples", keys.problem);
      ClusterHierarchy hierarchy(layout.layout, keys.key, samples, rule.reject_reach());
      const double node_bound = config.bounds == NodeBounds::implicit_cells
                                    ? std::max(bound, implicit_corner_bound(hierarchy, frame))
                                    : bound;
      ClusterTraversal traversal(hierarchy, frame, samples, rule, config.bounds,
                                 config.extra_planes, NodeTolerances::for_bounds(node_bound, bound),
                                 output.shadowed, counters);
      clock.lap(build_phase);
      if (config.two_pass) {
        traverse_two_pass(traversal, volumes, default_job_level(hierarchy.leaf_level()), counters);
      } else {
        phase_progress::begin(volumes.size(), "shadow volumes");
        phase_progress::Batch done;
        for (const ShadowVolume& volume : volumes) {
          traversal.traverse_from_root(volume);
          done.add();
        }
      }
      traversal.mark_trivially_accepted(keys.key);
      clock.lap(query_phase);
      shape = {.nodes = hierarchy.node_count(),
               .levels = std::uint64_t(hierarchy.leaf_level()) + 1,
               .key_bits = std::uint64_t(layout.layout.key_bits())};
    }
    const std::uint64_t light_on_caster =
        shadow_samples_by_light_on_caster(c, samples, output.shadowed);

    output.counters = to_counters(counters, setup_counts, shape, light_on_caster);
    output.phase_ms = clock.times();
    return output;
  }

  // Why the variant's structures cannot hold these samples, or "".
  static std::string structure_problem(const Case& c, const ViewSamples& samples,
                                       const VariantConfig& config) {
    if (samples.width == 0 || samples.height == 0 ||
        samples.samples.size() != std::size_t(samples.width) * samples.height)
      return "the view samples are not one per pixel";
    const ViewFrame frame = make_view_frame(c.camera, samples.width, samples.height);
    if (config.depth_buffer_2011) return HierarchicalDepthBuffer(frame, samples, nullptr).problem();
    const KeyLayoutResult layout = make_cluster_key_layout(c.camera, samples.width, samples.height);
    if (!layout.problem.empty()) return layout.problem;
    return assign_cluster_keys(layout.layout, frame, samples,
                               config.bounds == NodeBounds::implicit_cells)
        .problem;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_ptsv() {
  return std::make_unique<Ptsv>(
      AlgorithmDescription{
          .id = "ptsv",
          .backend = "reference",
          .summary = "per-triangle shadow volumes through the view-sample cluster hierarchy "
                     "(Sintorn 2014): implicit/explicit bounds, extra culling planes, two-pass "
                     "traversal; hdb2011: the 2011 hierarchical-depth-buffer PTSV. Front-face "
                     "culling for closed meshes clear of the camera",
          .capabilities = point_and_directional_hard_shadows},
      ptsv_variants());
}

std::vector<AlgorithmVariant<ptsv::VariantConfig>> ptsv_variants() {
  using ptsv::NodeBounds;
  return {
      {"twopass", {false, NodeBounds::explicit_boxes, true, true}},
      {"implicit", {false, NodeBounds::implicit_cells, false, false}},
      {"implicit+planes", {false, NodeBounds::implicit_cells, true, false}},
      {"explicit", {false, NodeBounds::explicit_boxes, false, false}},
      {"explicit+planes", {false, NodeBounds::explicit_boxes, true, false}},
      {"hdb2011", {true, NodeBounds::implicit_cells, false, false}},
  };
}

namespace ptsv {

Counters to_counters(const TraversalCounters& traversal, const SetupCounts& setup,
                     const HierarchyShape& hierarchy, std::uint64_t light_on_caster_samples) {
  return {{"test_and_set_operations", traversal.test_and_set()},
          {"node_tests", traversal.node_tests},
          {"sample_tests", traversal.sample_tests},
          {"nodes_visited", traversal.nodes_visited},
          {"trivial_accepts", traversal.trivial_accepts},
          {"trivial_rejects", traversal.trivial_rejects},
          {"culling_plane_rejects", traversal.culling_plane_rejects},
          {"first_pass_jobs", traversal.first_pass_jobs},
          {"second_pass_jobs", traversal.second_pass_jobs},
          {"shadow_volumes", setup.volumes},
          {"front_faces_culled", setup.front_faces_culled},
          {"edge_on_triangles", setup.edge_on},
          {"zero_area_triangles", setup.zero_area},
          {"culling_planes", setup.extra_planes + setup.silhouette_planes},
          {"hierarchy_nodes", hierarchy.nodes},
          {"hierarchy_levels", hierarchy.levels},
          {"key_bits", hierarchy.key_bits},
          {"light_on_caster_samples", light_on_caster_samples}};
}

}  // namespace ptsv

}  // namespace shadowcts
