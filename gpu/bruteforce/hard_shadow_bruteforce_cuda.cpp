#include "gpu/bruteforce/hard_shadow_bruteforce_cuda.h"

#include <stdexcept>

#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/device.h"

namespace shadowcts {
namespace {

AlgorithmInfo bruteforce_cuda_info() {
  AlgorithmInfo info;
  info.id = "bruteforce";
  info.backend = "cuda";
  info.variants = {"float32"};
  info.summary =
      "every regular sample against every caster triangle on the GPU, one thread per sample, "
      "watertight float32 segment/triangle test";
  info.capabilities.output = OutputKind::hard_shadow;
  info.capabilities.point_light = true;
  info.capabilities.directional_light = true;
  // A few seconds on a current data-centre GPU.
  info.capabilities.max_sample_triangle_pairs = 40'000'000'000ull;
  return info;
}

// The kernel's input: regular samples and caster triangles only.
BruteforceShadowInput kernel_input(const Case& c, const ViewSamples& samples,
                                   std::vector<std::size_t>& regular_samples) {
  BruteforceShadowInput input;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& sample = samples.samples[i];
    if (sample.sample_class != SampleClass::regular) continue;
    regular_samples.push_back(i);
    input.sample_positions.push_back(sample.position);
    input.sample_receivers.push_back(sample.receiver);
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

class BruteforceHardShadowCuda final : public Algorithm {
 public:
  const AlgorithmInfo& info() const override { return info_; }

  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override {
    if (auto reason = Algorithm::unsupported_reason(c, samples, variant)) return reason;
    return cuda_unavailable_reason();
  }

  AlgorithmOutput run(const Case& c, const ViewSamples& samples,
                      const std::string& variant) const override {
    if (variant != info_.variants.front()) {
      throw std::invalid_argument("bruteforce/cuda: unknown variant '" + variant + "'");
    }
    if (auto reason = cuda_unavailable_reason()) throw std::runtime_error(*reason);
    if (!c.light) throw std::invalid_argument("bruteforce/cuda: the case has no shadow light");
    std::vector<std::size_t> regular_samples;
    const BruteforceShadowResult result =
        run_bruteforce_hard_shadow_kernel(kernel_input(c, samples, regular_samples));

    AlgorithmOutput output;
    output.shadowed.assign(samples.samples.size(), 0);  // non-regular samples stay 0
    for (std::size_t i = 0; i < regular_samples.size(); ++i) {
      output.shadowed[regular_samples[i]] = result.shadowed[i];
    }
    output.counters = {{"pair_tests", result.pair_tests}};
    return output;
  }

 private:
  AlgorithmInfo info_ = bruteforce_cuda_info();
};

}  // namespace

std::unique_ptr<Algorithm> make_bruteforce_hard_shadow_cuda() {
  return std::make_unique<BruteforceHardShadowCuda>();
}

}  // namespace shadowcts
