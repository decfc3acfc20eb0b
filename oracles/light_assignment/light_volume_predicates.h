#pragma once
// Exact predicates on ranged-light volumes (DESIGN.md, "Light assignment"), for the oracle, the
// comparison and the reference algorithms that must cull exactly.
//
// Every predicate is exact for the float inputs (light centre, range, spot axis and half angle,
// sample position and normal, box corners) and for band-moved query points base + delta * move:
// a double evaluation with a proven forward error bound decides whenever its margin exceeds the
// bound (a semi-static filter); otherwise the same expression is evaluated in exact rationals
// (CGAL::Exact_rational, GMP). The spot cone compares against cos(theta) of the float half angle
// theta, which is transcendental (Lindemann-Weierstrass: theta != 0 is algebraic), so it never
// equals the algebraic cosine of the query's angle and MPFR intervals of growing precision always
// separate the two.
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"

namespace shadowcts {

// base + delta * move, move in {-1, 0, 1}^3: a sample position, possibly moved by the ambiguity
// band. The sum is never rounded by the predicates.
struct LightQueryPoint {
  glm::dvec3 base{0.0};
  double delta = 0.0;
  glm::ivec3 move{0};
};

// A ranged light prepared for exact queries: the cone's cosine enclosed once, in doubles, by MPFR
// with directed rounding.
struct ExactLightVolume {
  RangedLightKind kind = RangedLightKind::sphere;
  glm::dvec3 centre{0.0};
  double range = 0.0;
  double range_squared = 0.0;  // exact: a float squared fits a double
  glm::dvec3 axis{0.0};        // spot: the float direction as given (not normalized)
  double axis_length = 0.0;    // spot: |axis| rounded to nearest
  float cone_half_angle = 0.0f;
  double cos_low = 0.0, cos_high = 0.0;  // spot: cos_low <= cos(half angle) <= cos_high
};

ExactLightVolume prepare_light_volume(const RangedLight& light);

// Whether x lies in the closed light volume: |x - c| <= r, and for a spot also
// angle(x - c, axis) <= half angle (the apex belongs to the cone).
bool light_volume_contains(const ExactLightVolume& light, const LightQueryPoint& x);

// The normal rule of Paper II's back-face culling: n . (c - x) > 0 (the light is in front of the
// sample); lights with n . (c - x) <= 0 are dropped.
bool light_in_front_of(const glm::vec3& normal, const ExactLightVolume& light,
                       const LightQueryPoint& x);

// Whether the closed ball |x - c| <= r meets the closed box (float corners, min <= max). The
// papers cull every light, spots included, by its bounding sphere.
bool sphere_meets_box(const glm::vec3& centre, float range, const Aabb& box);

// The same predicates evaluated in exact rationals only, without the double filter: the
// definition the filtered versions must agree with (tests compare the two).
namespace exact_only {
bool light_volume_contains(const ExactLightVolume& light, const LightQueryPoint& x);
bool light_in_front_of(const glm::vec3& normal, const ExactLightVolume& light,
                       const LightQueryPoint& x);
bool sphere_meets_box(const glm::vec3& centre, float range, const Aabb& box);
}  // namespace exact_only

// How often the double filter could not decide and exact rationals did (for tests and counters;
// a process-wide relaxed counter).
std::uint64_t exact_light_predicate_fallbacks();

}  // namespace shadowcts
