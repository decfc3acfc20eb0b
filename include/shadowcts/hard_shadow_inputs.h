#pragma once
// The inputs of a hard-shadow query as the oracles and the reference algorithms read them: the
// light, and the view samples' receivers.
#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

struct RegularSamples;  // shadowcts/prepared_scene.h

struct HardShadowLight {
  bool directional = false;
  glm::dvec3 position{0.0};   // point light L (float values held exactly)
  glm::dvec3 direction{0.0};  // directional: d, from the scene towards the light (not unit)
};

// Throws InputError when the case has no point or directional light (a sun disk has soft
// shadows, which the hard-shadow oracles do not define).
HardShadowLight hard_shadow_light(const Case& c);

// The case as hard-shadow algorithms and oracles see it: a sun disk becomes its centre direction,
// a directional light. Other cases are returned unchanged.
Case hard_shadow_view(const Case& c);

// Whether triangle i can cast a shadow: its mesh is a caster and it has non-zero area (exact).
// Throws InputError when its mesh id is out of range.
bool casts_shadow(const Case& c, std::size_t i);

// Throws InputError naming the sample when a regular sample's receiver is neither no_receiver
// nor a triangle index of the case.
void check_receivers(const Case& c, const ViewSamples& samples);
// The same from the prepared scene's regular samples (the same message).
void check_receivers(const Case& c, const RegularSamples& samples);

}  // namespace shadowcts
