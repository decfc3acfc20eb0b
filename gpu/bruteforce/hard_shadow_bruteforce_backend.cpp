#include "gpu/bruteforce/hard_shadow_bruteforce_backend.h"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/bruteforce/hard_shadow_bruteforce.h"
#include "reference/light_on_caster.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts {

BruteforceShadowInput bruteforce_kernel_input(const Case& c, const ViewSamples& samples,
                                              std::vector<std::size_t>& regular_samples) {
  BruteforceShadowInput input;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& sample = samples.samples[i];
    if (sample.sample_class != SampleClass::regular) continue;
    regular_samples.push_back(i);
    input.sample_positions.push_back(sample.position);
    input.sample_receivers.push_back(sample.receiver);
    BruteforceReceiver receiver;
    if (sample.receiver != no_receiver) {
      const Triangle& r = c.triangles[sample.receiver];
      receiver = {r.v0, r.v1, r.v2};
    }
    input.sample_receiver_triangles.push_back(receiver);
  }
  for (std::size_t t = 0; t < c.triangles.size(); ++t) {
    const Triangle& triangle = c.triangles[t];
    if (!c.meshes.at(triangle.mesh).caster) continue;
    input.casters.push_back({triangle.v0, triangle.v1, triangle.v2, static_cast<std::uint32_t>(t)});
  }
  // A sun disk is shadowed as a directional light from its centre direction (the runner decides
  // whether such hard shadows are compared).
  const ShadowLight& light = c.light.value();
  input.directional_light = light.kind != ShadowLightKind::point;
  input.light = input.directional_light ? light.direction : light.position;
  return input;
}

namespace {

struct ExactFallback {
  std::uint64_t samples = 0, predicate_calls = 0;
};

// Decides the given regular samples as the reference brute force does, in parallel: beside-edge
// samples are common on finely tessellated models (most samples of model.spider).
ExactFallback decide_exactly(const PreparedScene& scene, const std::vector<std::size_t>& unsure,
                             std::vector<std::uint8_t>& shadowed) {
  ExactFallback fallback;
  if (unsure.empty()) return fallback;
  const ExactBruteforce exact(scene);
  fallback.samples = unsure.size();
  std::atomic<std::uint64_t> predicate_calls{0};
  phase_progress::begin(unsure.size(), "samples", "the exact fallback");
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, unsure.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::uint64_t pairs = 0, calls = 0;
                      for (std::size_t u = range.begin(); u != range.end(); ++u) {
                        const std::size_t i = unsure[u];
                        shadowed[scene.samples.index[i]] = exact.shadowed(i, pairs, calls) ? 1 : 0;
                      }
                      predicate_calls += calls;  // an integer sum: independent of the split
                      phase_progress::advance(range.size());
                    });
  fallback.predicate_calls = predicate_calls.load();
  return fallback;
}

class BruteforceKernelAlgorithm final : public VariantTableAlgorithm<> {
 public:
  explicit BruteforceKernelAlgorithm(BruteforceKernelBackend backend)
      : VariantTableAlgorithm(
            backend.describe("bruteforce", Capabilities{.output = OutputKind::hard_shadow,
                                                        .point_light = true,
                                                        .directional_light = true,
                                                        .max_sample_triangle_pairs =
                                                            backend.max_sample_triangle_pairs}),
            {{.name = "float32", .phases = {}}}),
        backend_(std::move(backend)) {}

 private:
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant&) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    if (!c.light)
      throw std::invalid_argument("bruteforce/" + backend_.backend +
                                  ": the case has no shadow light");
    check_receivers(c, samples);
    std::vector<std::size_t> regular_samples;
    BruteforceShadowInput input = bruteforce_kernel_input(c, samples, regular_samples);
    BruteforceShadowResult result;
    AlgorithmOutput output;
    std::vector<std::size_t> unsure;
    ExactFallback fallback;
    // The emulator spreads blocks over oneTBB and the fallback runs on it: both keep to the
    // case's thread limit, as the reference backends do.
    run_with_thread_limit(c.parameters.threads, [&] {
      result = backend_.run_kernel(std::move(input));     // frees each array once uploaded
      output.shadowed.assign(samples.samples.size(), 0);  // non-regular samples stay 0
      for (std::size_t i = 0; i < regular_samples.size(); ++i) {
        const std::uint8_t state = result.shadowed[i];
        output.shadowed[regular_samples[i]] = state == bruteforce_sample_shadowed ? 1 : 0;
        if (state == bruteforce_sample_unsure) unsure.push_back(i);
      }
      fallback = decide_exactly(scene, unsure, output.shadowed);
    });

    // The definition's closed segment ends at L: a caster containing L shadows every sample it
    // does not receive, which no segment/triangle test in float sees reliably.
    const std::uint64_t light_on_caster =
        shadow_samples_by_light_on_caster(c, samples, output.shadowed);
    output.counters = {{"pair_tests", result.pair_tests},
                       {"exact_fallback_samples", fallback.samples},
                       {"exact_predicate_calls", fallback.predicate_calls},
                       {"light_on_caster_samples", light_on_caster}};
    if (backend_.emulated) {
      const std::uint64_t blocks = (regular_samples.size() + 255) / 256;
      output.counters.push_back({"emulated_threads", blocks * 256});
    }
    return output;
  }

  BruteforceKernelBackend backend_;
};

}  // namespace

std::unique_ptr<Algorithm> make_bruteforce_kernel_algorithm(BruteforceKernelBackend backend) {
  return std::make_unique<BruteforceKernelAlgorithm>(std::move(backend));
}

}  // namespace shadowcts
