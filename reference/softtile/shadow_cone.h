#pragma once
// The post's truncated shadow cone of a triangle or cluster, and the two receiver bounds of a
// tile (sphere, tapered capsule) it is culled against. In double precision with margins far above
// the rounding error: culling may keep too much, never drop a triangle that shadows a sample.
#include <glm/vec3.hpp>

namespace shadowcts::softtile {

// Everything the geometry inside the sphere (centre, radius) can shadow under a sun disk of
// direction d and angular radius a lies in the cone with apex `tip` = centre + d radius / sin(a),
// axis -d and half-angle a, at height (tip - x) . d >= start_height, the height of the nearest
// vertex (nothing is shadowed nearer to the light than the caster's nearest point).
struct ShadowCone {
  glm::dvec3 tip{0.0};
  double start_height = 0.0;
};

struct SunGeometry {
  glm::dvec3 direction{0.0, 0.0, 1.0};  // d, unit, towards the light
  double angular_radius = 0.0;
};

// `highest` is max over the caster's vertices of v . d.
ShadowCone shadow_cone(const SunGeometry& sun, const glm::dvec3& centre, double radius,
                       double highest);

// A tile's relevant samples: a sphere, or a tapered capsule (the convex hull of two spheres).
struct TileBound {
  bool capsule = false;
  glm::dvec3 a{0.0}, b{0.0};  // sphere: centre a; capsule: axis from a to b
  double radius_a = 0.0, radius_b = 0.0;
};

// Whether the cone may meet the bound (conservative).
bool may_shadow(const SunGeometry& sun, const ShadowCone& cone, const TileBound& bound);

}  // namespace shadowcts::softtile
