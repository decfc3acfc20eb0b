#pragma once
// Conservative floating-point geometry of one sample's shadow query: the segment from p to a
// point light, or the ray from p along a directional light. Used to find candidate casters: every
// test here may answer "maybe" where the exact answer is "no", never "no" where it is "maybe".
//
// "Inflated" means Minkowski-summed with the cube [-t, t]^3. A band move p -> p + delta u with
// |u_i| <= 1 keeps the moved segment (the light stays fixed) or ray inside the query inflated by
// delta: x = s p' + (1 - s) L = (s p + (1 - s) L) + s delta u for s in [0, 1], and s delta u lies
// in the cube. So a triangle that misses the query inflated by delta misses every moved query too.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/vec3.hpp>

#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {

struct ShadowSegment {
  glm::dvec3 origin{0.0};  // p
  glm::dvec3 end{0.0};     // point light: L; directional: unused
  // Point light: L - p rounded to double; directional: d exactly. The tests below account for
  // the rounding of L - p.
  glm::dvec3 direction{0.0};
  glm::dvec3 inverse_direction{0.0};  // 1 / direction, rounded; unused where a component is 0
  bool is_ray = false;
  double bound = 0.0;  // >= every |coordinate| of origin, end and every caster triangle
};

// scene_bound: >= every |coordinate| of every caster triangle (Case::scale() is).
inline ShadowSegment make_shadow_segment(const glm::dvec3& p, const HardShadowLight& light,
                                         double scene_bound) {
  ShadowSegment s;
  s.origin = p;
  s.is_ray = light.directional;
  s.end = light.directional ? p : light.position;
  s.direction = light.directional ? light.direction : light.position - p;
  for (int i = 0; i < 3; ++i)
    s.inverse_direction[i] = s.direction[i] != 0.0 ? 1.0 / s.direction[i] : 0.0;
  s.bound = scene_bound;
  for (int i = 0; i < 3; ++i) s.bound = std::max({s.bound, std::fabs(p[i]), std::fabs(s.end[i])});
  return s;
}

// The amount by which box_may_meet() inflates a box: the requested inflation plus a margin that
// covers the rounding of box +- inflation (one rounding of a value below 2 * bound, relative
// error 2^-53, is far below bound * 2^-40).
inline double box_padding(const ShadowSegment& s, double inflation) {
  return inflation * (1.0 + 0x1p-40) + s.bound * 0x1p-40;
}

// Conservative: false only if the box [lo, hi], inflated by the inflation behind `padding`
// (see box_padding), does not meet the query.
//
// Slab test after Ize ("Robust BVH Ray Traversal", JCGT 2013). With exact box planes b (they
// are, after rounding outward by the padding) every computed parameter (b - p) * (1 / d) has
// relative error at most gamma_4 = 4u / (1 - 4u) against the exact (b - p) / (L - p): one
// rounding each for the subtraction, L - p, the reciprocal and the product. If the exact
// intervals overlap at some t* in [0, t_max], then tnear <= t* (1 + gamma) and
// tfar >= t* (1 - gamma), so tnear <= tfar (1 + gamma) / (1 - gamma); the factor 1 + 2^-48 is
// larger than that times the rounding of the product. Zero direction components are decided
// exactly (L_i - p_i rounds to zero only when it is zero).
inline bool box_may_meet(const ShadowSegment& s, const float lo[3], const float hi[3],
                         double padding) {
  double tnear = 0.0;
  double tfar = s.is_ray ? std::numeric_limits<double>::infinity() : 1.0;
  for (int i = 0; i < 3; ++i) {
    const double low = double(lo[i]) - padding;
    const double high = double(hi[i]) + padding;
    if (s.direction[i] == 0.0) {
      if (s.origin[i] < low || s.origin[i] > high) return false;
      continue;
    }
    double t0 = (low - s.origin[i]) * s.inverse_direction[i];
    double t1 = (high - s.origin[i]) * s.inverse_direction[i];
    if (t0 > t1) std::swap(t0, t1);
    tnear = std::max(tnear, t0);
    tfar = std::min(tfar, t1);
  }
  return tnear <= tfar * (1.0 + 0x1p-48);
}

// A conservative lower bound s >= 0 on the inflation needed to make the query meet the triangle:
// for every t < s the query inflated by t misses the closed triangle. 0 when the triangle may
// meet the query itself. Stops early, returning some value > give_up_above, once that is known.
// See shadow_segment.cpp for the separating-axis argument and its error bound.
double separation_inflation(const ShadowSegment& s, const glm::dvec3& v0, const glm::dvec3& v1,
                            const glm::dvec3& v2, double give_up_above);

}  // namespace shadowcts
