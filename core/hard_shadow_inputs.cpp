#include "shadowcts/hard_shadow_inputs.h"

#include <string>

#include "shadowcts/errors.h"
#include "shadowcts/geometry/triangle_area.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts {

Case hard_shadow_view(const Case& c) {
  Case view = c;
  if (view.light && view.light->kind == ShadowLightKind::sun_disk) {
    view.light->kind = ShadowLightKind::directional;
    view.light->angular_radius = 0.0f;
  }
  return view;
}

HardShadowLight hard_shadow_light(const Case& c) {
  if (!c.light) throw InputError(c.source, "light", "a hard-shadow case needs a shadow light");
  HardShadowLight light;
  switch (c.light->kind) {
    case ShadowLightKind::point:
      light.position = glm::dvec3(c.light->position);
      return light;
    case ShadowLightKind::directional:
      light.directional = true;
      light.direction = glm::dvec3(c.light->direction);
      if (light.direction == glm::dvec3(0.0))
        throw InputError(c.source, "light.direction", "has zero length");
      return light;
    case ShadowLightKind::sun_disk:
      break;
  }
  throw InputError(c.source, "light",
                   "hard shadows need a point or directional light, not a sun disk");
}

bool casts_shadow(const Case& c, std::size_t i) {
  const Triangle& t = c.triangles[i];
  if (t.mesh >= c.meshes.size())
    throw InputError(c.source, "triangles[" + std::to_string(i) + "].mesh",
                     "mesh id " + std::to_string(t.mesh) + " out of range");
  return c.meshes[t.mesh].caster && !triangle_has_zero_area(t.v0, t.v1, t.v2);
}

void check_receivers(const Case& c, const RegularSamples& samples) {
  for (std::size_t i = 0; i < samples.size(); ++i)
    if (samples.receiver[i] != no_receiver && samples.receiver[i] >= c.triangles.size())
      throw InputError(
          c.source, "view sample " + std::to_string(samples.index[i]),
          "receiver " + std::to_string(samples.receiver[i]) + " is not a triangle index");
}

void check_receivers(const Case& c, const ViewSamples& samples) {
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class == SampleClass::regular && s.receiver != no_receiver &&
        s.receiver >= c.triangles.size())
      throw InputError(c.source, "view sample " + std::to_string(i),
                       "receiver " + std::to_string(s.receiver) + " is not a triangle index");
  }
}

}  // namespace shadowcts
