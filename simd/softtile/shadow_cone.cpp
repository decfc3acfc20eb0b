// Highway translation unit of the simd softtile's cone culling (see shadow_cone.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/shadow_cone.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <hwy/contrib/sort/vqsort.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "shadowcts/geometry/morton.h"
#include "simd/lane_bits-inl.h"
#include "simd/softtile/shadow_cone.h"

#ifndef SHADOWCTS_SIMD_SOFTTILE_BOUND_TERMS
#define SHADOWCTS_SIMD_SOFTTILE_BOUND_TERMS
namespace shadowcts::simd::softtile::detail {

// The reference's relative margin (reference/softtile/shadow_cone.cpp).
inline constexpr double relative_margin = 1e-9;

// What may_shadow computes from the bound alone, once per tile, in the reference's expressions.
struct BoundTerms {
  bool capsule = false;
  double a[3], b[3], ra, rb;
  double length_a, length_b;    // terms of the height slack
  double middle[3], enclosing;  // the capsule's enclosing sphere
  double ab[3], dr, lipschitz;  // b - a, rb - ra, |b - a| + |rb - ra|
  double magnitude;             // |a| + |b| + ra + rb: the scale of every gap's rounding
};

inline BoundTerms bound_terms(const shadowcts::softtile::TileBound& bound) {
  BoundTerms t;
  t.capsule = bound.capsule;
  const glm::dvec3 middle = 0.5 * (bound.a + bound.b);
  const glm::dvec3 ab = bound.b - bound.a;
  for (int k = 0; k < 3; ++k) {
    t.a[k] = bound.a[k];
    t.b[k] = bound.b[k];
    t.middle[k] = middle[k];
    t.ab[k] = ab[k];
  }
  t.ra = bound.radius_a;
  t.rb = bound.radius_b;
  t.length_a = glm::length(bound.a);
  t.length_b = glm::length(bound.b);
  t.enclosing = 0.5 * glm::length(bound.b - bound.a) + std::max(bound.radius_a, bound.radius_b);
  t.dr = bound.radius_b - bound.radius_a;
  t.lipschitz = glm::length(bound.b - bound.a) + std::fabs(bound.radius_b - bound.radius_a);
  t.magnitude = t.length_a + t.length_b + t.ra + t.rb;
  return t;
}

}  // namespace shadowcts::simd::softtile::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::softtile {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using shadowcts::simd::HWY_NAMESPACE::lane_bits;

using detail::BoundTerms;
using detail::relative_margin;
using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

struct ConeLanes {
  V tip[3], start, tip_length;
};

struct SunLanes {
  V d[3], axis[3], c, s;
};

// std::max(x, y) = x < y ? y : x (its NaN and tie behaviour included).
HWY_INLINE V max_of(V x, V y) {
  return hn::IfThenElse(hn::Lt(x, y), y, x);
}

// glm::length: sqrt((x x + y y) + z z).
HWY_INLINE V length3(V x, V y, V z) {
  return hn::Sqrt(hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Mul(z, z)));
}

// height(x) = dot(tip - x, d).
HWY_INLINE V height(const ConeLanes& l, const SunLanes& sun, const V x[3]) {
  return hn::Add(hn::Add(hn::Mul(hn::Sub(l.tip[0], x[0]), sun.d[0]),
                         hn::Mul(hn::Sub(l.tip[1], x[1]), sun.d[1])),
                 hn::Mul(hn::Sub(l.tip[2], x[2]), sun.d[2]));
}

// gap(cone, x, radius) = distance_to_cone(cone, x) - radius - slack, the cone (tip, -d, a).
HWY_INLINE V gap(D d, const ConeLanes& l, const SunLanes& sun, const V x[3], V radius) {
  const V v0 = hn::Sub(x[0], l.tip[0]), v1 = hn::Sub(x[1], l.tip[1]), v2 = hn::Sub(x[2], l.tip[2]);
  const V length_v = length3(v0, v1, v2);
  const V slack = hn::Mul(hn::Set(d, relative_margin), hn::Add(length_v, radius));
  const V h = hn::Add(hn::Add(hn::Mul(v0, sun.axis[0]), hn::Mul(v1, sun.axis[1])),
                      hn::Mul(v2, sun.axis[2]));
  const V lateral =
      length3(hn::Sub(v0, hn::Mul(h, sun.axis[0])), hn::Sub(v1, hn::Mul(h, sun.axis[1])),
              hn::Sub(v2, hn::Mul(h, sun.axis[2])));
  const V zero = hn::Zero(d);
  // In the (height, lateral) half-plane the cone is the wedge below the ray (cos a, sin a).
  const M apex = hn::Le(hn::Add(hn::Mul(h, sun.c), hn::Mul(lateral, sun.s)), zero);
  const V side = hn::Sub(hn::Mul(lateral, sun.c), hn::Mul(h, sun.s));
  const V distance = hn::IfThenElse(apex, length_v, max_of(zero, side));
  return hn::Sub(hn::Sub(distance, radius), slack);
}

// g(s) of the capsule: the gap at a + s (b - a) with radius ra + s (rb - ra).
HWY_INLINE V capsule_gap(D d, const ConeLanes& l, const SunLanes& sun, const BoundTerms& t, V s) {
  V x[3];
  for (int k = 0; k < 3; ++k) x[k] = hn::Add(hn::Set(d, t.a[k]), hn::Mul(s, hn::Set(d, t.ab[k])));
  return gap(d, l, sun, x, hn::Add(hn::Set(d, t.ra), hn::Mul(s, hn::Set(d, t.dr))));
}

// The least, over t in [0, 1], of max(L(t), R(t)) with L(t) = left + left_slope t and R(t) = right
// - right_slope (1 - t): any weight w in [0, 1] gives max(L, R) >= w L + (1 - w) R, linear in t,
// so least at t = 0 or 1; the w that makes it flat gives the lines' crossing (L alone where it
// does not fall, R alone where it does not rise).
HWY_INLINE V lines_bound(D d, V left, V left_slope, V right, V right_slope) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  V w = hn::Div(right_slope, hn::Sub(right_slope, left_slope));
  w = hn::IfThenElse(hn::Ge(left_slope, zero), one, w);
  w = hn::IfThenElse(hn::Le(right_slope, zero), zero, w);
  w = hn::Min(hn::Max(w, zero), one);
  const V at0 = hn::Add(hn::Mul(w, left), hn::Mul(hn::Sub(one, w), hn::Sub(right, right_slope)));
  const V at1 = hn::Add(hn::Mul(w, hn::Add(left, left_slope)), hn::Mul(hn::Sub(one, w), right));
  return hn::Min(at0, at1);
}

// What computed gaps are within of the exact ones: 1e-12 of |tip| + the bound's magnitude, far
// above the rounding of gap()'s few operations on those magnitudes.
HWY_INLINE V gap_error(D d, const ConeLanes& l, const BoundTerms& t) {
  return hn::Mul(hn::Set(d, 1e-12), hn::Add(l.tip_length, hn::Set(d, t.magnitude)));
}

struct CapsuleMinimum {
  M above;    // lanes whose exact minimum is > above_limit - err
  M below;    // lanes whose exact minimum is < below_limit
  M neither;  // other lanes that no certificate can decide
};

// Where c |q0 + s w| + beta s (c > 0) is smallest on [0, 1]: with |q0 + s w|^2 = A ((s - s0)^2 +
// k^2), at s0 - beta k / sqrt(c^2 A - beta^2), or at an end where it is monotone.
HWY_INLINE V minimizer_of(D d, const V (&q0)[3], const V (&w)[3], V c, V beta) {
  const V a = hn::Add(hn::Add(hn::Mul(w[0], w[0]), hn::Mul(w[1], w[1])), hn::Mul(w[2], w[2]));
  const V b = hn::Add(hn::Add(hn::Mul(q0[0], w[0]), hn::Mul(q0[1], w[1])), hn::Mul(q0[2], w[2]));
  // k A = |q0 x w| (Lagrange's identity, without A C - B^2's cancellation).
  const V k_a = length3(hn::Sub(hn::Mul(q0[1], w[2]), hn::Mul(q0[2], w[1])),
                        hn::Sub(hn::Mul(q0[2], w[0]), hn::Mul(q0[0], w[2])),
                        hn::Sub(hn::Mul(q0[0], w[1]), hn::Mul(q0[1], w[0])));
  const V room = hn::Sub(hn::Mul(hn::Mul(c, c), a), hn::Mul(beta, beta));
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  V s = hn::Sub(hn::Neg(hn::Div(hn::Mul(beta, k_a), hn::Mul(a, hn::Sqrt(room)))), hn::Div(b, a));
  const V end = hn::IfThenElse(hn::Gt(beta, zero), zero, one);
  s = hn::IfThenElse(hn::Gt(room, zero), s, end);
  s = hn::IfThenElse(hn::Eq(s, s), s, end);  // NaN: A = 0 or non-finite inputs
  return hn::Min(hn::Max(s, zero), one);
}

// Two places to look for the capsule's smallest g, the minima of the two pieces of dist(x, cone)
// less r(s) (v = x(s) - tip, h its part along the axis, q the part across): c |q| - sin(a) h, which
// is <= dist everywhere and equal outside the apex's region and the cone, and |v|, which is >=
// dist and equal inside the apex's region. Both are convex, so where g's minimum lies outside the
// cone one of the two is at it. Only places to look: nothing depends on their being exact.
struct Places {
  V side, apex;
};

HWY_INLINE Places minimum_places(D d, const ConeLanes& l, const SunLanes& sun,
                                 const BoundTerms& t) {
  V v0[3], w[3];
  for (int k = 0; k < 3; ++k) {
    v0[k] = hn::Sub(hn::Set(d, t.a[k]), l.tip[k]);
    w[k] = hn::Set(d, t.ab[k]);
  }
  const V h0 = hn::Add(hn::Add(hn::Mul(v0[0], sun.axis[0]), hn::Mul(v0[1], sun.axis[1])),
                       hn::Mul(v0[2], sun.axis[2]));
  const V hw = hn::Add(hn::Add(hn::Mul(w[0], sun.axis[0]), hn::Mul(w[1], sun.axis[1])),
                       hn::Mul(w[2], sun.axis[2]));
  V q0[3], qw[3];
  for (int k = 0; k < 3; ++k) {
    q0[k] = hn::Sub(v0[k], hn::Mul(h0, sun.axis[k]));
    qw[k] = hn::Sub(w[k], hn::Mul(hw, sun.axis[k]));
  }
  const V dr = hn::Set(d, t.dr);
  return {minimizer_of(d, q0, qw, sun.c, hn::Neg(hn::Add(hn::Mul(sun.s, hw), dr))),
          minimizer_of(d, v0, w, hn::Set(d, 1.0), hn::Neg(dr))};
}

// Half the spacing of the samples around a place (dyadic, so they are exact).
inline constexpr double near_step = 1.0 / 4096.0;

// Certifies, for the lanes of `alive`, where the exact minimum over s in [0, 1] of the capsule's g
// (the gap of cone l at a + s (b - a), radius ra + s (rb - ra); g0 and g1 its computed values at 0
// and 1) lies against two limits, from five samples of g, each computed within err of the exact g:
// the ends and three near_step apart around `place` (rounded to 2^-20 and kept near_step inside
// [0, 1], so the positions are exact). The exact g is L-Lipschitz in s and convex but for its slack
// term -1e-9 |x(s) - tip|, at most 1000 err (err is 1e-12 of |tip| + magnitude). Lower bounds:
// - on each interval, Lipschitz: g >= (g_k + g_k+1 - L length) / 2;
// - g + 1e-9 |x(s) - tip| lies above the line through any two samples beyond them. A line
//   through samples `base` apart, followed D = length / base further, carries (1 + 2 D) err from
//   its samples, and the slack term (varying by at most 1e-9 L base between them) moves it by at
//   most 2000 err + 1e-9 L. On [0, p - step] and [p + step, 1] the line through the nearer two
//   samples; on the two inner intervals the lines from either side (lines_bound).
// The upper bound is the smallest sample + err. A NaN or infinity anywhere: never certified.
HWY_INLINE CapsuleMinimum certify_around(D d, const ConeLanes& l, const SunLanes& sun,
                                         const BoundTerms& t, V place, V g0, V g1, M alive, V err,
                                         V above_limit, V below_limit) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const V step = hn::Set(d, near_step), steps_per_unit = hn::Set(d, 1.0 / near_step);
  const V lipschitz = hn::Set(d, t.lipschitz * (1.0 + 1e-6));
  const V inf = hn::Set(d, HUGE_VAL);
  const V grid = hn::Set(d, 1048576.0), inverse_grid = hn::Set(d, 1.0 / 1048576.0);
  V p = hn::Mul(hn::Round(hn::Mul(place, grid)), inverse_grid);
  p = hn::Min(hn::Max(p, step), hn::Sub(one, step));
  const V p_left = hn::Sub(p, step), p_right = hn::Add(p, step);
  const V g_left = capsule_gap(d, l, sun, t, p_left), g_mid = capsule_gap(d, l, sun, t, p),
          g_right = capsule_gap(d, l, sun, t, p_right);
  M finite = hn::Lt(hn::Abs(err), inf);
  for (const V& g : {g0, g1, g_left, g_mid, g_right})
    finite = hn::And(finite, hn::Lt(hn::Abs(g), inf));
  const V fixed_line_err =
      hn::Add(hn::Mul(hn::Set(d, 2001.0), err), hn::Set(d, 1e-9 * t.lipschitz));
  // [0, p_left]: D = p_left / step.
  const V d_left = hn::Mul(p_left, steps_per_unit);
  const V line_left =
      hn::Sub(hn::Sub(g_left, hn::Mul(hn::Max(zero, hn::Sub(g_mid, g_left)), d_left)),
              hn::Add(fixed_line_err, hn::Mul(hn::Add(d_left, d_left), err)));
  const V outer_left =
      hn::Max(line_left, hn::Mul(half, hn::Sub(hn::Add(g0, g_left), hn::Mul(lipschitz, p_left))));
  // [p_right, 1]: D = (1 - p_right) / step.
  const V right_length = hn::Sub(one, p_right);
  const V d_right = hn::Mul(right_length, steps_per_unit);
  const V line_right =
      hn::Sub(hn::Sub(g_right, hn::Mul(hn::Max(zero, hn::Sub(g_mid, g_right)), d_right)),
              hn::Add(fixed_line_err, hn::Mul(hn::Add(d_right, d_right), err)));
  const V outer_right = hn::Max(
      line_right, hn::Mul(half, hn::Sub(hn::Add(g_right, g1), hn::Mul(lipschitz, right_length))));
  // [p_left, p] and [p, p_right]: Lipschitz, and the lines through the samples on either side,
  // one of them from the end's sample, a baseline of `length` extended by step: (1 + 2 step /
  // length) err. An end at the interval (length 0) leaves one line.
  const V lipschitz_step = hn::Mul(lipschitz, step);
  const V inner_line_err = hn::Add(fixed_line_err, hn::Mul(hn::Set(d, 2.0), err));
  const M room_left = hn::Gt(p_left, zero), room_right = hn::Gt(right_length, zero);
  const V from_start = hn::Div(step, p_left), from_end = hn::Div(step, right_length);
  const V lines_left =
      hn::IfThenElse(room_left,
                     hn::Sub(lines_bound(d, g_left, hn::Mul(hn::Sub(g_left, g0), from_start), g_mid,
                                         hn::Sub(g_right, g_mid)),
                             hn::Mul(hn::Add(from_start, from_start), err)),
                     hn::Min(g_mid, hn::Sub(hn::Add(g_mid, g_mid), g_right)));
  const V lines_right =
      hn::IfThenElse(room_right,
                     hn::Sub(lines_bound(d, g_mid, hn::Sub(g_mid, g_left), g_right,
                                         hn::Mul(hn::Sub(g1, g_right), from_end)),
                             hn::Mul(hn::Add(from_end, from_end), err)),
                     hn::Min(g_mid, hn::Sub(hn::Add(g_mid, g_mid), g_left)));
  const V inner = hn::Min(hn::Max(hn::Mul(half, hn::Sub(hn::Add(g_left, g_mid), lipschitz_step)),
                                  hn::Sub(lines_left, inner_line_err)),
                          hn::Max(hn::Mul(half, hn::Sub(hn::Add(g_mid, g_right), lipschitz_step)),
                                  hn::Sub(lines_right, inner_line_err)));
  const V lower = hn::Min(hn::Min(outer_left, outer_right), inner);  // exact minimum >= lower - err
  const V upper = hn::Min(hn::Min(hn::Min(g0, g1), hn::Min(g_left, g_right)), g_mid);
  const M decidable = hn::And(alive, finite);
  CapsuleMinimum out;
  out.above = hn::And(decidable, hn::Gt(lower, above_limit));
  out.below = hn::AndNot(out.above, hn::And(decidable, hn::Lt(hn::Add(upper, err), below_limit)));
  // Other certificates cannot decide either: any lower bound is at most the minimum + err <= upper
  // + 2 err, any upper bound at least the minimum - err >= lower - 2 err.
  out.neither =
      hn::AndNot(hn::Or(out.above, out.below),
                 hn::And(decidable, hn::And(hn::Le(hn::Add(upper, hn::Add(err, err)), above_limit),
                                            hn::Ge(lower, hn::Add(below_limit, err)))));
  return out;
}

// certify_around at the side's place, then at the apex's for the lanes it left open (a lane that
// no certificate can decide is not tried again).
HWY_INLINE CapsuleMinimum certify_capsule_minimum(D d, const ConeLanes& l, const SunLanes& sun,
                                                  const BoundTerms& t, V g0, V g1, M alive, V err,
                                                  V above_limit, V below_limit) {
  const Places places = minimum_places(d, l, sun, t);
  const M none = hn::Lt(hn::Zero(d), hn::Zero(d));
  CapsuleMinimum out{none, none, none};
  M open = alive;
  for (const V& place : {places.side, places.apex}) {
    if (hn::AllFalse(d, open)) break;
    const CapsuleMinimum near =
        certify_around(d, l, sun, t, place, g0, g1, open, err, above_limit, below_limit);
    out.above = hn::Or(out.above, near.above);
    out.below = hn::Or(out.below, near.below);
    out.neither = hn::Or(out.neither, near.neither);
    open = hn::AndNot(hn::Or(hn::Or(near.above, near.below), near.neither), open);
  }
  return out;
}

// Entries [begin, begin + count) of each of five arrays, count <= lanes; missing lanes repeat
// entry `begin` (a full vector is one unaligned load per array).
HWY_INLINE void load_five(D d, const double* const (&arrays)[5], std::size_t begin,
                          std::size_t count, V (&out)[5]) {
  const std::size_t lanes = hn::Lanes(d);
  if (count == lanes) {
    for (int k = 0; k < 5; ++k) out[k] = hn::LoadU(d, arrays[k] + begin);
    return;
  }
  HWY_ALIGN double buffer[5][HWY_MAX_BYTES / sizeof(double)];
  for (std::size_t i = 0; i < lanes; ++i)
    for (int k = 0; k < 5; ++k) buffer[k][i] = arrays[k][begin + (i < count ? i : 0)];
  for (int k = 0; k < 5; ++k) out[k] = hn::Load(d, buffer[k]);
}

// The cones [begin, begin + count) of `a`, count <= lanes; missing lanes repeat the first cone.
HWY_INLINE ConeLanes load_cones(D d, const ConeArrays& a, std::size_t begin, std::size_t count) {
  V v[5];
  load_five(d,
            {a.tip[0].data(), a.tip[1].data(), a.tip[2].data(), a.start_height.data(),
             a.tip_length.data()},
            begin, count, v);
  ConeLanes l;
  for (int k = 0; k < 3; ++k) l.tip[k] = v[k];
  l.start = v[3];
  l.tip_length = v[4];
  return l;
}

// The cones indices[0 .. count) of `a`, count <= lanes; missing lanes repeat the first cone.
HWY_INLINE ConeLanes gather_cones(D d, const ConeArrays& a, const std::uint32_t* indices,
                                  std::size_t count) {
  const std::size_t lanes = hn::Lanes(d);
  HWY_ALIGN double buffer[5][HWY_MAX_BYTES / sizeof(double)];
  for (std::size_t i = 0; i < lanes; ++i) {
    const std::size_t j = indices[i < count ? i : 0];
    for (int k = 0; k < 3; ++k) buffer[k][i] = a.tip[k][j];
    buffer[3][i] = a.start_height[j];
    buffer[4][i] = a.tip_length[j];
  }
  ConeLanes l;
  for (int k = 0; k < 3; ++k) l.tip[k] = hn::Load(d, buffer[k]);
  l.start = hn::Load(d, buffer[3]);
  l.tip_length = hn::Load(d, buffer[4]);
  return l;
}

// may_shadow for the first `count` cones of l: bit i for lane i.
HWY_INLINE std::uint64_t may_shadow_lanes(D d, const ConeLanes& l, std::size_t count,
                                          const SunLanes& sun, const BoundTerms& t) {
  const V zero = hn::Zero(d);
  V bound_a[3], bound_b[3], middle[3];
  for (int k = 0; k < 3; ++k) {
    bound_a[k] = hn::Set(d, t.a[k]);
    bound_b[k] = hn::Set(d, t.b[k]);
    middle[k] = hn::Set(d, t.middle[k]);
  }
  const V ra = hn::Set(d, t.ra), rb = hn::Set(d, t.rb);
  // relative_margin * (length(tip) + length(a) + length(b) + ra + rb), left to right.
  const V height_slack = hn::Mul(
      hn::Set(d, relative_margin),
      hn::Add(
          hn::Add(hn::Add(hn::Add(l.tip_length, hn::Set(d, t.length_a)), hn::Set(d, t.length_b)),
                  ra),
          rb));
  const V floor = hn::Sub(l.start, height_slack);
  M result;
  if (!t.capsule) {
    const M below = hn::Lt(hn::Add(height(l, sun, bound_a), ra), floor);
    result = hn::AndNot(below, hn::Le(gap(d, l, sun, bound_a, ra), zero));
  } else {
    // Truncation, then the enclosing sphere: decided false where either rejects.
    const M below = hn::Lt(
        max_of(hn::Add(height(l, sun, bound_a), ra), hn::Add(height(l, sun, bound_b), rb)), floor);
    const M enclosing_out = hn::Gt(gap(d, l, sun, middle, hn::Set(d, t.enclosing)), zero);
    M alive = hn::Not(hn::Or(below, enclosing_out));
    // Most cones of a tile's surviving clusters end here.
    if (hn::AllFalse(d, hn::And(alive, hn::FirstN(d, count)))) return 0;
    const V g0 = capsule_gap(d, l, sun, t, zero), g1 = capsule_gap(d, l, sun, t, hn::Set(d, 1.0));
    const M end_hit = hn::And(alive, hn::Or(hn::Le(g0, zero), hn::Le(g1, zero)));
    result = end_hit;
    alive = hn::AndNot(end_hit, alive);
    if (!hn::AllFalse(d, alive)) {
      // Certified answers for most lanes, without the ternary search:
      // - false where the exact minimum of g over [0, 1] exceeds L (2/3)^40 (the final interval,
      //   below 1e-7 L) plus 2 err: every g the search evaluates is then > 0, and so is
      //   best - L (hi - lo);
      // - true where the exact minimum is below -2200 err: with f = g + 1e-9 |x(s) - tip| (convex,
      //   at most 1000 err above g), each of the search's 40 comparisons can lose at most 2 err
      //   plus 1e-9 L third of f's minimum over the interval (a wrong choice means the two
      //   thirds' f differ by less than that, and convexity bounds what lies beyond), so the
      //   final interval's f stays below -(2200 - 1000 - 80 - 1000) err, and its g(mid) - L (hi -
      //   lo) <= that + L (hi - lo) / 2 - L (hi - lo) < 0 (L <= magnitude).
      const V err = gap_error(d, l, t);
      const V above_limit = hn::Add(hn::Set(d, 1e-7 * t.lipschitz), hn::Add(err, err));
      const V below_limit = hn::Mul(hn::Set(d, -2200.0), err);
      const CapsuleMinimum decided =
          certify_capsule_minimum(d, l, sun, t, g0, g1, alive, err, above_limit, below_limit);
      result = hn::Or(result, decided.below);
      alive = hn::AndNot(hn::Or(decided.above, decided.below), alive);
    }
    V lo = zero, hi = hn::Set(d, 1.0);
    const V three = hn::Set(d, 3.0);
    for (int i = 0; i < 40 && !hn::AllFalse(d, alive); ++i) {
      const V third = hn::Div(hn::Sub(hi, lo), three);
      const V m1 = hn::Add(lo, third), m2 = hn::Sub(hi, third);
      const V gm1 = capsule_gap(d, l, sun, t, m1), gm2 = capsule_gap(d, l, sun, t, m2);
      const M hit = hn::And(alive, hn::Or(hn::Le(gm1, zero), hn::Le(gm2, zero)));
      result = hn::Or(result, hit);
      alive = hn::AndNot(hit, alive);
      const M left = hn::Le(gm1, gm2);
      hi = hn::IfThenElse(hn::And(alive, left), m2, hi);
      lo = hn::IfThenElse(hn::AndNot(left, alive), m1, lo);
    }
    if (!hn::AllFalse(d, alive)) {
      // best = std::min({g(lo), g(hi), g(mid), g(0), g(1)}): the first smallest.
      V best = capsule_gap(d, l, sun, t, lo);
      const V candidates[4] = {capsule_gap(d, l, sun, t, hi),
                               capsule_gap(d, l, sun, t, hn::Mul(hn::Set(d, 0.5), hn::Add(lo, hi))),
                               g0, g1};
      for (const V& g : candidates) best = hn::IfThenElse(hn::Lt(g, best), g, best);
      const M last = hn::Le(hn::Sub(best, hn::Mul(hn::Set(d, t.lipschitz), hn::Sub(hi, lo))), zero);
      result = hn::Or(result, hn::And(alive, last));
    }
  }
  return lane_bits(d, hn::And(result, hn::FirstN(d, count)));
}

// Bit i set where node begin + i of `level` (count <= lanes) may have a triangle below it whose
// may_shadow is true for the bound; clear where every one provably answers false. A triangle's
// cone_i lies inside the node's cone G and |x - tip_i| <= |x - tip_G| + spread, so its gap at any
// x and radius r, dist(cone_i, x) - r - 1e-9 (|x - tip_i| + r), is at least G's minus 1e-9
// spread (G's tip is rounded by ulps of |tip_G|, far inside these slacks). Hence:
// - the sphere the triangle tests first (the sphere bound, or the capsule's enclosing sphere):
//   G's computed gap > 2e-9 (|tip_G| + magnitude + spread + r) >= 2e-9 (|x - tip_G| + spread + r)
//   leaves the triangle's gap > 0 with room for every rounding, and it answers false;
// - a capsule: a triangle answers false once its exact minimum over s exceeds 1e-7 L + err_i (see
//   may_shadow_lanes), err_i <= err_max = 1e-12 (|tip_G| + spread + magnitude); so G's certified
//   minimum above 1e-7 L + 2 err_max + 2e-9 spread decides it.
HWY_INLINE std::uint64_t open_nodes(D d, const ConeGroups& level, std::size_t begin,
                                    std::size_t count, const SunLanes& sun, const BoundTerms& t) {
  V v[5];
  load_five(d,
            {level.tip[0].data(), level.tip[1].data(), level.tip[2].data(), level.tip_length.data(),
             level.spread.data()},
            begin, count, v);
  ConeLanes l;
  for (int k = 0; k < 3; ++k) l.tip[k] = v[k];
  l.tip_length = v[3];
  const V spread = v[4];
  l.start = hn::Zero(d);  // unused: truncation is left to the triangles
  const V zero = hn::Zero(d);
  V centre[3];
  for (int k = 0; k < 3; ++k) centre[k] = hn::Set(d, t.capsule ? t.middle[k] : t.a[k]);
  const V radius = hn::Set(d, t.capsule ? t.enclosing : t.ra);
  const V magnitude = hn::Set(d, t.magnitude);
  const V sphere_limit =
      hn::Mul(hn::Set(d, 2.0 * relative_margin),
              hn::Add(hn::Add(hn::Add(l.tip_length, magnitude), spread), radius));
  // An infinite spread (a non-finite tip below) or a NaN never closes a node.
  M closed = hn::Gt(gap(d, l, sun, centre, radius), sphere_limit);
  const M open = hn::AndNot(closed, hn::FirstN(d, count));
  if (t.capsule && !hn::AllFalse(d, open)) {
    const V err_max = hn::Mul(hn::Set(d, 1e-12), hn::Add(hn::Add(l.tip_length, spread), magnitude));
    const V above_limit =
        hn::Add(hn::Add(hn::Set(d, 1e-7 * t.lipschitz), hn::Add(err_max, err_max)),
                hn::Mul(hn::Set(d, 2.0 * relative_margin), spread));
    const V g0 = capsule_gap(d, l, sun, t, zero), g1 = capsule_gap(d, l, sun, t, hn::Set(d, 1.0));
    const M tried = hn::And(open, hn::And(hn::Gt(g0, above_limit), hn::Gt(g1, above_limit)));
    if (!hn::AllFalse(d, tried))
      closed =
          hn::Or(closed, certify_capsule_minimum(d, l, sun, t, g0, g1, tried, gap_error(d, l, t),
                                                 above_limit, hn::Set(d, -HUGE_VAL))
                             .above);
  }
  return lane_bits(d, hn::AndNot(closed, hn::FirstN(d, count)));
}

void CullCandidates(const GatheredCones& cones, const shadowcts::softtile::TileBound& bound,
                    std::vector<std::uint32_t>& candidates) {
  const D d;
  const std::size_t lanes = hn::Lanes(d);
  const BoundTerms t = detail::bound_terms(bound);
  SunLanes sun;
  for (int k = 0; k < 3; ++k) {
    sun.d[k] = hn::Set(d, cones.direction[k]);
    sun.axis[k] = hn::Set(d, -cones.direction[k]);
  }
  sun.c = hn::Set(d, cones.cos_radius);
  sun.s = hn::Set(d, cones.sin_radius);
  candidates.clear();
  const ConeTree& tree = cones.tree;
  if (tree.levels.empty()) return;
  // Depth first from the top level: (level, first node, node count) of child runs to test.
  struct Run {
    std::size_t level, first, count;
  };
  std::vector<Run> stack;
  const std::size_t top = tree.levels.size() - 1;
  for (std::size_t n0 = 0; n0 < tree.levels[top].spread.size(); n0 += lanes)
    stack.push_back({top, n0, std::min(lanes, tree.levels[top].spread.size() - n0)});
  while (!stack.empty()) {
    const Run run = stack.back();
    stack.pop_back();
    std::uint64_t open = open_nodes(d, tree.levels[run.level], run.first, run.count, sun, t);
    for (; open != 0; open &= open - 1) {
      const std::size_t node = run.first + std::size_t(__builtin_ctzll(open));
      const std::size_t first = node * tree_arity;
      if (run.level > 0) {
        const std::size_t end =
            std::min(tree.levels[run.level - 1].spread.size(), first + tree_arity);
        for (std::size_t c0 = first; c0 < end; c0 += lanes)
          stack.push_back({run.level - 1, c0, std::min(lanes, end - c0)});
        continue;
      }
      const std::size_t end = std::min(tree.index.size(), first + tree_arity);
      for (std::size_t k0 = first; k0 < end; k0 += lanes) {
        const std::size_t m = std::min(lanes, end - k0);
        for (std::uint64_t bits =
                 may_shadow_lanes(d, load_cones(d, tree.triangles, k0, m), m, sun, t);
             bits != 0; bits &= bits - 1)
          candidates.push_back(tree.index[k0 + std::size_t(__builtin_ctzll(bits))]);
      }
    }
  }
  // Gathered order, then only the triangles whose cluster's cone may shadow the bound too.
  // (Highway's sort: std::sort took 5.6 % of the simd run at foliage.1M. A Sorter owns a buffer:
  // one per thread.)
  static thread_local const hwy::Sorter sorter;
  sorter(candidates.data(), candidates.size(), hwy::SortAscending());
  std::vector<std::uint32_t> clusters;
  for (const std::uint32_t k : candidates)
    if (clusters.empty() || clusters.back() != cones.cluster_of[k])
      clusters.push_back(cones.cluster_of[k]);
  std::vector<std::uint8_t> kept(clusters.size());
  for (std::size_t c0 = 0; c0 < clusters.size(); c0 += lanes) {
    const std::size_t n = std::min(lanes, clusters.size() - c0);
    const std::uint64_t bits =
        may_shadow_lanes(d, gather_cones(d, cones.clusters, clusters.data() + c0, n), n, sun, t);
    for (std::size_t i = 0; i < n; ++i) kept[c0 + i] = (bits >> i) & 1u;
  }
  std::size_t out = 0, c = 0;
  for (const std::uint32_t k : candidates) {
    while (clusters[c] != cones.cluster_of[k]) ++c;
    if (kept[c]) candidates[out++] = k;
  }
  candidates.resize(out);
}

}  // namespace HWY_NAMESPACE
}  // namespace shadowcts::simd::softtile
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::softtile {

HWY_EXPORT(CullCandidates);

namespace {

void resize(ConeArrays& arrays, std::size_t n) {
  for (int k = 0; k < 3; ++k) arrays.tip[k].resize(n);
  arrays.start_height.resize(n);
  arrays.tip_length.resize(n);
}

void set_cone(ConeArrays& arrays, std::size_t i, const shadowcts::softtile::ShadowCone& cone) {
  for (int k = 0; k < 3; ++k) arrays.tip[k][i] = cone.tip[k];
  arrays.start_height[i] = cone.start_height;
  arrays.tip_length[i] = glm::length(cone.tip);
}

// A ball that holds the tips of every triangle below a node (from the box around them), and
// whether each of those tips and the node's cone are finite.
struct TipBall {
  glm::dvec3 lo, hi, centre;
  double radius;
  bool finite;
};

// Node `index` of `level` over members [begin, end), given as balls around the triangle tips below
// each (a triangle: its tip, radius 0). The node's ball is centred in the box around the members'
// balls' boxes and holds each member's ball; a ball (centre c, radius R) lies inside the cone of
// half-angle a whose tip is R / sin(a) above c (as shadow_cone() places a cone around a caster's
// sphere; widened by 1e-9 against rounding), so every triangle's tip below lies inside the node's
// cone, and so does the triangle's cone, a translate of it by a point inside it. The ball is made
// from the tips, not from the members' cone tips: each level would raise those again by R / sin(a)
// (x 29 at the sun's 2 degrees), and nodes above the first levels would hold everything.
template <class Ball>
TipBall set_node(ConeGroups& level, std::size_t index, std::size_t begin, std::size_t end,
                 const Ball& ball_of, const glm::dvec3& direction, double sin_radius) {
  TipBall members[tree_arity] = {};
  const std::size_t count = end - begin;
  for (std::size_t i = 0; i < count; ++i) members[i] = ball_of(begin + i);
  TipBall node = members[0];
  for (std::size_t i = 1; i < count; ++i) {
    node.lo = glm::min(node.lo, members[i].lo);
    node.hi = glm::max(node.hi, members[i].hi);
    node.finite = node.finite && members[i].finite;
  }
  node.centre = 0.5 * (node.lo + node.hi);
  double radius = 0.0;
  for (std::size_t i = 0; i < count; ++i)
    radius = std::max(radius, glm::length(members[i].centre - node.centre) + members[i].radius);
  node.radius = radius * (1.0 + 1e-9) + 1e-300;
  const glm::dvec3 node_tip = node.centre + direction * (node.radius * (1.0 + 1e-9) / sin_radius);
  // The largest distance from the node's tip to a triangle's tip below it.
  double spread = 0.0;
  for (std::size_t i = 0; i < count; ++i)
    spread = std::max(spread, glm::length(members[i].centre - node_tip) + members[i].radius);
  spread *= 1.0 + 1e-9;
  node.finite = node.finite && std::isfinite(node.radius) && std::isfinite(node_tip.x) &&
                std::isfinite(node_tip.y) && std::isfinite(node_tip.z) && std::isfinite(spread);
  for (int k = 0; k < 3; ++k) level.tip[k][index] = node_tip[k];
  level.tip_length[index] = glm::length(node_tip);
  level.spread[index] = node.finite ? spread : HUGE_VAL;
  return node;
}

ConeTree cone_tree(const shadowcts::softtile::Gathered& gathered, const glm::dvec3& direction,
                   double sin_radius) {
  const std::size_t n = gathered.triangles.size();
  const auto finite = [](const glm::dvec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  for (const shadowcts::softtile::GatheredTriangle& t : gathered.triangles)
    if (finite(t.cone.tip)) {
      lo = glm::min(lo, t.cone.tip);
      hi = glm::max(hi, t.cone.tip);
    }
  // Keys in one 64-bit word, sorted in lanes: whether the tip is not finite (those after every
  // finite one), the Morton code of the tip over the finite tips' box in as many bits per axis as
  // the index leaves (21 down to 14 at a million triangles: their top bits), then the index:
  // unique, so the order is deterministic.
  const auto index_bits = unsigned(std::bit_width(n));
  const unsigned axis_bits = std::min(21u, (63u - index_bits) / 3u);
  HugePageVector<std::uint64_t> keys(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const glm::dvec3 tip = gathered.triangles[i].cone.tip;
    const std::uint64_t code =
        finite(tip) ? geometry::morton_code_in_box(tip, lo, hi - lo) >> (63u - 3u * axis_bits)
                    : std::uint64_t(1) << (3u * axis_bits);
    keys[i] = code << index_bits | i;
  });
  const hwy::Sorter sorter;
  sorter(keys.data(), n, hwy::SortAscending());
  const std::uint64_t index_mask = (std::uint64_t(1) << index_bits) - 1;
  ConeTree tree;
  resize(tree.triangles, n);
  tree.index.resize(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
    const auto i = std::uint32_t(keys[k] & index_mask);
    set_cone(tree.triangles, k, gathered.triangles[i].cone);
    tree.index[k] = i;
  });
  const ConeArrays& leaves = tree.triangles;
  // Of the nodes of the level below and of the new level (88 bytes each: 11 MB over a million
  // triangles).
  HugePageVector<TipBall> balls, above;
  std::size_t count = n;
  while (count > 0 && (tree.levels.empty() || count > tree_arity)) {
    const std::size_t nodes = (count + tree_arity - 1) / tree_arity;
    ConeGroups level;
    for (std::vector<double>* array :
         {&level.tip[0], &level.tip[1], &level.tip[2], &level.tip_length, &level.spread})
      array->resize(nodes);
    above.resize(nodes);
    const bool over_triangles = tree.levels.empty();
    tbb::parallel_for(std::size_t(0), nodes, [&](std::size_t node) {
      const std::size_t first = node * tree_arity, end = std::min(count, first + tree_arity);
      if (over_triangles)
        above[node] = set_node(
            level, node, first, end,
            [&](std::size_t i) {
              const glm::dvec3 tip(leaves.tip[0][i], leaves.tip[1][i], leaves.tip[2][i]);
              return TipBall{tip, tip, tip, 0.0, finite(tip)};
            },
            direction, sin_radius);
      else
        above[node] = set_node(
            level, node, first, end, [&](std::size_t i) { return balls[i]; }, direction,
            sin_radius);
    });
    std::swap(balls, above);
    count = nodes;
    tree.levels.push_back(std::move(level));
  }
  return tree;
}

}  // namespace

GatheredCones gathered_cones(const shadowcts::softtile::Gathered& gathered) {
  GatheredCones cones;
  cones.cluster_of.resize(gathered.triangles.size());
  resize(cones.clusters, gathered.clusters.size());
  for (std::size_t c = 0; c < gathered.clusters.size(); ++c) {
    const shadowcts::softtile::GatheredCluster& cluster = gathered.clusters[c];
    set_cone(cones.clusters, c, cluster.cone);
    std::fill_n(cones.cluster_of.begin() + cluster.first, cluster.count, std::uint32_t(c));
  }
  for (int k = 0; k < 3; ++k) cones.direction[k] = gathered.sun.direction[k];
  // distance_to_cone's std::cos / std::sin of the half-angle, the same value every call.
  cones.cos_radius = std::cos(gathered.sun.angular_radius);
  cones.sin_radius = std::sin(gathered.sun.angular_radius);
  cones.tree = cone_tree(gathered, gathered.sun.direction, cones.sin_radius);
  return cones;
}

void cull_candidates(const GatheredCones& cones, const shadowcts::softtile::TileBound& bound,
                     std::vector<std::uint32_t>& candidates) {
  HWY_DYNAMIC_DISPATCH(CullCandidates)(cones, bound, candidates);
}

}  // namespace shadowcts::simd::softtile
#endif  // HWY_ONCE
