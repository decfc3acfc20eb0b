// Highway translation unit of the simd softtile's cone culling (see shadow_cone.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/softtile/shadow_cone.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <hwy/contrib/sort/vqsort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <glm/geometric.hpp>

#include "shadowcts/geometry/morton.h"
#include "simd/softtile/shadow_cone.h"

#ifndef SHADOWCTS_SIMD_SOFTTILE_BOUND_TERMS
#define SHADOWCTS_SIMD_SOFTTILE_BOUND_TERMS
namespace shadowcts::simd::softtile::detail {

// The reference's relative margin (reference/softtile/shadow_cone.cpp).
inline constexpr double relative_margin = 1e-9;

// Rounds of nine more samples of a capsule's g before the reference's ternary search decides.
inline constexpr int refinement_levels = 3;

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

using detail::BoundTerms;
using detail::refinement_levels;
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

// Lower bounds on the exact g over each interval between nine samples g[k] a step apart (each
// computed within err): Lipschitz, g >= (g_k + g_k+1 - L step) / 2 on [k, k+1]; convexity, g lies
// above the lines through the neighbouring pairs of samples, L(t) = g_k + (g_k - g_k-1) t and R(t)
// = g_k+1 - (g_k+2 - g_k+1) (1 - t), t in [0, 1]. Any weight w in [0, 1] gives min(max(L, R)) >=
// min over t of w L(t) + (1 - w) R(t), attained at t = 0 or 1; the w that makes it flat gives the
// lines' crossing. Each line carries at most 3 err from the samples; and g is convex only up to its
// slack term -1e-9 |x(s) - tip| (concave), which moves the lines by at most 2e-9 max |x - tip|
// <= 2e-9 (|tip| + magnitude) = 2000 err (err is 1e-12 of that sum).
HWY_INLINE void interval_bounds(D d, const V g[9], V lipschitz_step, V err, V bound[8]) {
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const V line_err = hn::Mul(hn::Set(d, 2004.0), err);
  for (int k = 0; k < 8; ++k) {
    const V piece = hn::Mul(half, hn::Sub(hn::Add(g[k], g[k + 1]), lipschitz_step));
    V convex;
    if (k == 0) {
      convex = hn::Min(hn::Sub(hn::Add(g[1], g[1]), g[2]), g[1]);
    } else if (k == 7) {
      convex = hn::Min(g[7], hn::Sub(hn::Add(g[7], g[7]), g[6]));
    } else {
      const V left_slope = hn::Sub(g[k], g[k - 1]);       // of L, per step
      const V right_slope = hn::Sub(g[k + 2], g[k + 1]);  // of R, per step
      // w left_slope + (1 - w) right_slope = 0; L alone where it does not fall, R alone where it
      // does not rise.
      V w = hn::Div(right_slope, hn::Sub(right_slope, left_slope));
      w = hn::IfThenElse(hn::Ge(left_slope, zero), one, w);
      w = hn::IfThenElse(hn::Le(right_slope, zero), zero, w);
      w = hn::Min(hn::Max(w, zero), one);
      const V at0 =
          hn::Add(hn::Mul(w, g[k]), hn::Mul(hn::Sub(one, w), hn::Sub(g[k + 1], right_slope)));
      const V at1 =
          hn::Add(hn::Mul(w, hn::Add(g[k], left_slope)), hn::Mul(hn::Sub(one, w), g[k + 1]));
      convex = hn::Min(at0, at1);
    }
    bound[k] = hn::Max(piece, hn::Sub(convex, line_err));
  }
}

// What computed gaps are within of the exact ones: 1e-12 of |tip| + the bound's magnitude, far
// above the rounding of gap()'s few operations on those magnitudes.
HWY_INLINE V gap_error(D d, const ConeLanes& l, const BoundTerms& t) {
  return hn::Mul(hn::Set(d, 1e-12), hn::Add(l.tip_length, hn::Set(d, t.magnitude)));
}

struct CapsuleMinimum {
  M above;  // lanes whose exact minimum is > above_limit - err
  M below;  // lanes whose exact minimum is < below_limit
};

// Certifies, for the lanes of `alive`, where the exact minimum over s in [0, 1] of the capsule's
// g (the gap of cone l at a + s (b - a), radius ra + s (rb - ra); g0 and g1 its computed values at
// 0 and 1) lies against two limits, from samples of g, each computed within err of the exact g,
// which is L-Lipschitz in s and convex but for its slack term (see interval_bounds).
// Nine samples at k / 8 first; then, while lanes stay undecided, nine across the two intervals
// beside the smallest sample, whose bounds replace those two intervals' (the positions stay
// dyadic, hence exact). A NaN or infinity anywhere: never certified.
HWY_INLINE CapsuleMinimum certify_capsule_minimum(D d, const ConeLanes& l, const SunLanes& sun,
                                                  const BoundTerms& t, V g0, V g1, M alive, V err,
                                                  V above_limit, V below_limit) {
  const V zero = hn::Zero(d);
  const V lipschitz = hn::Set(d, t.lipschitz * (1.0 + 1e-6));
  const V inf = hn::Set(d, HUGE_VAL), one = hn::Set(d, 1.0), eighth = hn::Set(d, 0.125);
  CapsuleMinimum out{hn::Lt(zero, zero), hn::Lt(zero, zero)};
  M finite = hn::Lt(hn::Abs(err), inf);
  V g[9];
  g[0] = g0;
  g[8] = g1;
  for (int k = 1; k < 8; ++k) g[k] = capsule_gap(d, l, sun, t, hn::Set(d, k / 8.0));
  V lo = zero, step = eighth;
  V outside = inf;  // a lower bound on g over [0, 1] outside [lo, lo + 8 step]
  V upper = inf;    // the smallest sample
  for (int level = 0;; ++level) {
    for (const V& gk : g) {
      finite = hn::And(finite, hn::Lt(hn::Abs(gk), inf));
      upper = hn::Min(upper, gk);
    }
    V bound[8];
    interval_bounds(d, g, hn::Mul(lipschitz, step), err, bound);
    V lower = outside;  // exact minimum >= lower - err
    for (const V& b : bound) lower = hn::Min(lower, b);
    const M above = hn::And(hn::And(alive, finite), hn::Gt(lower, above_limit));
    out.above = hn::Or(out.above, above);
    alive = hn::AndNot(above, alive);
    // upper + err >= the exact minimum.
    const M below = hn::And(hn::And(alive, finite), hn::Lt(hn::Add(upper, err), below_limit));
    out.below = hn::Or(out.below, below);
    alive = hn::AndNot(below, alive);
    // Lanes that can be neither any more: a later lower is at most the minimum + err <= upper +
    // 2 err, a later upper at least the minimum - err >= lower - 2 err.
    alive = hn::AndNot(hn::And(hn::Le(hn::Add(upper, hn::Add(err, err)), above_limit),
                               hn::Ge(lower, hn::Add(below_limit, err))),
                       alive);
    if (level == refinement_levels || hn::AllFalse(d, alive)) break;
    V smallest = g[0], at = zero;
    for (int k = 1; k < 9; ++k) {
      const M smaller = hn::Lt(g[k], smallest);
      smallest = hn::IfThenElse(smaller, g[k], smallest);
      at = hn::IfThenElse(smaller, hn::Set(d, double(k)), at);
    }
    const V first = hn::Max(hn::Sub(at, one), zero),
            last = hn::Min(hn::Add(at, one), hn::Set(d, 8.0));
    V g_first = g[0], g_last = g[8];
    for (int k = 0; k < 9; ++k) {
      const V index = hn::Set(d, double(k));
      g_first = hn::IfThenElse(hn::Eq(first, index), g[k], g_first);
      g_last = hn::IfThenElse(hn::Eq(last, index), g[k], g_last);
      if (k < 8)
        outside = hn::IfThenElse(hn::Or(hn::Lt(index, first), hn::Ge(index, last)),
                                 hn::Min(outside, bound[k]), outside);
    }
    lo = hn::Add(lo, hn::Mul(first, step));
    step = hn::Mul(hn::Mul(hn::Sub(last, first), step), eighth);
    g[0] = g_first;
    g[8] = g_last;
    for (int k = 1; k < 8; ++k)
      g[k] = capsule_gap(d, l, sun, t, hn::Add(lo, hn::Mul(hn::Set(d, double(k)), step)));
  }
  return out;
}

HWY_INLINE std::uint64_t mask_bits(D d, M m) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, m, bytes);
  std::uint64_t bits = 0;
  std::memcpy(&bits, bytes, sizeof bits);
  return bits;
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
      const CapsuleMinimum decided =
          certify_capsule_minimum(d, l, sun, t, g0, g1, alive, err,
                                  hn::Add(hn::Set(d, 1e-7 * t.lipschitz), hn::Add(err, err)),
                                  hn::Mul(hn::Set(d, -2200.0), err));
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
  return mask_bits(d, hn::And(result, hn::FirstN(d, count)));
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
  return mask_bits(d, hn::AndNot(closed, hn::FirstN(d, count)));
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

void append(ConeArrays& arrays, const shadowcts::softtile::ShadowCone& cone) {
  for (int k = 0; k < 3; ++k) arrays.tip[k].push_back(cone.tip[k]);
  arrays.start_height.push_back(cone.start_height);
  arrays.tip_length.push_back(glm::length(cone.tip));
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
  // Keys: the Morton code of the tip in 21 bits per axis over the finite tips' box (non-finite
  // tips after every finite one), then the index: unique, so the order is deterministic.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    const glm::dvec3 tip = gathered.triangles[i].cone.tip;
    keys[i] = {finite(tip) ? geometry::morton_code_in_box(tip, lo, hi - lo) : ~std::uint64_t(0),
               std::uint32_t(i)};
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  ConeTree tree;
  for (const auto& [code, i] : keys) {
    append(tree.triangles, gathered.triangles[i].cone);
    tree.index.push_back(i);
  }
  const ConeArrays& leaves = tree.triangles;
  std::vector<TipBall> balls, above;  // of the nodes of the level below and of the new level
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
  for (std::size_t c = 0; c < gathered.clusters.size(); ++c) {
    const shadowcts::softtile::GatheredCluster& cluster = gathered.clusters[c];
    append(cones.clusters, cluster.cone);
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
