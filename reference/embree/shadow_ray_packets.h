#pragma once
// The embree peer's own ray tracer: Embree 3 occlusion rays in robust mode, traced 16 at a time
// (rtcOccluded16, the fastest CPU path for coherent rays such as one image row of samples). Kept
// apart from the fast oracle's single-ray tracer (oracles/embree_shadow_rays.h) so that the judge
// and the judged share Embree itself, not our code around it. An occlusion filter drops each
// ray's receiver triangle and applies the receiver half-space rule (DESIGN.md) with the shared
// geometry.
#include <cstdint>
#include <span>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/embree_scene.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

class ShadowRayPackets {
 public:
  static constexpr std::size_t width = 16;

  // The scene holds the case's shadow casters (casts_shadow). Throws InputError without a point
  // or directional light.
  explicit ShadowRayPackets(const Case& c);

  // Decides the samples samples.samples[i] for i in `indices` (at most `width`, all regular):
  // shadowed[i] = 1 where a counting caster blocks the segment to the light (ray towards it).
  // Thread-safe.
  void trace(const ViewSamples& samples, std::span<const std::uint32_t> indices,
             std::vector<std::uint8_t>& shadowed) const;

 private:
  const Case& case_;
  HardShadowLight light_;
  EmbreeScene casters_;
};

}  // namespace shadowcts
