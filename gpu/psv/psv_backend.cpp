#include "gpu/psv/psv_backend.h"

#include <utility>

#include "reference/light_on_caster.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/variant_table_algorithm.h"

namespace shadowcts::gpu_psv {
namespace {

class PsvKernelAlgorithm final : public VariantTableAlgorithm<psv::PsvOptions> {
 public:
  explicit PsvKernelAlgorithm(PsvKernelBackend backend)
      : VariantTableAlgorithm(
            backend.describe("psv", point_and_directional_hard_shadows),
            // The four queries, under the reference's names: stack32 is the paper's PSV
            // (stack of 32). The reference's stack (12) and hybrid4 run the same kernel with
            // another capacity; the diff test (tests/gpu/psv) checks them against the reference,
            // and leaving them out of the registry saves their 18 conformance cases of CI time.
            variant_table({"stack32", "depth", "stackless", "hybrid"}, psv::psv_variant_options)),
        backend_(std::move(backend)) {}

 private:
  // build: insertion order, the TOP tree (descents on the device, commits on the host), the
  // query kernel's input; query: the query kernel.
  AlgorithmOutput run_variant(const PreparedScene& scene, const Variant& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    psv::PsvOptions options = variant.config;
    options.seed = c.parameters.seed;
    psv::PsvResult result;
    // The emulator spreads blocks over oneTBB: keep to the case's thread limit, as the reference
    // backends do.
    run_with_thread_limit(c.parameters.threads, [&] {
      result =
          psv_hard_shadows(c, samples, options, backend_.run_kernel, backend_.make_descent_session);
    });
    AlgorithmOutput output;
    output.shadowed = std::move(result.shadowed);
    output.counters = std::move(result.counters);
    output.phase_ms = std::move(result.phase_ms);
    output.counters.push_back({"light_on_caster_samples",
                               shadow_samples_by_light_on_caster(c, samples, output.shadowed)});
    if (backend_.emulated) {
      std::uint64_t regular = 0;
      for (const ViewSample& s : samples.samples)
        if (s.sample_class == SampleClass::regular) ++regular;
      const std::uint64_t blocks = (regular + psv_threads_per_block - 1) / psv_threads_per_block;
      output.counters.push_back({"emulated_threads", blocks * psv_threads_per_block});
    }
    return output;
  }

  PsvKernelBackend backend_;
};

}  // namespace

std::unique_ptr<Algorithm> make_psv_kernel_algorithm(PsvKernelBackend backend) {
  return std::make_unique<PsvKernelAlgorithm>(std::move(backend));
}

}  // namespace shadowcts::gpu_psv
