#include "simd/ptsv/ptsv_algorithm.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "reference/light_on_caster.h"
#include "reference/ptsv/counters.h"
#include "reference/ptsv/hdb2011.h"
#include "reference/ptsv/ptsv_algorithm.h"
#include "reference/ptsv/triangle_setup.h"
#include "reference/ptsv/two_pass.h"
#include "shadowcts/errors.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/variant_table_algorithm.h"
#include "simd/ptsv/cluster_keys.h"
#include "simd/ptsv/receiver_rule.h"
#include "simd/ptsv/traversal.h"
#include "simd/ptsv/triangle_setup.h"

namespace shadowcts {
namespace {

namespace ref = ::shadowcts::ptsv;
namespace port = ::shadowcts::simd::ptsv;

using ref::VariantConfig;

// The reference's variants that this backend ports.
const std::vector<AlgorithmVariant<VariantConfig>> ported_variants =
    select_variants(ptsv_variants(), {"twopass", "explicit+planes", "implicit"});

const VariantConfig& variant_config(const std::string& variant) {
  return find_variant(ported_variants, variant, "ptsv/simd").config;
}

double max_abs(const glm::dvec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// The reference's scene bound: the case's scale (the prepared scene's copy of Case::scale) and
// every regular sample (max is exact in any order).
double scene_bound(const PreparedScene& scene) {
  const RegularSamples& s = scene.samples;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, s.size(), 8192), scene.scale,
      [&](const tbb::blocked_range<std::size_t>& r, double bound) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          bound = std::max(bound, max_abs(glm::dvec3(s.position(i))));
        return bound;
      },
      [](double a, double b) { return std::max(a, b); });
}

// The reference's checks of run(): a point or directional light (hard_shadow_light's words),
// receivers that name triangles, one sample per pixel.
void check_inputs(const PreparedScene& scene) {
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  if (!c.light) throw InputError(c.source, "light", "a hard-shadow case needs a shadow light");
  if (c.light->kind == ShadowLightKind::sun_disk)
    throw InputError(c.source, "light",
                     "hard shadows need a point or directional light, not a sun disk");
  if (c.light->kind == ShadowLightKind::directional && c.light->direction == glm::vec3(0.0f))
    throw InputError(c.source, "light.direction", "has zero length");
  // The regular samples' receivers from the prepared arrays (3.7 MB at 1080p), not from the view
  // samples (83 MB): the same samples in the same order.
  const RegularSamples& regular = scene.samples;
  for (std::size_t i = 0; i < regular.size(); ++i) {
    const std::uint32_t receiver = regular.receiver[i];
    if (receiver != no_receiver && receiver >= c.triangles.size())
      throw InputError(c.source, "view sample " + std::to_string(regular.index[i]),
                       "receiver " + std::to_string(receiver) + " is not a triangle index");
  }
  if (samples.width == 0 || samples.height == 0 ||
      samples.samples.size() != std::size_t(samples.width) * samples.height)
    throw InputError(c.source, "view samples", "not one sample per pixel");
}

struct Built {
  ref::KeyLayoutResult layout;
  port::ClusterKeys keys;
  port::Hierarchy hierarchy;
};

Built build(const PreparedScene& scene, const ref::ViewFrame& frame, const port::ReceiverRule& rule,
            const VariantConfig& config) {
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  Built b;
  b.layout = ref::make_cluster_key_layout(c.camera, samples.width, samples.height);
  if (!b.layout.problem.empty()) throw InputError(c.source, "camera", b.layout.problem);
  b.keys = port::assign_cluster_keys(b.layout.layout, frame, scene, config.implicit_cells());
  if (!b.keys.problem.empty()) throw InputError(c.source, "view samples", b.keys.problem);
  b.hierarchy = port::build_hierarchy(b.layout.layout, frame, scene, b.keys.key,
                                      rule.reject_reach(), config.implicit_cells());
  return b;
}

// The reference's implicit_corner_bound: the root's children contain all deeper cells.
double implicit_corner_bound(const port::Hierarchy& h, const ref::ViewFrame& frame) {
  double bound = 0.0;
  const int level = std::min(1, h.leaf_level());
  for (std::uint32_t index : h.levels[std::size_t(level)].index)
    for (const glm::dvec3& corner :
         ref::cell_corners(frame, ref::implicit_node_cell(h.layout, level, index)))
      bound = std::max(bound, max_abs(corner));
  return bound;
}

class SimdPtsv final : public VariantTableAlgorithm<VariantConfig> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  std::optional<std::string> input_problem(const Case& c, const ViewSamples& samples,
                                           const Variant& variant) const override {
    if (samples.width == 0 || samples.height == 0 ||
        samples.samples.size() != std::size_t(samples.width) * samples.height)
      return "the view samples are not one per pixel";
    const ref::ViewFrame frame = ref::make_view_frame(c.camera, samples.width, samples.height);
    const ref::KeyLayoutResult layout =
        ref::make_cluster_key_layout(c.camera, samples.width, samples.height);
    if (!layout.problem.empty()) return layout.problem;
    const std::string problem =
        ref::assign_cluster_keys(layout.layout, frame, samples, variant.config.implicit_cells())
            .problem;
    if (!problem.empty()) return problem;
    return std::nullopt;
  }

  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const VariantConfig& config = variant.config;
    check_inputs(scene);
    PhaseClock clock;
    const ref::ViewFrame frame = ref::make_view_frame(c.camera, samples.width, samples.height);
    const double bound = scene_bound(scene);
    const port::ReceiverRule rule(scene);
    const Built built = build(scene, frame, rule, config);
    clock.lap(build_phase);

    // The hierarchy answers which meshes' boxes hold samples (front-face culling).
    ref::SetupOptions setup;
    setup.extra_planes = config.extra_planes;
    const auto culled =
        port::front_face_culling_meshes(scene, built.hierarchy, rule.reject_reach());
    const port::PackedVolumes volumes = port::set_up_shadow_volumes(c, culled, setup, bound);
    const port::Hierarchy& h = built.hierarchy;
    const double node_bound =
        config.implicit_cells() ? std::max(bound, implicit_corner_bound(h, frame)) : bound;
    port::TraversalInputs inputs;
    inputs.hierarchy = &h;
    inputs.volumes = &volumes;
    inputs.rule = &rule;
    inputs.source = &c;
    inputs.scene = &scene;
    inputs.config.implicit_cells = config.implicit_cells();
    inputs.config.extra_planes = config.extra_planes;
    inputs.config.job_level = config.two_pass ? ref::default_job_level(h.leaf_level()) : -1;
    inputs.tolerances = ref::NodeTolerances::for_bounds(node_bound, bound);
    clock.lap(query_phase);

    AlgorithmOutput output;
    output.shadowed.assign(samples.samples.size(), 0);
    ref::TraversalCounters counters;
    port::traverse(inputs, output.shadowed, counters);
    clock.lap(query_phase);
    const std::uint64_t light_on_caster =
        shadow_samples_by_light_on_caster(c, samples, output.shadowed);

    output.counters = ref::to_counters(counters, volumes.counts,
                                       {.nodes = h.node_count(),
                                        .levels = std::uint64_t(h.leaf_level()) + 1,
                                        .key_bits = std::uint64_t(built.layout.layout.key_bits())},
                                       light_on_caster);
    output.phase_ms = clock.times();
    return output;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_simd_ptsv() {
  return std::make_unique<SimdPtsv>(
      AlgorithmDescription{
          .id = "ptsv",
          .backend = "simd",
          .summary = "per-triangle shadow volumes through the view-sample cluster hierarchy "
                     "(Sintorn 2014), Highway lanes over a node's children and a leaf's samples, "
                     "oneTBB over nodes and two-pass jobs; the reference's keys, nodes, counters "
                     "and mask",
          .capabilities = point_and_directional_hard_shadows},
      ported_variants);
}

namespace simd::ptsv {

Structures build_structures(const PreparedScene& scene, const std::string& variant) {
  const VariantConfig& config = variant_config(variant);
  check_inputs(scene);
  const ref::ViewFrame frame = ref::make_view_frame(scene.source.camera, scene.view_samples.width,
                                                    scene.view_samples.height);
  const port::ReceiverRule rule(scene);
  Built b = build(scene, frame, rule, config);
  Structures s;
  s.key = keys_per_view_sample(scene, b.keys.key);
  s.hierarchy = std::move(b.hierarchy);
  return s;
}

}  // namespace simd::ptsv
}  // namespace shadowcts
