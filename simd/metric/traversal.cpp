// The packet traversal of the simd `metric` (traversal.h): the one translation unit of the port
// that Highway compiles once per target; the plain C++ precomputations are at the end (HWY_ONCE).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/metric/traversal.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "shadowcts/float_rounding.h"
#include "simd/lane_bits-inl.h"
#include "simd/metric/traversal.h"

// Plain C++ used by every target and by the precomputations: defined once per translation unit.
#ifndef SHADOWCTS_SIMD_METRIC_TRAVERSAL_ONCE
#define SHADOWCTS_SIMD_METRIC_TRAVERSAL_ONCE
namespace shadowcts::simd::metric {
// The window of the float cone tests: at least 2^-16 (see evaluate_in_float), wider where a test
// widens the double one, so that the lanes it hands back still reach the double path. The planar
// tests' window is this times S.
inline float cone_window(double decision_window) {
  return float(std::max(0x1p-16, 2.0 * decision_window));
}
// How far outside a cluster's plane bounds (NodeCluster::plane_low, plane_high) a directional
// light's line must pass to miss every triangle of the cluster certainly: 2^-14 of the case's
// scale, eight times the rounding of the ray-space vertices (lanes_missing_cluster).
inline double cluster_miss_margin(double scale) {
  return 0x1p-14 * scale;
}
// The float bounds of x, y, x + y and x - y of a cluster's vertices in the light's plane, before
// NodeCluster's widening (ClusterPlaneBounds); finite = 0 where some coordinate is NaN.
struct PlaneBounds {
  float low[4], high[4];
  bool finite;
};
}  // namespace shadowcts::simd::metric
#endif

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::metric::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using shadowcts::simd::HWY_NAMESPACE::lane_bits;

using shadowcts::metric::LightFrame;
using shadowcts::metric::LightSpaceQuery;
using shadowcts::metric::TraversalCounters;
using shadowcts::metric::TraversalScene;
using shadowcts::metric::TreeChild;

// Float lanes per packet chunk: a whole 16-sample packet is one AVX-512 vector of floats.
constexpr std::size_t max_float_lanes = 16;

template <std::size_t P>
struct Packet {
  alignas(64) double ux[P], uy[P], uz[P], qld[P];
  // The direction in float, and floats below and above the light distance; at least 16 wide so
  // that a full float vector can always be loaded (lanes past P are masked off).
  static constexpr std::size_t float_lanes = P < max_float_lanes ? max_float_lanes : P;
  alignas(64) float fx[float_lanes], fy[float_lanes], fz[float_lanes];
  alignas(64) float qlo[float_lanes], qhi[float_lanes];
  // Lanes whose sample lies within the case's scale (LightFrame::scale) on every axis: the
  // directional cluster test (lanes_missing_cluster) is certain only for those.
  std::uint64_t within_scale = 0;
  std::uint32_t sample_index[P];  // the view sample's (ViewSamples::samples) index
  const ViewSample* sample[P];
  std::uint32_t receiver[P];
  std::uint32_t receiver_slot[P];  // the receiver's slot in cluster order, or ~0u
  // The plane of the receiver (ClusterPlanes::of_triangle); at least 16 wide, as the floats.
  alignas(64) std::uint32_t receiver_plane[float_lanes];
  RaySpace ray[P];
  // The ends of the segment the slabs are tested against (segment_meets_slabs), by coordinate.
  alignas(64) double from_x[P], from_y[P], from_z[P], to_x[P], to_y[P], to_z[P];
  std::optional<geometry::ReceiverHalfSpace> half_space[P];
};

// Whether a threshold's lanes are read below it (inside, overlap_high, near_side) or above it.
constexpr bool read_below(int k) {
  return k == inside || k == overlap_high || k == near_side;
}

// Lane l of a packet is bit l (packets of up to 64 samples).
using LaneMask = std::uint64_t;

// A node and the lanes that walk it. Each field is written and read whole, so that every pop's
// loads are forwarded from the push's stores.
struct StackEntry {
  LaneMask lanes;
  std::uint32_t node;
};

// The decisions of one node for the lanes of a packet, as lane masks.
struct NodeDecisions {
  LaneMask reached = 0;  // step 1 passed: the sample is not closer to the light
  LaneMask deep = 0;     // not in front of the pivot's own volume
  LaneMask inside = 0, overlap = 0, far = 0, near = 0;
};

template <class D, class V>
HWY_INLINE void angle_thresholds(D d, const PacketNode& n, V s, V c, int k, V& f) {
  f = hn::Sub(hn::Mul(s, hn::Set(d, n.cos_t[k])), hn::Mul(c, hn::Set(d, n.sin_t[k])));
}

// Angle between u and a unit direction as (|u x a|, u . a), in glm's order of operations.
template <class V>
HWY_INLINE void sine_cosine(V ux, V uy, V uz, V ax, V ay, V az, V& s, V& c) {
  const V cx = hn::Sub(hn::Mul(uy, az), hn::Mul(ay, uz));
  const V cy = hn::Sub(hn::Mul(uz, ax), hn::Mul(az, ux));
  const V cz = hn::Sub(hn::Mul(ux, ay), hn::Mul(ax, uy));
  s = hn::Sqrt(hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz)));
  c = hn::Add(hn::Add(hn::Mul(ux, ax), hn::Mul(uy, ay)), hn::Mul(uz, az));
}

template <std::size_t P>
NodeDecisions evaluate_node(const PacketTraversal& traversal, const PacketNode& n,
                            const Packet<P>& pk, LaneMask lanes) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  constexpr std::size_t max_lanes = 8;
  const std::size_t N = std::min(hn::Lanes(d), max_lanes);
  const LaneMask chunk = (LaneMask(1) << N) - 1;
  const LightFrame& frame = traversal.scene->frame;
  const double window = frame.directional ? traversal.nodes->decision_window * frame.scale
                                          : traversal.nodes->decision_window;
  const V lo = hn::Set(d, -window), hi = hn::Set(d, window);
  bool needed[thresholds];
  needed[inside] = true;
  needed[overlap_low] = needed[overlap_high] = n.has_child[int(TreeChild::overlap)];
  needed[far_side] = n.has_child[int(TreeChild::far)];
  needed[near_side] = n.has_child[int(TreeChild::near)];

  NodeDecisions out;
  LaneMask below[thresholds] = {}, above[thresholds] = {}, unsure = 0;
  for (std::size_t j = 0; j < P; j += N) {
    const LaneMask here = (lanes >> j) & chunk;
    if (here == 0) continue;
    const V qld = hn::Load(d, pk.qld + j);
    const LaneMask reached =
        lane_bits(d, hn::Not(hn::Lt(qld, hn::Set(d, n.light_distance)))) & here;
    if (reached == 0) continue;
    out.reached |= reached << j;
    out.deep |= (lane_bits(d, hn::Ge(qld, hn::Set(d, n.pivot_light_distance))) & reached) << j;
    if (n.kind == NodeKind::covers_everything) {
      unsure |= reached << j;
      continue;
    }
    const V ux = hn::Load(d, pk.ux + j), uy = hn::Load(d, pk.uy + j);
    V f[thresholds];
    if (n.kind == NodeKind::point_cone || n.kind == NodeKind::arc_cone) {
      const V uz = hn::Load(d, pk.uz + j);
      const V ax = hn::Set(d, n.a[0]), ay = hn::Set(d, n.a[1]), az = hn::Set(d, n.a[2]);
      V s, c;
      sine_cosine(ux, uy, uz, ax, ay, az, s, c);
      if (n.kind == NodeKind::point_cone) {
        for (int k = 0; k < thresholds; ++k) {
          if (!needed[k]) continue;
          angle_thresholds(d, n, s, c, k, f[k]);
          below[k] |= (lane_bits(d, hn::Lt(f[k], lo)) & reached) << j;
          above[k] |= (lane_bits(d, hn::Gt(f[k], hi)) & reached) << j;
        }
      } else {
        // distance_to_arc: the projection on the arc's plane when the arc spans it, else the
        // nearer endpoint (below if either endpoint is below, above if both are above).
        const V bx = hn::Set(d, n.b[0]), by = hn::Set(d, n.b[1]), bz = hn::Set(d, n.b[2]);
        const V nx = hn::Set(d, n.normal[0]), ny = hn::Set(d, n.normal[1]),
                nz = hn::Set(d, n.normal[2]);
        const V h = hn::Add(hn::Add(hn::Mul(ux, nx), hn::Mul(uy, ny)), hn::Mul(uz, nz));
        const V px = hn::Sub(ux, hn::Mul(h, nx)), py = hn::Sub(uy, hn::Mul(h, ny)),
                pz = hn::Sub(uz, hn::Mul(h, nz));
        const V length =
            hn::Sqrt(hn::Add(hn::Add(hn::Mul(px, px), hn::Mul(py, py)), hn::Mul(pz, pz)));
        // arc_spans: (a x w) . n >= 0 and (w x b) . n >= 0.
        const V awx = hn::Sub(hn::Mul(ay, pz), hn::Mul(py, az));
        const V awy = hn::Sub(hn::Mul(az, px), hn::Mul(pz, ax));
        const V awz = hn::Sub(hn::Mul(ax, py), hn::Mul(px, ay));
        const V wbx = hn::Sub(hn::Mul(py, bz), hn::Mul(by, pz));
        const V wby = hn::Sub(hn::Mul(pz, bx), hn::Mul(bz, px));
        const V wbz = hn::Sub(hn::Mul(px, by), hn::Mul(bx, py));
        const V zero = hn::Zero(d);
        const auto spans = hn::And(
            hn::Gt(length, zero),
            hn::And(hn::Ge(hn::Add(hn::Add(hn::Mul(awx, nx), hn::Mul(awy, ny)), hn::Mul(awz, nz)),
                           zero),
                    hn::Ge(hn::Add(hn::Add(hn::Mul(wbx, nx), hn::Mul(wby, ny)), hn::Mul(wbz, nz)),
                           zero)));
        const LaneMask span_bits = lane_bits(d, spans);
        V sb, cb;
        sine_cosine(ux, uy, uz, bx, by, bz, sb, cb);
        const V sp = hn::Abs(h);
        for (int k = 0; k < thresholds; ++k) {
          if (!needed[k]) continue;
          V fa, fb, fp;
          angle_thresholds(d, n, s, c, k, fa);
          angle_thresholds(d, n, sb, cb, k, fb);
          angle_thresholds(d, n, sp, length, k, fp);
          const LaneMask below_spanned = lane_bits(d, hn::Lt(fp, lo)),
                         above_spanned = lane_bits(d, hn::Gt(fp, hi));
          const LaneMask below_ends = lane_bits(d, hn::Or(hn::Lt(fa, lo), hn::Lt(fb, lo))),
                         above_ends = lane_bits(d, hn::And(hn::Gt(fa, hi), hn::Gt(fb, hi)));
          below[k] |= (((span_bits & below_spanned) | (~span_bits & below_ends)) & reached) << j;
          above[k] |= (((span_bits & above_spanned) | (~span_bits & above_ends)) & reached) << j;
        }
      }
    } else {
      const V dx = hn::Sub(ux, hn::Set(d, n.a[0])), dy = hn::Sub(uy, hn::Set(d, n.a[1]));
      V ex = dx, ey = dy;
      if (n.kind == NodeKind::capsule_2d) {
        // closest_parameter, then p - (a + t (b - a)).
        const V abx = hn::Set(d, n.b[0]), aby = hn::Set(d, n.b[1]);
        V t = hn::Zero(d);
        if (n.segment_length_squared > 0.0) {
          t = hn::Div(hn::Add(hn::Mul(dx, abx), hn::Mul(dy, aby)),
                      hn::Set(d, n.segment_length_squared));
          t = hn::Min(hn::Max(t, hn::Zero(d)), hn::Set(d, 1.0));
        }
        ex = hn::Sub(ux, hn::Add(hn::Set(d, n.a[0]), hn::Mul(t, abx)));
        ey = hn::Sub(uy, hn::Add(hn::Set(d, n.a[1]), hn::Mul(t, aby)));
      }
      const V distance =
          hn::Sub(hn::Sqrt(hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey))), hn::Set(d, n.radius));
      for (int k = 0; k < thresholds; ++k) {
        if (!needed[k]) continue;
        f[k] = hn::Sub(distance, hn::Set(d, n.threshold[k]));
        below[k] |= (lane_bits(d, hn::Lt(f[k], lo)) & reached) << j;
        above[k] |= (lane_bits(d, hn::Gt(f[k], hi)) & reached) << j;
      }
    }
  }
  for (int k = 0; k < thresholds; ++k)
    if (needed[k]) unsure |= out.reached & ~(below[k] | above[k]);
  out.inside = below[inside];
  out.overlap = above[overlap_low] & below[overlap_high];
  out.far = above[far_side];
  out.near = below[near_side];
  // The reference's own pivot distance and comparisons for the lanes near a threshold.
  const auto& scene = *traversal.scene;
  for (LaneMask rest = unsure; rest != 0; rest &= rest - 1) {
    const int l = std::countr_zero(rest);
    const LaneMask bit = LaneMask(1) << l;
    // The lane's query, as make_light_space_query made it (a lane at the light is never walked).
    LightSpaceQuery query;
    query.position = glm::dvec3(pk.ux[l], pk.uy[l], pk.uz[l]);
    query.light_distance = pk.qld[l];
    const double distance =
        shadowcts::metric::pivot_distance(frame, (*scene.elements)[n.pivot], query);
    out.inside = (out.inside & ~bit) | (distance <= n.threshold[inside] ? bit : 0);
    out.overlap =
        (out.overlap & ~bit) |
        (distance >= n.threshold[overlap_low] && distance <= n.threshold[overlap_high] ? bit : 0);
    out.far = (out.far & ~bit) | (distance >= n.threshold[far_side] ? bit : 0);
    out.near = (out.near & ~bit) | (distance <= n.threshold[near_side] ? bit : 0);
  }
  if (!needed[overlap_low]) out.overlap = 0;
  if (!needed[far_side]) out.far = 0;
  if (!needed[near_side]) out.near = 0;
  return out;
}

// Of the lanes `here` of chunk j: those whose light distance certainly reaches the node
// (returned), the deep ones among them (into out.deep, by the pivot's distance), and in `doubt`
// those whose reach or depth the float bounds leave open.
template <class D, class V>
HWY_INLINE LaneMask reaching_lanes(D d, const FastNode& n, V qlo, V qhi, LaneMask here,
                                   std::size_t j, NodeDecisions& out, LaneMask& doubt) {
  const LaneMask reached = lane_bits(d, hn::Ge(qlo, hn::Set(d, n.light_distance_high))) & here;
  const LaneMask not_reached = lane_bits(d, hn::Lt(qhi, hn::Set(d, n.light_distance_low))) & here;
  doubt = here & ~(reached | not_reached);
  if (reached != 0) {
    const LaneMask deep = lane_bits(d, hn::Ge(qlo, hn::Set(d, n.pivot_light_distance_high)));
    const LaneMask shallow = lane_bits(d, hn::Lt(qhi, hn::Set(d, n.pivot_light_distance_low)));
    doubt |= reached & ~(deep | shallow);
    out.deep |= (deep & reached) << j;
  }
  return reached;
}

// The node's decisions from the lanes read below and above each threshold, for the lanes no
// test left unsure.
inline NodeDecisions certain_decisions(const FastNode& n, NodeDecisions out, const LaneMask* below,
                                       const LaneMask* above, LaneMask unsure) {
  const LaneMask sure = ~unsure;
  out.reached &= sure;
  out.deep &= sure;
  out.inside = below[inside] & sure;
  out.overlap = n.needed >> overlap_low & 1 ? above[overlap_low] & below[overlap_high] & sure : 0;
  out.far = n.needed >> far_side & 1 ? above[far_side] & sure : 0;
  out.near = n.needed >> near_side & 1 ? below[near_side] & sure : 0;
  return out;
}

// The node tests of a point cone in float lanes (16 per AVX-512 vector). Returns the decisions of
// the lanes it is certain of and sets `unsure` to the lanes the double path must decide.
// Light distances: the float bounds below and above each double decide qld >= d wherever they
// do not overlap. Angles: with float u, a, cos T and sin T (|u|, |a| = 1 up to rounding,
// |cos T| <= 2, |sin T| <= 1), f = s cos T - c sin T is within 2^-18 of its exact value for the
// double inputs: rounding u and a to float moves each cross-product component by at most 4 u_f
// and its two products and difference add 4 u_f more (u_f = 2^-24), so |u x a| moves by at most
// sqrt(3) 8 u_f < 2^-20 (a norm is 1-Lipschitz; the squares and the root add a few u_f of it);
// u . a moves by at most 16 u_f = 2^-20; with the two products and the difference of f at most
// 2 * 2^-20 + 2^-20 + 12 u_f < 2^-18. A lane is decided only where |f| exceeds `window` (at least
// 2^-16): then the double f lies beyond the double path's own window (2^-40), on the same side,
// and the double path would decide it alike.
//
// An arc centre (arc = true) is distance_to_arc's two cases: where the arc certainly spans the
// projection w = u - (u . n) n (both (a x w) . n and (w x b) . n above 2^-16, hence |w| > 0 in
// double too) the angle is atan2(|u . n|, |w|), tested as above with s = |u . n|, c = |w|; where it
// certainly does not (either below -2^-16), the nearer endpoint: below if either endpoint is,
// above if both are. Each of those floats moves by less than 2^-18 from its double value (the
// same count of operations on unit inputs, plus the projection's), so the same windows hold; a lane
// where the span is not certain goes to the double path.
template <bool arc, std::size_t P>
NodeDecisions evaluate_in_float(const FastNode& n, const Packet<P>& pk, LaneMask lanes,
                                float window, LaneMask& unsure) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = std::min(hn::Lanes(d), max_float_lanes);
  const LaneMask chunk = (LaneMask(1) << N) - 1;
  const V lo = hn::Set(d, -window), hi = hn::Set(d, window);
  NodeDecisions out;
  LaneMask below[thresholds] = {}, above[thresholds] = {};
  unsure = 0;
  for (std::size_t j = 0; j < P; j += N) {
    const LaneMask here = (lanes >> j) & chunk;
    if (here == 0) continue;
    const V qlo = hn::Load(d, pk.qlo + j), qhi = hn::Load(d, pk.qhi + j);
    LaneMask doubt = 0;
    const LaneMask reached = reaching_lanes(d, n, qlo, qhi, here, j, out, doubt);
    if (reached != 0) {
      auto sure = hn::Eq(qlo, qlo);  // true but in NaN lanes, which `reached` leaves out
      const V ux = hn::Load(d, pk.fx + j), uy = hn::Load(d, pk.fy + j), uz = hn::Load(d, pk.fz + j);
      const V ax = hn::Set(d, n.a[0]), ay = hn::Set(d, n.a[1]), az = hn::Set(d, n.a[2]);
      // Angle between u and a as (|u x a|, u . a), in glm's order of operations (sine_cosine),
      // with the root taken only where it is read.
      const V cx = hn::Sub(hn::Mul(uy, az), hn::Mul(ay, uz));
      const V cy = hn::Sub(hn::Mul(uz, ax), hn::Mul(az, ux));
      const V cz = hn::Sub(hn::Mul(ux, ay), hn::Mul(ax, uy));
      const V s2 = hn::Add(hn::Add(hn::Mul(cx, cx), hn::Mul(cy, cy)), hn::Mul(cz, cz));
      const V c = hn::Add(hn::Add(hn::Mul(ux, ax), hn::Mul(uy, ay)), hn::Mul(uz, az));
      const auto f_of = [&](V sine, V cosine, int k) {
        return hn::Sub(hn::Mul(sine, hn::Set(d, n.cos_t[k])),
                       hn::Mul(cosine, hn::Set(d, n.sin_t[k])));
      };
      if constexpr (!arc) {
        if (n.squared) {
          // Every needed cos T >= 0: f < -W iff c sin T - W > 0 and s^2 cos^2 T < (c sin T -
          // W)^2, f > W iff c sin T + W < 0 or s^2 cos^2 T > (c sin T + W)^2. No root: it was
          // the longest latency of a walk step. The squares' roundings (a few 2^-24 relative)
          // move the comparisons by far less than the error bound above allows.
          const V zero = hn::Zero(d);
          for (int k = 0; k < thresholds; ++k) {
            if (!(n.needed >> k & 1)) continue;
            const V lhs = hn::Mul(s2, hn::Set(d, n.cos_t[k] * n.cos_t[k]));
            const V g = hn::Mul(c, hn::Set(d, n.sin_t[k]));
            const V low = hn::Add(g, lo), high = hn::Add(g, hi);
            const auto b = hn::And(hn::Gt(low, zero), hn::Lt(lhs, hn::Mul(low, low)));
            const auto a = hn::Or(hn::Lt(high, zero), hn::Gt(lhs, hn::Mul(high, high)));
            sure = hn::And(sure, hn::Or(a, b));
            (read_below(k) ? below : above)[k] |= (lane_bits(d, read_below(k) ? b : a) & reached)
                                                  << j;
          }
          doubt |= reached & ~lane_bits(d, sure);
          out.reached |= reached << j;
          unsure |= doubt << j;
          continue;
        }
        const V s = hn::Sqrt(s2);
        for (int k = 0; k < thresholds; ++k) {
          if (!(n.needed >> k & 1)) continue;
          const V f = f_of(s, c, k);
          const auto b = hn::Lt(f, lo), a = hn::Gt(f, hi);
          // Sureness stays in mask registers; one side's bits are read per threshold.
          sure = hn::And(sure, hn::Or(a, b));
          (read_below(k) ? below : above)[k] |= (lane_bits(d, read_below(k) ? b : a) & reached)
                                                << j;
        }
      } else {
        const V bx = hn::Set(d, n.b[0]), by = hn::Set(d, n.b[1]), bz = hn::Set(d, n.b[2]);
        const V nx = hn::Set(d, n.normal[0]), ny = hn::Set(d, n.normal[1]),
                nz = hn::Set(d, n.normal[2]);
        const V h = hn::Add(hn::Add(hn::Mul(ux, nx), hn::Mul(uy, ny)), hn::Mul(uz, nz));
        const V px = hn::Sub(ux, hn::Mul(h, nx)), py = hn::Sub(uy, hn::Mul(h, ny)),
                pz = hn::Sub(uz, hn::Mul(h, nz));
        const V length =
            hn::Sqrt(hn::Add(hn::Add(hn::Mul(px, px), hn::Mul(py, py)), hn::Mul(pz, pz)));
        // (a x w) . n and (w x b) . n.
        const V from_a = hn::Add(hn::Add(hn::Mul(hn::Sub(hn::Mul(ay, pz), hn::Mul(py, az)), nx),
                                         hn::Mul(hn::Sub(hn::Mul(az, px), hn::Mul(pz, ax)), ny)),
                                 hn::Mul(hn::Sub(hn::Mul(ax, py), hn::Mul(px, ay)), nz));
        const V to_b = hn::Add(hn::Add(hn::Mul(hn::Sub(hn::Mul(py, bz), hn::Mul(by, pz)), nx),
                                       hn::Mul(hn::Sub(hn::Mul(pz, bx), hn::Mul(bz, px)), ny)),
                               hn::Mul(hn::Sub(hn::Mul(px, by), hn::Mul(bx, py)), nz));
        const V span_window = hn::Set(d, 0x1p-16f);
        // A lane where neither is certain is unsure for every threshold (a and b stay false).
        const auto spans = hn::And(hn::Gt(from_a, span_window), hn::Gt(to_b, span_window));
        const auto misses =
            hn::Or(hn::Lt(from_a, hn::Neg(span_window)), hn::Lt(to_b, hn::Neg(span_window)));
        const V s = hn::Sqrt(s2);
        V sb, cb;
        sine_cosine(ux, uy, uz, bx, by, bz, sb, cb);
        const V sp = hn::Abs(h);
        for (int k = 0; k < thresholds; ++k) {
          if (!(n.needed >> k & 1)) continue;
          const V fp = f_of(sp, length, k), fa = f_of(s, c, k), fb = f_of(sb, cb, k);
          const auto b = hn::Or(hn::And(spans, hn::Lt(fp, lo)),
                                hn::And(misses, hn::Or(hn::Lt(fa, lo), hn::Lt(fb, lo))));
          const auto a = hn::Or(hn::And(spans, hn::Gt(fp, hi)),
                                hn::And(misses, hn::And(hn::Gt(fa, hi), hn::Gt(fb, hi))));
          sure = hn::And(sure, hn::Or(a, b));
          (read_below(k) ? below : above)[k] |= (lane_bits(d, read_below(k) ? b : a) & reached)
                                                << j;
        }
      }
      doubt |= reached & ~lane_bits(d, sure);
      out.reached |= reached << j;
    }
    unsure |= doubt << j;
  }
  return certain_decisions(n, out, below, above, unsure);
}

// The node tests of a directional light's disk or 2D capsule in float lanes: distance = |u - x| -
// radius, x the closest point of the centre, against each threshold, as f = |u - x| - (T +
// radius) with T + radius rounded to float (FastNode::cos_t). Every plane coordinate, radius and
// threshold is below 8 S in magnitude (nodes and scenes where that may fail stay in double), so
// each rounding moves f by at most 2^-21 S and all of them together (the coordinates, the
// closest parameter t in [0, 1], the difference, the norm) by less than 2^-18 S; `window` is at
// least 2^-16 S, beyond which the double f is beyond the double path's window on the same side.
template <bool capsule, std::size_t P>
NodeDecisions evaluate_planar_in_float(const FastNode& n, const Packet<P>& pk, LaneMask lanes,
                                       LaneMask& unsure) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = std::min(hn::Lanes(d), max_float_lanes);
  const LaneMask chunk = (LaneMask(1) << N) - 1;
  NodeDecisions out;
  LaneMask below[thresholds] = {}, above[thresholds] = {};
  unsure = 0;
  for (std::size_t j = 0; j < P; j += N) {
    const LaneMask here = (lanes >> j) & chunk;
    if (here == 0) continue;
    const V qlo = hn::Load(d, pk.qlo + j), qhi = hn::Load(d, pk.qhi + j);
    LaneMask doubt = 0;
    const LaneMask reached = reaching_lanes(d, n, qlo, qhi, here, j, out, doubt);
    if (reached != 0) {
      auto sure = hn::Eq(qlo, qlo);  // true but in NaN lanes, which `reached` leaves out
      const V ux = hn::Load(d, pk.fx + j), uy = hn::Load(d, pk.fy + j);
      const V ax = hn::Set(d, n.a[0]), ay = hn::Set(d, n.a[1]);
      V ex = hn::Sub(ux, ax), ey = hn::Sub(uy, ay);
      if constexpr (capsule) {
        if (n.segment_length_squared > 0.0f) {
          // closest_parameter, then u - (a + t (b - a)).
          const V abx = hn::Set(d, n.b[0]), aby = hn::Set(d, n.b[1]);
          V t = hn::Div(hn::Add(hn::Mul(ex, abx), hn::Mul(ey, aby)),
                        hn::Set(d, n.segment_length_squared));
          t = hn::Min(hn::Max(t, hn::Zero(d)), hn::Set(d, 1.0f));
          ex = hn::Sub(ux, hn::Add(ax, hn::Mul(t, abx)));
          ey = hn::Sub(uy, hn::Add(ay, hn::Mul(t, aby)));
        }
      }
      // |e| - (T + r) < -W iff T + r - W > 0 and |e|^2 < (T + r - W)^2; > W iff T + r + W < 0
      // or |e|^2 > (T + r + W)^2: the node's squared limits (FastNode::cos_t and sin_t) against
      // |e|^2, no root (the longest latency of a walk step) and no branch. The squares' relative
      // roundings (a few 2^-24, of values below 8 S) stay far inside the error bound above;
      // S >= 2^-30 keeps the squares of any bound that matters normal. A threshold no child
      // needs is always above (0 and -1), a NaN |e|^2 never sure.
      const V length2 = hn::Add(hn::Mul(ex, ex), hn::Mul(ey, ey));
      for (int k = 0; k < thresholds; ++k) {
        const auto b = hn::Lt(length2, hn::Set(d, n.cos_t[k]));
        const auto a = hn::Gt(length2, hn::Set(d, n.sin_t[k]));
        sure = hn::And(sure, hn::Or(a, b));
        (read_below(k) ? below : above)[k] |= (lane_bits(d, read_below(k) ? b : a) & reached) << j;
      }
      doubt |= reached & ~lane_bits(d, sure);
      out.reached |= reached << j;
    }
    unsure |= doubt << j;
  }
  return certain_decisions(n, out, below, above, unsure);
}

// The cluster's slots [begin, begin + count), count <= 64, that the reference's
// triangle_blocks_sample might not reject. A slot is left out only where the line of the ray
// certainly misses the triangle, as line_certainly_misses_triangle (caster_blocks_sample.h)
// decides it: one edge function certainly negative and one certainly positive, "certainly" by
// the rounding bound of ray_within_rounding_of_triangle_edge (edge_proximity.h),
// 2^-16 (n_q m_p + n_p m_q) + 2^-30 n_p n_q (+ 2^-140 (n_p + n_q)), with m = |x| + |y| and n = m +
// |v_z - o_z|. The float edge function E_f = q.x p.y - q.y p.x of the same float ray-space
// vertices segment_triangle.h computes (bit for bit) is within 2.1 u m_p m_q (u = 2^-24) of its
// exact value E; the filter asks |E_f| > 9/8 of the bound plus 2^-60 (the absolute terms, with
// n <= 2^60), so |E| exceeds the bound. Then (1) the watertight test's signs, exact for E, are
// mixed: it misses; (2) the exact line misses too, so the reference answers "passes" whether or
// not it goes on to its exact test (ray_near_triangle_edge's looser bound only decides whether it
// does). Non-finite values compare false and leave the slot to the reference.
std::uint64_t triangles_to_decide(const TriangleGroup* groups, std::uint32_t count,
                                  const RaySpace& ray) {
  if (ray.zero_direction) return 0;  // the reference's tests hit nothing
  const hn::ScalableTag<float> df;
  using VF = hn::Vec<decltype(df)>;
  constexpr std::size_t max_lanes = 16;
  const std::size_t N = std::min(hn::Lanes(df), max_lanes);
  const VF ox = hn::Set(df, component(ray.origin, ray.kx)),
           oy = hn::Set(df, component(ray.origin, ray.ky)),
           oz = hn::Set(df, component(ray.origin, ray.kz));
  const VF shear_x = hn::Set(df, ray.shear_x), shear_y = hn::Set(df, ray.shear_y);
  const VF lateral_scale = hn::Set(df, 1.125f * 0x1p-16f),
           product_scale = hn::Set(df, 1.125f * 0x1p-30f), absolute = hn::Set(df, 0x1p-60f),
           largest = hn::Set(df, 0x1p60f), zero = hn::Zero(df);
  std::uint64_t decide = 0;
  for (std::uint32_t j = 0; j < count; j += std::uint32_t(N)) {
    VF x[3], y[3], scaled_lateral[3], extent[3];
    // N divides 16: a vector never leaves its group.
    const TriangleGroup& group = groups[j / 16];
    const std::uint32_t lane = j % 16;
    for (int k = 0; k < 3; ++k) {
      const VF rx = hn::Sub(hn::Load(df, group.xyz[ray.kx][k] + lane), ox);
      const VF ry = hn::Sub(hn::Load(df, group.xyz[ray.ky][k] + lane), oy);
      const VF rz = hn::Sub(hn::Load(df, group.xyz[ray.kz][k] + lane), oz);
      x[k] = hn::Sub(rx, hn::Mul(shear_x, rz));
      y[k] = hn::Sub(ry, hn::Mul(shear_y, rz));
      const VF lateral = hn::Add(hn::Abs(x[k]), hn::Abs(y[k]));
      extent[k] = hn::Add(lateral, hn::Abs(rz));
      scaled_lateral[k] = hn::Mul(lateral_scale, lateral);
    }
    // Compared one by one: a NaN extent fails its comparison (Max could drop it).
    const auto in_range = hn::And(hn::Le(extent[0], largest),
                                  hn::And(hn::Le(extent[1], largest), hn::Le(extent[2], largest)));
    // Edges (b, c), (c, a), (a, b), as exact_edge_function(p, q) = q.x p.y - q.y p.x.
    const int p_of[3] = {1, 2, 0}, q_of[3] = {2, 0, 1};
    auto negative = hn::Lt(largest, zero), positive = negative;  // all false
    for (int e = 0; e < 3; ++e) {
      const int p = p_of[e], q = q_of[e];
      const VF edge = hn::Sub(hn::Mul(x[q], y[p]), hn::Mul(y[q], x[p]));
      // n_q (9/8 2^-16 m_p + 9/8 2^-30 n_p) + (n_p 9/8 2^-16 m_q + 2^-60); fused or not, its
      // rounding stays far inside the 9/8.
      const VF bound =
          hn::MulAdd(extent[q], hn::MulAdd(product_scale, extent[p], scaled_lateral[p]),
                     hn::MulAdd(extent[p], scaled_lateral[q], absolute));
      // Certainly negative or positive: beyond the bound (at least 2^-60) on either side.
      negative = hn::Or(negative, hn::Lt(edge, hn::Neg(bound)));
      positive = hn::Or(positive, hn::Gt(edge, bound));
    }
    const auto skip = hn::And(in_range, hn::And(negative, positive));
    decide |= std::uint64_t(lane_bits(df, hn::Not(skip))) << j;
  }
  return count >= 64 ? decide : decide & ((std::uint64_t(1) << count) - 1);
}

// Directional light: the lanes of `visit` whose line towards the light certainly misses every
// triangle of the cluster, so that the reference's triangle_blocks_sample answers "passes" for
// each: their point in the light's plane lies outside the cluster's plane bounds. Why that is
// certain: the bounds hold every vertex, widened by the margin M = 2^-14 S (S the case's scale;
// 2M along the diagonals, a distance of sqrt(2) M), so the exact line passes at a distance above
// M from each triangle's projection along the light. The ray space of the watertight test
// projects along the light onto an axis plane: an oblique projection, which never shortens a
// distance orthogonal to the light, so the exact ray-space origin lies above M from each exact
// ray-space triangle. Each rounded ray-space coordinate lies within 5 u n of its exact value
// (edge_proximity.h; u = 2^-24, n = |x| + |y| + |v_z - o_z| <= 10 S with sample and vertices
// within S on every axis, as `within_scale` asks), under 2^-17 S per vertex: the rounded
// vertices' triangle still leaves the origin out, so the float test misses, and the exact line
// misses, so whatever ray_near_triangle_edge says, the exact decision passes too. The lane's float
// plane coordinates and their sum and difference are within 2^-20 S of the exact ones; the bounds
// are rounded outwards; the frame's axes are orthonormal and orthogonal to the light up to a few
// 2^-53.
template <std::size_t P>
LaneMask lanes_missing_cluster(const NodeCluster& cluster, const Packet<P>& pk, LaneMask visit) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = std::min(hn::Lanes(d), max_float_lanes);
  const LaneMask chunk = (LaneMask(1) << N) - 1;
  V low[4], high[4];
  for (int k = 0; k < 4; ++k) {
    low[k] = hn::Set(d, cluster.plane_low[k]);
    high[k] = hn::Set(d, cluster.plane_high[k]);
  }
  LaneMask missing = 0;
  for (std::size_t j = 0; j < P; j += N) {
    const LaneMask here = (visit >> j) & chunk;
    if (here == 0) continue;
    const V x = hn::Load(d, pk.fx + j), y = hn::Load(d, pk.fy + j);
    const V along[4] = {x, y, hn::Add(x, y), hn::Sub(x, y)};
    auto outside = hn::Lt(along[0], low[0]);
    for (int k = 0; k < 4; ++k)
      outside = hn::Or(outside, hn::Or(hn::Lt(along[k], low[k]), hn::Gt(along[k], high[k])));
    missing |= (lane_bits(d, outside) & here) << j;
  }
  return missing & pk.within_scale;
}

// The lanes of `visit` whose receiver's supporting plane holds every triangle of the cluster, so
// that none of them meets the segment strictly on the light's side of it (the receiver half-space
// rule): the reference's triangle_blocks_sample answers "passes" for each.
template <std::size_t P>
LaneMask lanes_in_plane(const NodeCluster& cluster, const Packet<P>& pk, LaneMask visit) {
  if (cluster.plane == no_plane) return 0;
  const hn::ScalableTag<std::uint32_t> d;
  const std::size_t N = std::min(hn::Lanes(d), max_float_lanes);
  const LaneMask chunk = (LaneMask(1) << N) - 1;
  const auto plane = hn::Set(d, cluster.plane);
  LaneMask in_plane = 0;
  for (std::size_t j = 0; j < P; j += N) {
    const LaneMask here = (visit >> j) & chunk;
    if (here == 0) continue;
    in_plane |= (lane_bits(d, hn::Eq(hn::Load(d, pk.receiver_plane + j), plane)) & here) << j;
  }
  return in_plane;
}

// The lanes of `visit` whose segment meets the cluster's slabs: segment_meets_slabs on the node's
// copy of the slabs, in its operations (glm::dot's (x + y) + z, std::max and std::min as
// comparisons, so that NaNs go the same way), 8 lanes per vector of doubles.
template <std::size_t P>
LaneMask lanes_meeting_slabs(const NodeCluster& cluster, const Packet<P>& pk, LaneMask visit) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  constexpr std::size_t max_lanes = 8;
  const std::size_t N = std::min(hn::Lanes(d), max_lanes);
  const LaneMask chunk = (LaneMask(1) << N) - 1;
  const V nx = hn::Set(d, cluster.slab_normal.x), ny = hn::Set(d, cluster.slab_normal.y),
          nz = hn::Set(d, cluster.slab_normal.z);
  const V low = hn::Set(d, cluster.low), high = hn::Set(d, cluster.high);
  LaneMask meets = 0;
  for (std::size_t j = 0; j < P; j += N) {
    const LaneMask here = (visit >> j) & chunk;
    if (here == 0) continue;
    const V s_from = hn::Add(
        hn::Add(hn::Mul(nx, hn::Load(d, pk.from_x + j)), hn::Mul(ny, hn::Load(d, pk.from_y + j))),
        hn::Mul(nz, hn::Load(d, pk.from_z + j)));
    const V s_to = hn::Add(
        hn::Add(hn::Mul(nx, hn::Load(d, pk.to_x + j)), hn::Mul(ny, hn::Load(d, pk.to_y + j))),
        hn::Mul(nz, hn::Load(d, pk.to_z + j)));
    // std::max(a, b) is a < b ? b : a; std::min(a, b) is b < a ? b : a.
    const V larger = hn::IfThenElse(hn::Lt(s_from, s_to), s_to, s_from);
    const V smaller = hn::IfThenElse(hn::Lt(s_to, s_from), s_to, s_from);
    meets |= (lane_bits(d, hn::And(hn::Ge(larger, low), hn::Le(smaller, high))) & here) << j;
  }
  return meets;
}

// Step 2 for one lane: the slabs, then the pivot cluster's triangles in cluster order with the
// reference's counters and decisions.
template <std::size_t P>
bool cluster_blocks(const PacketTraversal& traversal, Packet<P>& pk, int l,
                    const NodeCluster& cluster, TraversalCounters& counters) {
  const TraversalScene& scene = *traversal.scene;
  // segment_meets_slabs, on the node's copy of the slabs (the same operations).
  const double s_from =
      glm::dot(cluster.slab_normal, glm::dvec3(pk.from_x[l], pk.from_y[l], pk.from_z[l]));
  const double s_to = glm::dot(cluster.slab_normal, glm::dvec3(pk.to_x[l], pk.to_y[l], pk.to_z[l]));
  if (!(std::max(s_from, s_to) >= cluster.low && std::min(s_from, s_to) <= cluster.high))
    return false;
  const shadowcts::metric::Clustering& clustering = *scene.clustering;
  // The slot of the receiver, which is never tested nor counted (at most one per cluster).
  const std::uint32_t receiver_at = pk.receiver_slot[l];
  const std::uint32_t end = cluster.end;
  for (std::uint32_t begin = cluster.begin; begin < end; begin += 64) {
    const std::uint32_t count = std::min<std::uint32_t>(64, end - begin);
    const std::uint64_t decide = triangles_to_decide(
        traversal.triangles->groups.data() + cluster.group + (begin - cluster.begin) / 16, count,
        pk.ray[l]);
    const std::uint32_t* slots = clustering.triangles.data() + begin;
    const std::uint32_t receiver_slot =
        receiver_at >= begin && receiver_at - begin < count ? receiver_at - begin : count;
    // Only the slots the filter could not rule out need the reference; every other slot is a
    // test that misses, counted as the reference counts it.
    for (std::uint64_t rest = decide; rest != 0; rest &= rest - 1) {
      const std::uint32_t k = std::uint32_t(std::countr_zero(rest));
      if (k == receiver_slot) continue;
      if (shadowcts::metric::triangle_blocks_sample(scene, *pk.sample[l], pk.ray[l], slots[k],
                                                    pk.half_space[l])) {
        counters.triangle_tests += k + 1 - (receiver_slot < k ? 1 : 0);
        return true;
      }
    }
    counters.triangle_tests += count - (receiver_slot < count ? 1 : 0);
  }
  ++counters.clusters_tested_without_hit;
  return false;
}

template <std::size_t P>
void traverse_packet(const PacketTraversal& traversal, const std::uint32_t* members,
                     std::uint32_t count, Packet<P>& pk, std::vector<StackEntry>& stack,
                     std::uint8_t* shadowed, TraversalCounters& counters) {
  const TraversalScene& scene = *traversal.scene;
  const LightFrame& frame = scene.frame;
  const Case& c = *scene.c;
  const PreparedScene& prepared = *traversal.prepared;
  LaneMask active = 0;
  pk.within_scale = 0;
  // A directional light's ray space is the same for every sample but its origin: made once.
  const RaySpace directional_space =
      frame.directional
          ? make_ray_space(ray_to_directional_light(glm::vec3(0.0f), c.light->direction))
          : RaySpace();
  for (std::uint32_t l = 0; l < P; ++l) {
    pk.ux[l] = pk.uy[l] = pk.uz[l] = pk.qld[l] = 0.0;
    pk.from_x[l] = pk.from_y[l] = pk.from_z[l] = pk.to_x[l] = pk.to_y[l] = pk.to_z[l] = 0.0;
    pk.fx[l] = pk.fy[l] = pk.fz[l] = pk.qlo[l] = pk.qhi[l] = 0.0f;
    pk.receiver_plane[l] = no_plane;
    if (l >= count) continue;
    const std::uint32_t i = members[l];
    // The prepared scene's compacted arrays (the same floats as the view sample's); the view
    // sample itself is read only by the reference's triangle decisions.
    pk.sample[l] = &prepared.view_samples.samples[prepared.samples.index[i]];
    pk.receiver[l] = prepared.samples.receiver[i];
    const std::vector<std::uint32_t>& slot_of = traversal.triangles->slot_of;
    pk.receiver_slot[l] = pk.receiver[l] < slot_of.size() ? slot_of[pk.receiver[l]] : ~0u;
    const std::vector<std::uint32_t>& plane_of = traversal.triangles->planes.of_triangle;
    pk.receiver_plane[l] = pk.receiver[l] < plane_of.size() ? plane_of[pk.receiver[l]] : no_plane;
    pk.sample_index[l] = prepared.samples.index[i];
    shadowed[prepared.samples.index[i]] = 0;
    const float px = prepared.samples.px[i], py = prepared.samples.py[i],
                pz = prepared.samples.pz[i];
    const glm::dvec3 p(px, py, pz);
    double ux, uy, uz, qld;
    glm::dvec3 to;
    if (frame.directional) {
      // make_light_space_query's directional case (in_plane and directional_light_distance, the
      // same glm::dot operations) inline, and the ray space's origin written as three floats:
      // around the call and through the copies of whole vectors, the sample's coordinates were
      // stored narrow and loaded wide, and each lane waited for a failed store forward.
      ux = glm::dot(p, frame.plane_x);
      uy = glm::dot(p, frame.plane_y);
      uz = 0.0;
      qld = -glm::dot(p, frame.towards_light);
      RaySpace& ray = pk.ray[l];
      ray = directional_space;
      ray.origin.x = px;
      ray.origin.y = py;
      ray.origin.z = pz;
      to = p + scene.ray_length * frame.towards_light;
    } else {
      const LightSpaceQuery query = shadowcts::metric::make_light_space_query(frame, p);
      if (query.at_light) continue;  // the segment is a point: nothing hits it
      // Constructed in place by placement new (guaranteed elision; construct_at would copy a
      // temporary, with wide loads of narrow stores).
      ::new (static_cast<void*>(&pk.ray[l])) RaySpace(
          make_ray_space(segment_to_point_light(glm::vec3(px, py, pz), c.light->position)));
      ux = query.position.x;
      uy = query.position.y;
      uz = query.position.z;
      qld = query.light_distance;
      to = frame.light_position;
    }
    pk.from_x[l] = p.x, pk.from_y[l] = p.y, pk.from_z[l] = p.z;
    pk.to_x[l] = to.x, pk.to_y[l] = to.y, pk.to_z[l] = to.z;
    pk.half_space[l].reset();
    pk.ux[l] = ux;
    pk.uy[l] = uy;
    pk.uz[l] = uz;
    pk.qld[l] = qld;
    const float scale = float(frame.scale);  // a float maximum (Case::scale)
    if (std::fabs(px) <= scale && std::fabs(py) <= scale && std::fabs(pz) <= scale)
      pk.within_scale |= LaneMask(1) << l;
    pk.fx[l] = float(ux);
    pk.fy[l] = float(uy);
    pk.fz[l] = float(uz);
    pk.qlo[l] = float_below(qld);
    pk.qhi[l] = float_above(qld);
    active |= LaneMask(1) << l;
  }
  const FilledArray<PacketNode>& nodes = traversal.nodes->nodes;
  const FilledArray<FastNode>& fast = traversal.nodes->fast;
  const FilledArray<NodeCluster>& clusters = traversal.nodes->clusters;
  if (nodes.empty() || active == 0) return;
  // The float window: at least 2^-16 (see evaluate_in_float), wider where a test widens the
  // double one, so that the lanes it hands back still reach the double path.
  const float float_window = cone_window(traversal.nodes->decision_window);
  stack.clear();
  stack.push_back({active, 0});
  while (!stack.empty()) {
    const StackEntry entry = stack.back();
    stack.pop_back();
    const std::uint32_t index = entry.node;
    const LaneMask lanes = entry.lanes & active;
    if (lanes == 0) continue;
    counters.nodes_visited += std::uint64_t(std::popcount(lanes));
    const FastNode& fn = fast[index];
    NodeDecisions decisions;
    if (fn.in_float) {
      LaneMask unsure = 0;
      switch (fn.in_float) {
        case 1:
          decisions = evaluate_in_float<false>(fn, pk, lanes, float_window, unsure);
          break;
        case 2:
          decisions = evaluate_in_float<true>(fn, pk, lanes, float_window, unsure);
          break;
        case 3:
          decisions = evaluate_planar_in_float<false>(fn, pk, lanes, unsure);
          break;
        default:
          decisions = evaluate_planar_in_float<true>(fn, pk, lanes, unsure);
          break;
      }
      if (unsure != 0) {
        const NodeDecisions exact = evaluate_node(traversal, nodes[index], pk, unsure);
        decisions.reached |= exact.reached;
        decisions.deep |= exact.deep;
        decisions.inside |= exact.inside;
        decisions.overlap |= exact.overlap;
        decisions.far |= exact.far;
        decisions.near |= exact.near;
      }
    } else {
      decisions = evaluate_node(traversal, nodes[index], pk, lanes);
    }
    const LaneMask visiting = decisions.inside & decisions.deep;
    if (visiting != 0) {
      const NodeCluster& cluster = clusters[index];
      // A directional light's lines are parallel: most lanes that visit a cluster pass beside
      // all of its triangles, which the plane bounds tell for many lanes at once. Where their
      // segments meet the slabs, their tests are counted in bulk, none is made.
      // And a sample's receiver plane holds every triangle of many a cluster it visits (a
      // tessellated floor's): none of them can shadow it (ClusterPlanes).
      const LaneMask beside =
          (frame.directional ? lanes_missing_cluster(cluster, pk, visiting) : LaneMask(0)) |
          lanes_in_plane(cluster, pk, visiting);
      const LaneMask missing = beside != 0 ? lanes_meeting_slabs(cluster, pk, beside) : 0;
      if (missing != 0) {
        const std::uint32_t size = cluster.end - cluster.begin;
        std::uint64_t receivers_inside = 0;
        for (LaneMask rest = missing; rest != 0; rest &= rest - 1)
          receivers_inside += pk.receiver_slot[std::countr_zero(rest)] - cluster.begin < size;
        const std::uint64_t lanes_missing = std::uint64_t(std::popcount(missing));
        counters.triangle_tests += lanes_missing * size - receivers_inside;
        counters.clusters_tested_without_hit += lanes_missing;
      }
      for (LaneMask visit = visiting & ~beside; visit != 0; visit &= visit - 1) {
        const int l = std::countr_zero(visit);
        if (cluster_blocks(traversal, pk, l, cluster, counters)) {
          shadowed[pk.sample_index[l]] = 1;
          active &= ~(LaneMask(1) << l);
        }
      }
    }
    const LaneMask going = decisions.reached & active;
    // Pushed overlap, far, near, so that near is walked first, as the reference walks it.
    const LaneMask overlap = decisions.overlap & going, far = decisions.far & going,
                   near = decisions.near & going;
    // The first lines of a pushed node are fetched while the walk goes on: far and overlap
    // children lie elsewhere in the near-first order.
    const auto push = [&](int child, LaneMask mask) {
      const FastNode* next = &fast[fn.child[child]];
      __builtin_prefetch(next);
      __builtin_prefetch(reinterpret_cast<const char*>(next) + 64);
      stack.push_back({mask, fn.child[child]});
    };
    if (overlap) push(int(TreeChild::overlap), overlap);
    if (far) push(int(TreeChild::far), far);
    if (near) push(int(TreeChild::near), near);
  }
}

template <std::size_t P>
void traverse_tiles_of(const PacketTraversal& traversal, std::size_t tile_begin,
                       std::size_t tile_end, std::uint8_t* shadowed, TraversalCounters& counters) {
  Packet<P> packet;
  std::vector<StackEntry> stack;
  stack.reserve(256);
  const SampleTiles& tiles = *traversal.tiles;
  for (std::size_t k = tile_begin; k < tile_end; ++k)
    traverse_packet<P>(traversal, tiles.samples.data() + tiles.begin[k],
                       tiles.begin[k + 1] - tiles.begin[k], packet, stack, shadowed, counters);
}

void TraverseTiles(const PacketTraversal& traversal, std::size_t tile_begin, std::size_t tile_end,
                   std::uint8_t* shadowed, TraversalCounters& counters) {
  if (traversal.tiles->packet <= 8)
    traverse_tiles_of<8>(traversal, tile_begin, tile_end, shadowed, counters);
  else if (traversal.tiles->packet <= 16)
    traverse_tiles_of<16>(traversal, tile_begin, tile_end, shadowed, counters);
  else
    traverse_tiles_of<64>(traversal, tile_begin, tile_end, shadowed, counters);
}

// Per cluster of the elements [element_begin, element_end): PlaneBounds of its vertices, x = v .
// plane_x and y = v . plane_y in float lanes, 16 slots of a group at once.
void ClusterPlaneBounds(const LightFrame& frame, const shadowcts::metric::Clustering& clustering,
                        const ClusterTriangles& triangles, const std::uint32_t* first_group,
                        const shadowcts::metric::LightSpaceElement* elements,
                        std::size_t element_begin, std::size_t element_end, PlaneBounds* out) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const std::size_t N = std::min(hn::Lanes(d), max_float_lanes);
  const V xx = hn::Set(d, float(frame.plane_x.x)), xy = hn::Set(d, float(frame.plane_x.y)),
          xz = hn::Set(d, float(frame.plane_x.z));
  const V yx = hn::Set(d, float(frame.plane_y.x)), yy = hn::Set(d, float(frame.plane_y.y)),
          yz = hn::Set(d, float(frame.plane_y.z));
  const V infinity = hn::Set(d, std::numeric_limits<float>::infinity());
  for (std::size_t e = element_begin; e != element_end; ++e) {
    const std::uint32_t c = elements[e].cluster;
    V low[4], high[4];
    for (int a = 0; a < 4; ++a) low[a] = infinity, high[a] = hn::Neg(infinity);
    auto numbers = hn::Eq(infinity, infinity);  // all true
    const std::uint32_t size = clustering.size(c);
    for (std::uint32_t j = 0; j < size; j += std::uint32_t(N)) {
      const TriangleGroup& group = triangles.groups[first_group[c] + j / 16];
      const std::uint32_t lane = j % 16;
      V v[3][3];  // [axis][corner]
      for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 3; ++k) v[axis][k] = hn::Load(d, group.xyz[axis][k] + lane);
      if (size - j < N) {
        // The last, partial vector: its padding lanes repeat the first lane's vertex, so that
        // Min and Max need no mask.
        const auto valid = hn::FirstN(d, size - j);
        for (int axis = 0; axis < 3; ++axis)
          for (int k = 0; k < 3; ++k)
            v[axis][k] = hn::IfThenElse(valid, v[axis][k], hn::Set(d, hn::GetLane(v[axis][k])));
      }
      for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 3; ++k) numbers = hn::And(numbers, hn::Eq(v[axis][k], v[axis][k]));
      for (int k = 0; k < 3; ++k) {
        const V x =
            hn::Add(hn::Add(hn::Mul(v[0][k], xx), hn::Mul(v[1][k], xy)), hn::Mul(v[2][k], xz));
        const V y =
            hn::Add(hn::Add(hn::Mul(v[0][k], yx), hn::Mul(v[1][k], yy)), hn::Mul(v[2][k], yz));
        const V along[4] = {x, y, hn::Add(x, y), hn::Sub(x, y)};
        for (int a = 0; a < 4; ++a) {
          low[a] = hn::Min(low[a], along[a]);
          high[a] = hn::Max(high[a], along[a]);
        }
      }
    }
    PlaneBounds& b = out[c];
    for (int a = 0; a < 4; ++a) {
      b.low[a] = hn::GetLane(hn::MinOfLanes(d, low[a]));
      b.high[a] = hn::GetLane(hn::MaxOfLanes(d, high[a]));
    }
    // No NaN coordinate: with the case's scale finite and far below float's range (asked by
    // cluster_plane_bounds), every value above is then finite and Min and Max saw them all.
    b.finite = hn::AllTrue(d, numbers);
  }
}

std::int64_t TraversalTarget() {
  return HWY_TARGET;
}

}  // namespace shadowcts::simd::metric::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::metric {

HWY_EXPORT(TraverseTiles);
HWY_EXPORT(TraversalTarget);
HWY_EXPORT(ClusterPlaneBounds);

std::int64_t traversal_target() {
  return HWY_DYNAMIC_DISPATCH(TraversalTarget)();
}

void traverse_tiles(const PacketTraversal& traversal, std::size_t tile_begin, std::size_t tile_end,
                    std::uint8_t* shadowed, shadowcts::metric::TraversalCounters& counters) {
  HWY_DYNAMIC_DISPATCH(TraverseTiles)(traversal, tile_begin, tile_end, shadowed, counters);
}

std::vector<std::uint32_t> first_groups(const shadowcts::metric::Clustering& clustering) {
  const std::size_t clusters = clustering.cluster_begin.size() - 1;
  std::vector<std::uint32_t> first(clusters + 1, 0);
  for (std::size_t k = 0; k < clusters; ++k)
    first[k + 1] = first[k] + (clustering.size(k) + 15) / 16;
  return first;
}

ClusterTriangles cluster_triangles_soa(const CasterArrays& casters,
                                       const shadowcts::metric::Clustering& clustering) {
  ClusterTriangles out;
  const std::vector<std::uint32_t> first = first_groups(clustering);
  out.groups.assign(first.back(), TriangleGroup{});  // zero padding: finite, and masked off
  const std::vector<float>* source[3] = {casters.x, casters.y, casters.z};
  const std::size_t clusters = first.size() - 1;
  for (std::size_t c = 0; c < clusters; ++c)
    for (std::uint32_t j = 0; j < clustering.size(c); ++j) {
      const std::uint32_t t = clustering.triangles[clustering.cluster_begin[c] + j];
      TriangleGroup& group = out.groups[first[c] + j / 16];
      for (int axis = 0; axis < 3; ++axis)
        for (int k = 0; k < 3; ++k) group.xyz[axis][k][j % 16] = source[axis][k][t];
    }
  const std::size_t slots = clustering.triangles.size();
  out.slot_of.assign(casters.size(), ~0u);
  for (std::size_t j = 0; j < slots; ++j) out.slot_of[clustering.triangles[j]] = std::uint32_t(j);
  out.planes = cluster_planes(casters, clustering);
  return out;
}

namespace {
// Per cluster, NodeCluster::plane_low and plane_high: the bounds of x, y, x + y and x - y of its
// vertices in the plane of a directional light, widened by cluster_miss_margin (twice that along
// the diagonals, where a distance moves x + y by up to sqrt(2) times it) and by 2^-19 S for the
// float evaluation (the axes rounded to float and three roundings, on coordinates within S: under
// 2^-20 S per value), then rounded outwards. (-inf, +inf), never outside, for a point light or a
// cluster with a value that is not finite.
// Only the clusters of the light's elements (the tree's pivots) are read: a third of the clusters
// face away from the light on a closed mesh, and reading every cluster's triangles was most of
// this function's time.
std::vector<PlaneBounds> cluster_plane_bounds(
    const shadowcts::metric::LightFrame& frame, const shadowcts::metric::Clustering& clustering,
    const ClusterTriangles& triangles,
    const std::vector<shadowcts::metric::LightSpaceElement>& elements) {
  constexpr float infinity = std::numeric_limits<float>::infinity();
  const std::size_t clusters = clustering.cluster_begin.size() - 1;
  std::vector<PlaneBounds> out(clusters);
  if (!frame.directional) {
    for (const shadowcts::metric::LightSpaceElement& e : elements) {
      PlaneBounds& b = out[e.cluster];
      for (int a = 0; a < 4; ++a) b.low[a] = -infinity, b.high[a] = infinity;
    }
    return out;
  }
  const std::vector<std::uint32_t> first = first_groups(clustering);
  const double margin = cluster_miss_margin(frame.scale), rounding = 0x1p-19 * frame.scale;
  // Every coordinate within S <= 2^100: sums of three products of them stay finite in float.
  const bool in_range = frame.scale <= 0x1p100;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, elements.size(), 1024),
      [&](const tbb::blocked_range<std::size_t>& range) {
        HWY_DYNAMIC_DISPATCH(ClusterPlaneBounds)
        (frame, clustering, triangles, first.data(), elements.data(), range.begin(), range.end(),
         out.data());
        for (std::size_t e = range.begin(); e != range.end(); ++e) {
          PlaneBounds& b = out[elements[e].cluster];
          for (int a = 0; a < 4; ++a) {
            const double widen = (a < 2 ? margin : 2.0 * margin) + rounding;
            b.low[a] = in_range && b.finite ? float_below(double(b.low[a]) - widen) : -infinity;
            b.high[a] = in_range && b.finite ? float_above(double(b.high[a]) + widen) : infinity;
          }
        }
      });
  return out;
}
}  // namespace

PacketNodes packet_nodes(const shadowcts::metric::TraversalScene& scene,
                         const ClusterTriangles& triangles, double decision_window) {
  using shadowcts::metric::CentreKind;
  using shadowcts::metric::no_node;
  using shadowcts::metric::TreeChild;
  const shadowcts::metric::LightFrame& frame = scene.frame;
  const auto& tree_nodes = scene.tree->nodes;
  // Near-first depth-first order, the order a walk pops the nodes in.
  std::vector<std::uint32_t> order, packed(tree_nodes.size(), 0);
  order.reserve(tree_nodes.size());
  if (!tree_nodes.empty()) {
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
      const std::uint32_t node = stack.back();
      stack.pop_back();
      packed[node] = std::uint32_t(order.size());
      order.push_back(node);
      for (int c : {int(TreeChild::overlap), int(TreeChild::far), int(TreeChild::near)})
        if (tree_nodes[node].child[c] != no_node) stack.push_back(tree_nodes[node].child[c]);
    }
  }
  PacketNodes out;
  out.decision_window = decision_window;
  const float planar_window = cone_window(decision_window) * float(frame.scale);
  out.nodes = FilledArray<PacketNode>(order.size());
  out.fast = FilledArray<FastNode>(order.size());
  out.clusters = FilledArray<NodeCluster>(order.size());
  FilledArray<PacketNode>& nodes = out.nodes;
  const std::vector<shadowcts::metric::LightSpaceElement>& elements = *scene.elements;
  const std::vector<shadowcts::metric::ClusterVolume>& volumes = *scene.volumes;
  const std::vector<std::uint32_t> first_group = first_groups(*scene.clustering);
  const std::vector<PlaneBounds> plane_bounds =
      cluster_plane_bounds(frame, *scene.clustering, triangles, *scene.elements);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, order.size(), 512),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          // The tree node, its pivot element and its cluster's volume lie at random places: each
          // is fetched a few nodes ahead, once the one it is found through has arrived.
          if (i + 16 < order.size()) __builtin_prefetch(&tree_nodes[order[i + 16]]);
          if (i + 8 < order.size()) __builtin_prefetch(&elements[tree_nodes[order[i + 8]].pivot]);
          if (i + 4 < order.size())
            __builtin_prefetch(&volumes[elements[tree_nodes[order[i + 4]].pivot].cluster]);
          const shadowcts::metric::MetricTreeNode& t = tree_nodes[order[i]];
          const shadowcts::metric::LightSpaceElement& e = elements[t.pivot];
          ::new (static_cast<void*>(&nodes[i])) PacketNode();
          ::new (static_cast<void*>(&out.fast[i])) FastNode();
          ::new (static_cast<void*>(&out.clusters[i])) NodeCluster();
          PacketNode& n = nodes[i];
          n.light_distance = t.light_distance;
          n.pivot_light_distance = e.light_distance;
          n.pivot = t.pivot;
          for (int c = 0; c < 3; ++c) {
            n.has_child[c] = t.child[c] != no_node;
            n.child[c] = n.has_child[c] ? packed[t.child[c]] : 0;
          }
          n.radius = e.radius;
          // The reference's comparisons: distance <= 0, >= overlap_min - slack, <=
          // overlap_max + slack, >= delta - slack, <= delta + slack.
          n.threshold[inside] = 0.0;
          n.threshold[overlap_low] = t.overlap_min - frame.slack;
          n.threshold[overlap_high] = t.overlap_max + frame.slack;
          n.threshold[far_side] = t.partition_distance - frame.slack;
          n.threshold[near_side] = t.partition_distance + frame.slack;
          const bool point = e.centre == CentreKind::point;
          if (e.covers_everything) {
            n.kind = NodeKind::covers_everything;
          } else if (frame.directional) {
            n.kind = point ? NodeKind::disk : NodeKind::capsule_2d;
          } else {
            n.kind = point ? NodeKind::point_cone : NodeKind::arc_cone;
          }
          const glm::dvec3 a = n.kind == NodeKind::arc_cone ? e.arc.a : e.a;
          n.a[0] = a.x, n.a[1] = a.y, n.a[2] = a.z;
          if (n.kind == NodeKind::arc_cone) {
            n.b[0] = e.arc.b.x, n.b[1] = e.arc.b.y, n.b[2] = e.arc.b.z;
            n.normal[0] = e.arc.normal.x, n.normal[1] = e.arc.normal.y,
            n.normal[2] = e.arc.normal.z;
          }
          if (n.kind == NodeKind::capsule_2d) {
            // b - a and dot(b - a, b - a) as closest_parameter computes them (z is 0
            // in the plane).
            const glm::dvec3 ab = e.b - e.a;
            n.b[0] = ab.x, n.b[1] = ab.y;
            n.segment_length_squared = glm::dot(ab, ab);
          }
          // Only the thresholds a child needs (a leaf has none but `inside`): cos
          // and sin are most of this loop's time.
          const bool needed[thresholds] = {true, n.has_child[int(TreeChild::overlap)] != 0,
                                           n.has_child[int(TreeChild::overlap)] != 0,
                                           n.has_child[int(TreeChild::far)] != 0,
                                           n.has_child[int(TreeChild::near)] != 0};
          if (!frame.directional && !e.covers_everything) {
            for (int k = 0; k < thresholds; ++k) {
              if (!needed[k]) continue;
              const double shifted = n.threshold[k] + e.radius;
              if (std::isnan(shifted)) {
                n.cos_t[k] = n.sin_t[k] = 0.0;  // always near: decided by the reference
              } else if (shifted < -0x1p-30) {
                n.cos_t[k] = 2.0;  // every angle is above
              } else if (shifted > std::numbers::pi + 0x1p-30) {
                n.cos_t[k] = -2.0;  // every angle is below
              } else {
                n.cos_t[k] = std::cos(shifted);
                n.sin_t[k] = std::sin(shifted);
              }
            }
          }
          FastNode& f = out.fast[i];
          f.light_distance_low = float_below(n.light_distance);
          f.light_distance_high = float_above(n.light_distance);
          f.pivot_light_distance_low = float_below(n.pivot_light_distance);
          f.pivot_light_distance_high = float_above(n.pivot_light_distance);
          f.needed = 1u << inside;
          if (n.has_child[int(TreeChild::overlap)])
            f.needed |= (1u << overlap_low) | (1u << overlap_high);
          if (n.has_child[int(TreeChild::far)]) f.needed |= 1u << far_side;
          if (n.has_child[int(TreeChild::near)]) f.needed |= 1u << near_side;
          for (int c = 0; c < 3; ++c) {
            f.child[c] = n.child[c];
            f.has_child |= std::uint8_t(n.has_child[c] << c);
          }
          f.in_float = n.kind == NodeKind::point_cone ? 1 : n.kind == NodeKind::arc_cone ? 2 : 0;
          // The squared test needs cos T >= 0 for every needed threshold (the +2 sentinel too).
          f.squared = f.in_float == 1;
          for (int k = 0; k < thresholds; ++k)
            if ((f.needed >> k & 1) && !(n.cos_t[k] >= 0.0)) f.squared = 0;
          for (int k = 0; k < 3; ++k) {
            f.a[k] = float(n.a[k]);
            f.b[k] = float(n.b[k]);
            f.normal[k] = float(n.normal[k]);
          }
          for (int k = 0; k < thresholds; ++k) {
            f.cos_t[k] = float(n.cos_t[k]);
            f.sin_t[k] = float(n.sin_t[k]);
          }
          if (n.kind == NodeKind::disk || n.kind == NodeKind::capsule_2d) {
            // The float planar test needs every value it reads below 8 S (its error bound) and
            // normal floats for S, its window and a nonzero |b - a|^2; else the double path.
            const double limit = 8.0 * frame.scale;
            bool in_float = frame.scale >= 0x1p-30 && frame.scale <= 0x1p60;
            const auto fits = [&](double x) { return std::fabs(x) <= limit; };
            in_float = in_float && fits(n.a[0]) && fits(n.a[1]) && fits(n.b[0]) && fits(n.b[1]);
            f.segment_length_squared = float(n.segment_length_squared);
            if (n.kind == NodeKind::capsule_2d && n.segment_length_squared > 0.0)
              in_float = in_float && f.segment_length_squared >= 0x1p-100f;
            for (int k = 0; k < thresholds; ++k) {
              // evaluate_planar_in_float's squared limits; 0 and -1 (always above) where no
              // child needs the threshold.
              f.cos_t[k] = 0.0f;
              f.sin_t[k] = -1.0f;
              if (!(f.needed >> k & 1)) continue;
              const double shifted = n.threshold[k] + n.radius;
              in_float = in_float && fits(shifted);
              const float low = float(shifted) - planar_window,
                          high = float(shifted) + planar_window;
              if (low > 0.0f) f.cos_t[k] = low * low;
              if (!(high < 0.0f)) f.sin_t[k] = high * high;
            }
            if (in_float) f.in_float = n.kind == NodeKind::disk ? 3 : 4;
          }
          const std::uint32_t cluster = e.cluster;
          const shadowcts::metric::ClusterVolume& volume = volumes[cluster];
          NodeCluster& record = out.clusters[i];
          record.slab_normal = volume.slab_normal;
          record.low = volume.slab_min - frame.margin;
          record.high = volume.slab_max + frame.margin;
          record.begin = scene.clustering->cluster_begin[cluster];
          record.end = scene.clustering->cluster_begin[cluster + 1];
          record.group = first_group[cluster];
          record.plane = triangles.planes.of_cluster[cluster];
          for (int k = 0; k < 4; ++k) {
            record.plane_low[k] = plane_bounds[cluster].low[k];
            record.plane_high[k] = plane_bounds[cluster].high[k];
          }
        }
      });
  return out;
}

SampleTiles sample_tiles(const RegularSamples& samples, std::uint32_t width, std::uint32_t packet) {
  SampleTiles tiles;
  tiles.packet = packet;
  const std::size_t n = samples.size();
  const std::uint32_t tile_width = tile_width_of(packet), tile_height = packet / tile_width;
  const int column_shift = std::countr_zero(tile_width);  // a power of two: no division
  const std::uint64_t w = std::max(width, 1u);
  const std::uint32_t columns = std::uint32_t((w + tile_width - 1) / tile_width);
  // The samples in pixel order (as the prepared scene gives them), else through a permutation
  // that sorts them.
  std::vector<std::uint32_t> order;
  const bool in_order = std::is_sorted(samples.index.begin(), samples.index.end());
  if (!in_order) {
    order.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return samples.index[a] < samples.index[b];
    });
  }
  const auto sample_at = [&](std::size_t k) { return in_order ? std::uint32_t(k) : order[k]; };
  const auto pixel_at = [&](std::size_t k) { return samples.index[sample_at(k)]; };
  const auto first_at = [&](std::uint64_t pixel) {  // the first sample at or after `pixel`
    std::size_t low = 0, high = n;
    while (low < high) {
      const std::size_t mid = (low + high) / 2;
      if (pixel_at(mid) < pixel)
        low = mid + 1;
      else
        high = mid;
    }
    return low;
  };
  // Bands of tile_height pixel rows hold contiguous runs of the samples in pixel order: each
  // band is sorted by tile column on its own, the bands in parallel (one counting sort of the
  // whole image was some 5 ms of serial work inside the timed query at 1080p).
  const std::uint64_t rows = n == 0 ? 0 : pixel_at(n - 1) / w + 1;
  const std::size_t bands = std::size_t((rows + tile_height - 1) / tile_height);
  std::vector<std::uint32_t> count(bands * columns, 0), used(bands + 1, 0);
  const auto for_each_in_band = [&](std::size_t b, auto&& visit) {
    for (std::uint64_t row = b * tile_height;
         row < std::min<std::uint64_t>((b + 1) * tile_height, rows); ++row)
      for (std::size_t k = first_at(row * w), end = first_at((row + 1) * w); k < end; ++k)
        visit(k, std::uint32_t((pixel_at(k) - row * w) >> column_shift));
  };
  tbb::parallel_for(std::size_t(0), bands, [&](std::size_t b) {
    std::uint32_t* band = count.data() + b * columns;
    for_each_in_band(b, [&](std::size_t, std::uint32_t column) { ++band[column]; });
    used[b + 1] =
        std::uint32_t(std::count_if(band, band + columns, [](std::uint32_t c) { return c > 0; }));
  });
  for (std::size_t b = 0; b < bands; ++b) used[b + 1] += used[b];
  tiles.samples = FilledArray<std::uint32_t>(n);
  tiles.begin.resize(used[bands] + 1);
  tbb::parallel_for(std::size_t(0), bands, [&](std::size_t b) {
    std::uint32_t* band = count.data() + b * columns;
    // Each tile's next slot, and its end into tiles.begin (the tiles of a band by column).
    std::uint32_t next = std::uint32_t(first_at(b * tile_height * w)), tile = used[b];
    for (std::uint32_t column = 0; column < columns; ++column) {
      const std::uint32_t size = band[column];
      band[column] = next;
      next += size;
      if (size > 0) tiles.begin[++tile] = next;
    }
    for_each_in_band(b, [&](std::size_t k, std::uint32_t column) {
      tiles.samples[band[column]++] = sample_at(k);
    });
  });
  return tiles;
}

}  // namespace shadowcts::simd::metric
#endif  // HWY_ONCE
