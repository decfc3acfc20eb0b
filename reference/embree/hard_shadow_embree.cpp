#include "reference/embree/hard_shadow_embree.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/embree/shadow_ray_packets.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {
namespace {

std::string power_of_two(double x) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g (2^%.1f)", x, std::log2(x));
  return text;
}

class EmbreeHardShadow final : public VariantTableAlgorithm<> {
 public:
  using VariantTableAlgorithm::VariantTableAlgorithm;

 private:
  // Embree intersects in float32, so its answers hold only where its products stay normal
  // floats: see embree_min_scale_exponent in the header and docs/specification.md.
  std::optional<std::string> input_problem(const Case& c, const ViewSamples&,
                                           const Variant&) const override {
    const double scale = c.scale();
    const double low = std::ldexp(1.0, embree_min_scale_exponent);
    const double high = std::ldexp(1.0, embree_max_scale_exponent);
    const std::string range = "outside Embree's float32 range 2^" +
                              std::to_string(embree_min_scale_exponent) + " <= S <= 2^" +
                              std::to_string(embree_max_scale_exponent) + ": ";
    if (!(scale >= low))
      return range + "the case scale S = " + power_of_two(scale) +
             " makes its ray/triangle products (of three coordinates) float32 denormals";
    if (scale > high)
      return range + "the case scale S = " + power_of_two(scale) +
             " makes its ray/triangle products (of three coordinates) overflow float32";
    if (c.light && c.light->kind != ShadowLightKind::point) {
      // The edge tests multiply two coordinates by the direction vector as given.
      const glm::vec3& d = c.light->direction;
      const double length = std::max({std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
      const double product = scale * scale * length;
      if (!(product >= low * low * low) || product > high * high * high)
        return range + "the light direction's largest component " + power_of_two(length) +
               " times S^2 = " + power_of_two(product) + " leaves the range 2^" +
               std::to_string(3 * embree_min_scale_exponent) + " ... 2^" +
               std::to_string(3 * embree_max_scale_exponent) + " of its products";
    }
    return std::nullopt;
  }

  // build: the Embree device and scene (geometry, BVH build, commit); query: the shadow rays.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant&) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    check_receivers(c, samples);
    AlgorithmOutput output;
    output.shadowed.assign(samples.samples.size(), 0);
    std::atomic<std::uint64_t> rays{0};
    PhaseClock clock;
    run_with_thread_limit(c.parameters.threads, [&] {
      clock.restart();
      const ShadowRayPackets tracer(c);
      clock.lap(build_phase);
      phase_progress::begin(scene.samples.size(), "regular samples");
      // Packets of consecutive regular samples: neighbouring pixels, coherent rays.
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.samples.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          std::array<std::uint32_t, ShadowRayPackets::width> packet;
                          std::size_t filled = 0;
                          std::uint64_t traced = 0;
                          for (std::size_t i = range.begin(); i != range.end(); ++i) {
                            if (samples.samples[i].sample_class != SampleClass::regular) continue;
                            packet[filled++] = std::uint32_t(i);
                            if (filled == packet.size()) {
                              tracer.trace(samples, packet, output.shadowed);
                              traced += filled;
                              filled = 0;
                            }
                          }
                          if (filled != 0) {
                            tracer.trace(samples, std::span(packet.data(), filled),
                                         output.shadowed);
                            traced += filled;
                          }
                          rays += traced;
                          phase_progress::advance(traced);
                        });
      clock.lap(query_phase);
    });
    output.counters = {{"rays", rays.load()}};
    output.phase_ms = clock.times();
    return output;
  }
};

}  // namespace

std::unique_ptr<Algorithm> make_embree_hard_shadow() {
  return std::make_unique<EmbreeHardShadow>(
      AlgorithmDescription{.id = "embree",
                           .backend = "embree",
                           .summary =
                               "Embree 3 occlusion rays in robust mode; a filter ignores the "
                               "receiver and applies the receiver half-space rule",
                           .capabilities = point_and_directional_hard_shadows},
      std::vector<AlgorithmVariant<>>{{"robust"}});
}

}  // namespace shadowcts
