#include "reference/sample_half_space.h"

namespace shadowcts {

geometry::ReceiverHalfSpace sample_half_space(const Case& c, const HardShadowLight& light,
                                              const ViewSample& sample) {
  if (sample.receiver == no_receiver) return {};
  const Triangle& r = c.triangles[sample.receiver];
  return geometry::receiver_half_space(glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2),
                                       light.directional,
                                       light.directional ? light.direction : light.position);
}

}  // namespace shadowcts
