#include "gpu/psv/psv_backend.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "reference/light_on_caster.h"
#include "shadowcts/phase_clock.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts::gpu_psv {
namespace {

class PsvKernelAlgorithm final : public Algorithm {
 public:
  explicit PsvKernelAlgorithm(PsvKernelBackend backend) : backend_(std::move(backend)) {
    info_.id = "psv";
    info_.backend = backend_.backend;
    // The four queries, under the reference's names: stack32 is the paper's PSV (stack of
    // 32). The reference's stack (12) and hybrid4 run the same kernel with another capacity; the
    // diff test (tests/gpu/psv) checks them against the reference, and leaving them out of the
    // registry saves their 18 conformance cases of CI time.
    info_.variants = {"stack32", "depth", "stackless", "hybrid"};
    info_.summary = backend_.summary;
    info_.capabilities.output = OutputKind::hard_shadow;
    info_.capabilities.point_light = true;
    info_.capabilities.directional_light = true;
  }

  const AlgorithmInfo& info() const override { return info_; }

  // build: insertion order, the TOP tree (descents on the device, commits on the host), the
  // query kernel's input; query: the query kernel.
  std::vector<std::string> timed_phases(const std::string&) const override {
    return build_and_query_phases();
  }

  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override {
    if (auto reason = Algorithm::unsupported_reason(c, samples, variant)) return reason;
    return backend_.unavailable_reason ? backend_.unavailable_reason() : std::nullopt;
  }

  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    const Case& c = scene.source;
    const ViewSamples& samples = scene.view_samples;
    if (backend_.unavailable_reason) {
      if (auto reason = backend_.unavailable_reason()) throw std::runtime_error(*reason);
    }
    if (std::find(info_.variants.begin(), info_.variants.end(), variant) == info_.variants.end())
      throw std::invalid_argument("psv/" + backend_.backend + ": unknown variant '" + variant +
                                  "'");
    psv::PsvOptions options = psv::psv_variant_options(variant);
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

 private:
  PsvKernelBackend backend_;
  AlgorithmInfo info_;
};

}  // namespace

std::unique_ptr<Algorithm> make_psv_kernel_algorithm(PsvKernelBackend backend) {
  return std::make_unique<PsvKernelAlgorithm>(std::move(backend));
}

}  // namespace shadowcts::gpu_psv
