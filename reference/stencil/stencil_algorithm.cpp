#include "reference/stencil/stencil_algorithm.h"

#include <atomic>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/light_on_caster.h"
#include "reference/stencil/crossing_reach.h"
#include "reference/stencil/receiver_rule.h"
#include "reference/stencil/shadow_volume.h"
#include "reference/stencil/silhouette.h"
#include "reference/stencil/view_grid.h"
#include "reference/stencil/volume_counting.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

using namespace stencil;

class StencilAlgorithm final : public VariantTableAlgorithm<stencil::CountingMode> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // build: occluders, silhouettes, volume faces and the view grid over them; query: the crossing
  // counts per sample.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    const CountingMode mode = variant.config;
    const HardShadowLight light = hard_shadow_light(c);
    check_receivers(c, samples);
    const glm::dvec3 eye(c.camera.position);

    AlgorithmOutput output;
    output.shadowed.assign(samples.samples.size(), 0);
    std::vector<std::uint32_t> faces_tested(samples.samples.size(), 0);
    std::atomic<std::uint64_t> quads_tested{0}, caps_tested{0}, rule_samples{0}, rule_candidates{0};
    std::uint64_t light_on_caster = 0;
    Occluders occluders;
    ShadowVolumes volumes;
    PhaseClock clock;
    run_with_thread_limit(c.parameters.threads, [&] {
      clock.restart();
      // A caster that contains the point light (exactly) has a degenerate volume and shadows
      // every sample it does not receive: it is no cap, and the rule is applied after counting.
      occluders = find_occluders(c, light, casters_containing_light(c));
      volumes = build_shadow_volumes(occluders, light, eye, samples);
      // z-pass never needs the dark caps (see volume_counting.h): leave them out of its grid.
      // The faces move out of `volumes` (filtered in place, order kept): one copy of them, the
      // largest per-triangle array of the run.
      std::vector<VolumeFace> faces = std::move(volumes.faces);
      if (mode == CountingMode::z_pass)
        std::erase_if(faces, [](const VolumeFace& f) { return f.kind == FaceKind::dark_cap; });
      std::vector<FaceEyeSides> sides(faces.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 1024),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t f = range.begin(); f != range.end(); ++f)
                            sides[f] = eye_sides(faces[f], eye, light);
                        });
      // Where along each sample's line a face's counted crossing can lie, for the grid's depth
      // bounds (crossing_reach.h).
      const double reach = sample_reach(eye, samples);
      std::vector<CrossingReach> reaches(faces.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, faces.size(), 1024),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t f = range.begin(); f != range.end(); ++f)
                            reaches[f] = crossing_reach(faces[f], sides[f], mode, volumes.extrusion,
                                                        light, eye, reach);
                        });
      const ViewGrid grid(c.camera, samples, faces, reaches, mode);
      // Each caster triangle's cap, for subtracting a receiver's own volume.
      std::vector<std::uint32_t> cap_of_triangle(c.triangles.size(), no_triangle);
      for (std::size_t k = 0; k < occluders.caps.size(); ++k)
        cap_of_triangle[occluders.caps[k].triangle] = std::uint32_t(k);
      const StencilReceiverRule rule(c, light, occluders, volumes.extrusion, mode, eye);
      clock.lap(build_phase);
      // The winding of one regular sample's p- without the receiver's own volume
      // (volume_counting.h) and, where that is non-zero, without the caps the receiver
      // half-space rule rejects (receiver_rule.h).
      const auto winding_of = [&](const ViewSample& s, FaceTally& tally, std::uint64_t& asked,
                                  std::uint64_t& candidates) {
        const glm::dvec3 p(s.position);
        int winding = 0;
        grid.for_each_candidate(p, [&](std::uint32_t f) {
          ++tally.faces;
          (faces[f].is_quad() ? tally.quads : tally.caps) += 1;
          std::array<glm::dvec3, 3> base;
          const bool dark = faces[f].kind == FaceKind::dark_cap;
          if (dark) base = dark_cap_base(occluders.caps[cap_of_triangle[faces[f].triangle]]);
          winding += count_crossings(faces[f], sides[f], mode, eye, p, light, volumes.extrusion,
                                     dark ? &base : nullptr);
        });
        const std::uint32_t own =
            s.receiver < cap_of_triangle.size() ? cap_of_triangle[s.receiver] : no_triangle;
        if (own != no_triangle)
          winding -=
              count_own_volume(occluders.caps[own], volumes.extrusion, mode, eye, p, light, tally);
        if (winding == 0 || s.receiver == no_receiver) return winding;
        const RuleOutcome outcome = rule.rejected(s.receiver, p, tally);
        ++asked;
        candidates += outcome.candidates;
        return outcome.every_cap_rejected ? 0 : winding - outcome.rejected;
      };
      phase_progress::begin(samples.samples.size(), "view samples");
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.samples.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          FaceTally tally;
                          std::uint64_t asked = 0, candidates = 0;
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                            const ViewSample& s = samples.samples[i];
                            if (s.sample_class != SampleClass::regular) continue;
                            tally.faces = 0;
                            output.shadowed[i] =
                                winding_of(s, tally, asked, candidates) != 0 ? 1 : 0;
                            faces_tested[i] = tally.faces;
                          }
                          // Integer sums: the totals do not depend on the partitioning.
                          quads_tested += tally.quads;
                          caps_tested += tally.caps;
                          rule_samples += asked;
                          rule_candidates += candidates;
                          phase_progress::advance(range.size());
                        });
      light_on_caster = shadow_samples_by_light_on_caster(c, samples, output.shadowed);
      clock.lap(query_phase);
    });
    output.phase_ms = clock.times();
    output.counters = {
        {"silhouette_edges", volumes.silhouette_edges}, {"caps", occluders.caps.size()},
        {"quads_tested", quads_tested.load()},          {"caps_tested", caps_tested.load()},
        {"rule_samples", rule_samples.load()},          {"rule_candidates", rule_candidates.load()},
        {"light_on_caster_samples", light_on_caster}};
    output.per_sample_counters = {{"faces_tested", std::move(faces_tested)}};
    return output;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_stencil() {
  return std::make_unique<StencilAlgorithm>(
      AlgorithmDescription{
          .id = "stencil",
          .backend = "reference",
          .summary = "software stencil shadow volumes: silhouette quads from exact-position "
                     "connectivity, exact crossing counts per sample; z-fail with caps, z-pass "
                     "from the eye",
          .capabilities = point_and_directional_hard_shadows},
      std::vector<AlgorithmVariant<stencil::CountingMode>>{
          {"zfail", stencil::CountingMode::z_fail}, {"zpass", stencil::CountingMode::z_pass}});
}

}  // namespace shadowcts
