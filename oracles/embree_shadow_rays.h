#pragma once
// Embree 3 occlusion rays for hard shadows, in robust mode: the fast oracle's and the Embree peer
// algorithm's ray tracer. The scene holds the case's casters (caster meshes, non-zero area); an
// occlusion filter ignores the sample's receiver triangle and asks the caller's rule about the
// others.
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

  // Decides whether a caster that Embree finds on a sample's ray counts for that sample: the
  // receiver half-space rule (DESIGN.md). The fast oracle decides it with CGAL, the Embree peer
  // algorithm with the shared geometry: each brings its own. `caster` is a Case::triangles index.
  struct CasterRule {
    const void* state = nullptr;
    bool (*counts)(const void* state, std::uint32_t caster) = nullptr;  // null: every caster
  };

  // Is the segment from origin to the point light (t in [0, 1] along light - origin), or the ray
  // from origin towards the directional light, blocked by a caster other than `receiver`
  // (a triangle index, or no_receiver) that `rule` lets count? Thread-safe.
  bool occluded(const glm::vec3& origin, std::uint32_t receiver, const CasterRule& rule) const;
  bool occluded(const glm::vec3& origin, std::uint32_t receiver) const {
    return occluded(origin, receiver, CasterRule{});
  }

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace shadowcts
