#pragma once
// Embree 3 occlusion rays for hard shadows, in robust mode: the fast oracle's and the Embree peer
// algorithm's ray tracer. The scene holds the case's casters (caster meshes, non-zero area); an
// occlusion filter ignores the sample's receiver triangle.
#include <cstdint>
#include <memory>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts {

class EmbreeShadowRays {
 public:
  // Throws InputError without a point or directional light.
  explicit EmbreeShadowRays(const Case& c);
  ~EmbreeShadowRays();
  EmbreeShadowRays(const EmbreeShadowRays&) = delete;
  EmbreeShadowRays& operator=(const EmbreeShadowRays&) = delete;

  // Is the segment from origin to the point light (t in [0, 1] along light - origin), or the ray
  // from origin towards the directional light, blocked by a caster other than `receiver`
  // (a triangle index, or no_receiver)? Thread-safe.
  bool occluded(const glm::vec3& origin, std::uint32_t receiver) const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace shadowcts
