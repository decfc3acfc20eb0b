#include "simd/ptsv/receiver_rule.h"

#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "reference/ptsv/receiver_rule.h"

namespace shadowcts::simd::ptsv {

ReceiverRule::ReceiverRule(const PreparedScene& scene)
    : slot_(scene.source.triangles.size(), 0u), reach_(scene.samples.size()) {
  const Case& c = scene.source;
  const RegularSamples& samples = scene.samples;
  const bool directional = c.light->kind == ShadowLightKind::directional;
  const glm::dvec3 towards =
      directional ? glm::dvec3(c.light->direction) : glm::dvec3(c.light->position);
  // Which triangles receive a regular sample: a slot each.
  std::vector<std::uint8_t> receives(c.triangles.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 8192),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        if (samples.receiver[i] != no_receiver)
                          std::atomic_ref<std::uint8_t>(receives[samples.receiver[i]])
                              .store(1, std::memory_order_relaxed);
                    });
  std::vector<std::uint32_t> receivers;
  for (std::size_t t = 0; t < receives.size(); ++t)
    if (receives[t]) {
      slot_[t] = std::uint32_t(receivers.size());
      receivers.push_back(std::uint32_t(t));
    }
  half_spaces_.resize(receivers.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k) {
                        const Triangle& t = c.triangles[receivers[k]];
                        half_spaces_[k] =
                            geometry::receiver_half_space(glm::dvec3(t.v0), glm::dvec3(t.v1),
                                                          glm::dvec3(t.v2), directional, towards);
                      }
                    });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, samples.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        reach_[i] = ::shadowcts::ptsv::reject_reach(
                            half_space(samples.receiver[i]), glm::dvec3(samples.position(i)));
                    });
}

}  // namespace shadowcts::simd::ptsv
