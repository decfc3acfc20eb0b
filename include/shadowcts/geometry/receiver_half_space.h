#pragma once
// The receiver half-space rule (DESIGN.md, "Cases and ground truth"; docs/specification.md), for
// host and device: a caster T != r shadows the sample p of receiver r only where T meets the
// segment p -> L (the ray, for a directional light) at a point strictly on the light's side of
// r's supporting plane. A float sample lies within rounding of its receiver's plane, often just
// below it; without the rule a coplanar neighbour of r, or the next face of a convex closed mesh,
// blocks the segments of the samples beside their common edge.
//
// Every decision is an exact orientation sign (exact_orientation.h), never an epsilon:
// - caster_reach() sorts a caster by its vertices: all strictly on the light's side (the rule
//   never removes one of its hits), none strictly on it (it never shadows this receiver), or
//   straddling;
// - for a straddling caster that meets the segment, hit_on_light_side() decides the side of the
//   one point where the segment crosses the caster's plane: with g the caster's orientation and f
//   the receiver's (positive on the light's side), that point has
//   f = (g(p) f(L) - f(p) g(L)) / (g(p) - g(L)) (point light) or
//   f = f(p) - g(p) Df / Dg with Dg, Df the orientations towards d (directional light),
//   a degree-6 sign decided by a filter and, where it cannot, by exact expansion products.
//
// Two limits, both outside what a robust sample can depend on (docs/specification.md explains
// why): a segment lying in the caster's plane (the caster seen edge-on, where float segment tests
// report no hit either) counts only through a light inside the caster, and where a factor of the
// exact products would need more than 16 components (a degree-3 orientation spanning more than
// about 420 bits: float inputs whose magnitudes differ by more than about 2^110 within one
// predicate) the answer is "not on the light's side".
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/expansion.h"
#include "shadowcts/host_device.h"

namespace shadowcts::geometry {
SHADOWCTS_GEOMETRY_ABI_BEGIN

struct ReceiverHalfSpace {
  glm::dvec3 a{0.0}, b{0.0}, c{0.0};  // the receiver's vertices
  glm::dvec3 light{0.0};              // point light L, or the direction d towards the light
  bool directional = false;
  // The receiver has a supporting plane (non-zero area). Without one the rule is void: every
  // caster point counts.
  bool has_plane = false;
  // +1 or -1: the sign of the receiver's orientation on the light's side; 0 when the light lies
  // in the receiver's plane (grazing: no point is strictly on the light's side, so no caster
  // counts; the sample classification calls such samples back-facing and never compares them).
  int light_side = 0;
};

SHADOWCTS_HD inline ReceiverHalfSpace receiver_half_space(const glm::dvec3& a, const glm::dvec3& b,
                                                          const glm::dvec3& c, bool directional,
                                                          const glm::dvec3& light) {
  ReceiverHalfSpace h;
  h.a = a;
  h.b = b;
  h.c = c;
  h.light = light;
  h.directional = directional;
  // Zero area iff every direction is in the plane's span: the orientation towards the three axes
  // vanishes (the normal (b - a) x (c - a) is zero), decided exactly.
  h.has_plane = orientation_towards(a, b, c, glm::dvec3(1.0, 0.0, 0.0)) != 0 ||
                orientation_towards(a, b, c, glm::dvec3(0.0, 1.0, 0.0)) != 0 ||
                orientation_towards(a, b, c, glm::dvec3(0.0, 0.0, 1.0)) != 0;
  if (h.has_plane)
    h.light_side = directional ? orientation_towards(a, b, c, light) : orientation(a, b, c, light);
  return h;
}

// +1: x strictly on the light's side of the receiver's plane; 0: in the plane; -1: beyond it.
SHADOWCTS_HD inline int light_side_of(const ReceiverHalfSpace& h, const glm::dvec3& x) {
  return orientation(h.a, h.b, h.c, x) * h.light_side;
}

enum class CasterReach : std::uint8_t {
  every_hit,  // every vertex strictly on the light's side (or the rule is void)
  no_hit,     // no vertex strictly on the light's side: the caster never shadows this receiver
  straddles,  // decide each hit with hit_on_light_side()
};

SHADOWCTS_HD inline CasterReach caster_reach(const ReceiverHalfSpace& h, const glm::dvec3& v0,
                                             const glm::dvec3& v1, const glm::dvec3& v2) {
  if (!h.has_plane) return CasterReach::every_hit;
  if (h.light_side == 0) return CasterReach::no_hit;
  const int s0 = light_side_of(h, v0), s1 = light_side_of(h, v1), s2 = light_side_of(h, v2);
  if (s0 > 0 && s1 > 0 && s2 > 0) return CasterReach::every_hit;
  if (s0 <= 0 && s1 <= 0 && s2 <= 0) return CasterReach::no_hit;
  return CasterReach::straddles;
}

namespace detail {

// The factors of the degree-6 sign, compressed to at most this many components (a compressed
// expansion needs about one component per 26 bits of its value's span: 16 hold an orientation of
// float inputs whose magnitudes differ by up to about 2^110). Small arrays keep the stack of a
// device thread small.
inline constexpr int factor_components = 16;
using Factor = Expansion<factor_components>;

// A factor from an exact expansion; false when it needs more components.
template <int N>
SHADOWCTS_HD inline bool to_factor(const Expansion<N>& e, int sign_factor, Factor& out) {
  const Expansion<N> c = compressed(e);
  if (!narrowed(c, out)) return false;
  if (sign_factor < 0) out = negated(out);
  return true;
}

SHADOWCTS_HD inline bool orientation_factor(const glm::dvec3& a, const glm::dvec3& b,
                                            const glm::dvec3& c, const glm::dvec3& d,
                                            int sign_factor, Factor& out) {
  return to_factor(orientation_value(a, b, c, d), sign_factor, out);
}

SHADOWCTS_HD inline bool towards_factor(const glm::dvec3& a, const glm::dvec3& b,
                                        const glm::dvec3& c, const glm::dvec3& d, int sign_factor,
                                        Factor& out) {
  return to_factor(orientation_towards_value(a, b, c, d), sign_factor, out);
}

// Whether x, in the plane of the non-degenerate triangle (v0, v1, v2), lies in the closed
// triangle: the three edge orientations seen along an axis the triangle's plane is not parallel
// to agree with the triangle's own (exact).
SHADOWCTS_HD inline bool point_in_coplanar_triangle(const glm::dvec3& x, const glm::dvec3& v0,
                                                    const glm::dvec3& v1, const glm::dvec3& v2) {
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 axis(0.0);
    axis[k] = 1.0;
    const int own = orientation_towards(v0, v1, v2, axis);
    if (own == 0) continue;
    return orientation_towards(v0, v1, x, axis) * own >= 0 &&
           orientation_towards(v1, v2, x, axis) * own >= 0 &&
           orientation_towards(v2, v0, x, axis) * own >= 0;
  }
  return false;  // zero area
}

// Sign of a b - c d for exact factors; 2 when the exact sum would outgrow its array (impossible
// by the span argument above, kept as a guard).
SHADOWCTS_HD inline int sign_of_product_difference(const Factor& a, const Factor& b,
                                                   const Factor& c, const Factor& d) {
  const int ab = sign(a) * sign(b), cd = sign(c) * sign(d);
  if (ab == 0 || cd == 0 || ab != cd) return ab != 0 ? ab : -cd;
  // Same signs: compare the magnitudes, first in doubles with a certified margin (the estimate of
  // a compressed expansion is within 2^-50 of its value; each product adds one rounding).
  const double x = estimate(a) * estimate(b), y = estimate(c) * estimate(d);
  const double margin = 0x1p-44 * (fabs(x) + fabs(y));
  if (x - y > margin) return 1;
  if (y - x > margin) return -1;
  // Exactly: the partial products grown into one sum, compressed after each term (the partial
  // sums span at most twice a factor's bits, so they stay far below the array's size).
  constexpr int capacity = 8 * factor_components;
  Expansion<capacity> sum_;
  sum_.size = 0;
  const auto add = [&](const Factor& e, double scale) {
    const Expansion<2 * factor_components> term = scaled(e, scale);
    if (sum_.size + term.size > capacity) return false;
    for (int i = 0; i < term.size; ++i) grow(sum_, term.component[i]);
    sum_ = compressed(sum_);
    return true;
  };
  for (int j = 0; j < b.size; ++j)
    if (!add(a, b.component[j])) return 2;
  for (int j = 0; j < d.size; ++j)
    if (!add(c, -d.component[j])) return 2;
  return sign(sum_);
}

}  // namespace detail

// For a non-degenerate caster (v0, v1, v2) that meets the closed segment from p to the point
// light (or the ray from p towards the directional light): whether it meets it at a point strictly
// on the light's side of the receiver's plane. The caller has decided that it meets it.
SHADOWCTS_HD inline bool hit_on_light_side(const ReceiverHalfSpace& h, const glm::dvec3& p,
                                           const glm::dvec3& v0, const glm::dvec3& v1,
                                           const glm::dvec3& v2) {
  if (!h.has_plane) return true;
  if (h.light_side == 0) return false;
  detail::Factor fp, gp;
  if (!detail::orientation_factor(h.a, h.b, h.c, p, h.light_side, fp) ||
      !detail::orientation_factor(v0, v1, v2, p, 1, gp))
    return false;
  int s = 0;
  if (!h.directional) {
    detail::Factor fl, gl;
    if (!detail::orientation_factor(h.a, h.b, h.c, h.light, h.light_side, fl) ||
        !detail::orientation_factor(v0, v1, v2, h.light, 1, gl))
      return false;
    const int sgp = sign(gp), sgl = sign(gl);
    // The segment lies in the caster's plane: it meets the caster at L itself (strictly on the
    // light's side) when L lies in the caster; other such hits vanish under every move of p off
    // that plane, so no robust sample depends on them.
    if (sgp == 0 && sgl == 0) return detail::point_in_coplanar_triangle(h.light, v0, v1, v2);
    // sign(g(p) - g(L)): the segment crosses the caster's plane, so g(p) and g(L) differ in sign
    // or one of them is zero.
    const int denominator = sgp != 0 ? sgp : -sgl;
    s = detail::sign_of_product_difference(gp, fl, fp, gl);
    if (s == 2) return false;
    s *= denominator;
  } else {
    detail::Factor dg, df;
    if (!detail::towards_factor(v0, v1, v2, h.light, 1, dg) ||
        !detail::towards_factor(h.a, h.b, h.c, h.light, h.light_side, df))
      return false;
    const int sdg = sign(dg);
    if (sdg == 0) return false;  // the ray is parallel to the caster's plane (and lies in it)
    s = detail::sign_of_product_difference(fp, dg, gp, df);  // f(p) Dg - g(p) Df
    if (s == 2) return false;
    s *= sdg;
  }
  return s > 0;
}

// Whether a caster that meets the shadow segment (ray) of p shadows p under the rule.
SHADOWCTS_HD inline bool caster_counts(const ReceiverHalfSpace& h, const glm::dvec3& p,
                                       const glm::dvec3& v0, const glm::dvec3& v1,
                                       const glm::dvec3& v2) {
  switch (caster_reach(h, v0, v1, v2)) {
    case CasterReach::every_hit:
      return true;
    case CasterReach::no_hit:
      return false;
    case CasterReach::straddles:
      break;
  }
  return hit_on_light_side(h, p, v0, v1, v2);
}

SHADOWCTS_GEOMETRY_ABI_END
}  // namespace shadowcts::geometry
