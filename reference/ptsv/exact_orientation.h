#pragma once
// Exact orientation of a triangle against the light, for float inputs. Every per-triangle sign
// decision of the triangle setup (is the triangle edge-on to the light, does it face it, on which
// side of each edge plane lies the triangle) is one of these signs; deciding it exactly keeps the
// four planes of a volume consistent with each other however thin the triangle looks from the
// light (the STYLE note: never construct a plane where an orientation predicate answers).
#include <glm/vec3.hpp>

namespace shadowcts::ptsv {

// Sign (-1, 0, 1) of det[b - a, c - a, light - a]: positive when the light lies on the side the
// normal (b - a) x (c - a) points to.
int orientation_towards_point(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              const glm::vec3& light);

// Sign of det[b - a, c - a, towards_light] = ((b - a) x (c - a)) . towards_light.
int orientation_towards_direction(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                  const glm::vec3& towards_light);

}  // namespace shadowcts::ptsv
