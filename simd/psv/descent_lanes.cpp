// The build's descents in Highway lanes (descent_lanes.h): compiled once per target.
//
// A descent waits for memory at every node, and its plane tests branch on every vertex; several
// descents in flight hide the first, lanes the second. Each round tests the current nodes of all
// walks at once: the three vertices' plane values against the node's error bound for every point
// of the scene (PlaneSide::node_bound, operation for operation: where it decides, it gives the
// exact side), and steps each walk by its location. A walk whose node leaves a vertex within the
// bound fetches the corners of the node's volume and waits a round; then its open vertices are
// tested in lanes against the plane's defining points (on gate_house.1M they decide 9 in 10 of
// those walks: shared vertices and vertices on an edge's line), and the rest is located with
// PlaneSide::triangle_location (the scalar descent's tests, exact where they must be).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/psv/descent_lanes.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <bit>

#include "shadowcts/geometry/volume_location.h"
#include "simd/lane_bits-inl.h"
#include "simd/psv/descent_lanes.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::psv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using shadowcts::simd::HWY_NAMESPACE::lane_bits;

// Walks in flight per call: as many as one thread's outstanding cache misses profit from (at
// gate_house.1M the descents took 450 ms with 8 walks, 410 with 16, 380 with 32; later the whole
// build 410 ms with 32 and 359 with 64), a multiple of the lanes (at most 8 doubles a vector), and
// at most the bits of a walk mask.
constexpr std::size_t walks = 64;
using WalkBits = std::uint64_t;  // bit w: walk w
static_assert(walks <= 64);

// b - a, and whether that difference is exact (geometry::two_sum's error is zero).
template <class D, class V>
HWY_INLINE V exact_difference(D d, V b, V a, decltype(hn::FirstN(d, 0))& exact) {
  const V minus_a = hn::Neg(a);
  const V s = hn::Add(b, minus_a);
  const V b_part = hn::Sub(s, b);
  const V a_part = hn::Sub(s, b_part);
  const V error = hn::Add(hn::Sub(b, a_part), hn::Sub(minus_a, b_part));
  exact = hn::And(exact, hn::Eq(error, hn::Zero(d)));
  return s;
}

// The open vertices of the walks on_their_planes tests, one per lane: the vertex, its node's
// plane's defining points, and its walk.
struct OpenVertices {
  static constexpr std::size_t capacity = 3 * walks + 8;  // and the padding of a last vector
  HWY_ALIGN double vertex[3][capacity];                   // [axis][item]
  HWY_ALIGN double point[3][3][capacity];                 // [defining point][axis][item]
  std::uint8_t walk_of[capacity];
};

// Of the walks in `check`, those whose open vertices (open[k], bit w: vertex k of walk w) all lie
// exactly on their node's plane, found from the plane's defining points alone: a vertex is one of
// them, or lies on the line through the first two (PlaneSide::near_side's surely_on_line, with
// fused multiply-subtracts for its exact products; targets without them leave that part to the
// scalar tests). An edge plane holds its edge, a capping plane its triangle.
template <class D>
HWY_NOINLINE WalkBits on_their_planes(D d, const VolumeCornerArray& corners,
                                      const std::uint32_t (&node)[walks],
                                      const double (&x)[3][walks], const double (&y)[3][walks],
                                      const double (&z)[3][walks], const WalkBits (&open)[3],
                                      WalkBits check, OpenVertices& items) {
  using V = hn::Vec<D>;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t count = 0;
  for (WalkBits bits = check; bits != 0; bits &= bits - 1) {
    const auto w = std::size_t(std::countr_zero(bits));
    const VolumeCorners& corner = corners[ref::volume_of(node[w])];
    const std::uint32_t k = node[w] % ref::nodes_per_volume;
    const bool capping = k == ref::capping_plane;
    // An edge plane's two vertices (the first twice), or the triangle's three.
    const glm::vec3* defining[3] = {&corner[capping ? 0 : k], &corner[capping ? 1 : (k + 1) % 3],
                                    &corner[capping ? 2 : k]};
    for (int v = 0; v < 3; ++v) {
      if (((open[v] >> w) & 1u) == 0) continue;
      items.vertex[0][count] = x[v][w];
      items.vertex[1][count] = y[v][w];
      items.vertex[2][count] = z[v][w];
      for (int i = 0; i < 3; ++i)
        for (int axis = 0; axis < 3; ++axis)
          items.point[i][axis][count] = double((*defining[i])[axis]);
      items.walk_of[count++] = std::uint8_t(w);
    }
  }
  // The last vector's lanes past the items: computed and ignored.
  for (std::size_t i = count; i % lanes != 0; ++i)
    for (int axis = 0; axis < 3; ++axis) {
      items.vertex[axis][i] = 0.0;
      for (int point = 0; point < 3; ++point) items.point[point][axis][i] = 0.0;
    }
  WalkBits off_their_planes = 0;  // walks with an open vertex not found on the plane
  for (std::size_t j = 0; j < count; j += lanes) {
    const auto valid = hn::FirstN(d, count - j);
    V p[3], point[3][3];
    for (int axis = 0; axis < 3; ++axis) {
      p[axis] = hn::Load(d, items.vertex[axis] + j);
      for (int i = 0; i < 3; ++i) point[i][axis] = hn::Load(d, items.point[i][axis] + j);
    }
    auto on = hn::FirstN(d, 0);
    for (int i = 0; i < 3; ++i)
      on = hn::Or(on, hn::And(hn::And(hn::Eq(p[0], point[i][0]), hn::Eq(p[1], point[i][1])),
                              hn::Eq(p[2], point[i][2])));
#if HWY_NATIVE_FMA
    if (!hn::AllTrue(d, hn::Or(on, hn::Not(valid)))) {
      // (second - first) x (p - first) = 0: each pair of products equal, compared as exact
      // (product, error) pairs, none of them near underflow; every difference exact.
      auto on_line = hn::FirstN(d, lanes);
      V edge[3], w[3];
      for (int axis = 0; axis < 3; ++axis) {
        edge[axis] = exact_difference(d, point[1][axis], point[0][axis], on_line);
        w[axis] = exact_difference(d, p[axis], point[0][axis], on_line);
      }
      const auto representable = [&](V v) {
        return hn::Or(hn::Eq(v, hn::Zero(d)), hn::Ge(hn::Abs(v), hn::Set(d, 0x1p-900)));
      };
      for (int axis = 0; axis < 3; ++axis) {
        const int next = (axis + 1) % 3;
        const V first = hn::Mul(edge[axis], w[next]), second = hn::Mul(edge[next], w[axis]);
        const V first_error = hn::MulSub(edge[axis], w[next], first);
        const V second_error = hn::MulSub(edge[next], w[axis], second);
        on_line = hn::And(on_line, hn::And(representable(first), representable(second)));
        on_line =
            hn::And(on_line, hn::And(hn::Eq(first, second), hn::Eq(first_error, second_error)));
      }
      on = hn::Or(on, on_line);
    }
#endif
    for (WalkBits off = lane_bits(d, hn::AndNot(on, valid)); off != 0; off &= off - 1)
      off_their_planes |= WalkBits(1) << items.walk_of[j + std::size_t(std::countr_zero(off))];
  }
  return check & ~off_their_planes;
}

void DescendInLanes(const ref::TopTree& tree, const VolumeCornerArray& corners,
                    const PlaneSide& planes, const std::vector<Triangle>& scene,
                    const std::uint32_t* triangles, std::size_t first, std::size_t last,
                    ref::Descent* out) {
  if (tree.root == ref::no_node) {
    std::fill(out + first, out + last, ref::Descent());
    return;
  }
  const hn::CappedTag<double, walks> d;
  const std::size_t lanes = hn::Lanes(d);
  const geometry::PlaneFilter& filter = planes.exact().filter();
  const double m = filter.scene_bound;

  // plane_error_bound at (M, M, M): the terms that do not depend on the plane.
  const double subnormal_error = 0x1p-149 * (((m + m) + m) + 1.0);

  HWY_ALIGN double x[3][walks] = {}, y[3][walks] = {}, z[3][walks] = {};
  HWY_ALIGN double a[walks] = {}, b[walks] = {}, c[walks] = {}, offset[walks] = {};
  HWY_ALIGN double extra_error[walks] = {};
  std::uint32_t node[walks];
  std::size_t item[walks];
  ref::Descent state[walks];
  WalkBits live = 0;
  // Walks whose node left a vertex within the bound: its volume's corners were fetched last round.
  WalkBits deferred = 0;
  OpenVertices open_vertices;
  std::size_t next = first;
  const auto start = [&](std::size_t w) {
    if (next == last) return false;
    // The triangles lie in the scene's order, not the batch's: fetch ahead.
    if (next + walks < last) __builtin_prefetch(&scene[triangles[next + walks]]);
    item[w] = next;
    const Triangle& t = scene[triangles[next++]];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& v = k == 0 ? t.v0 : (k == 1 ? t.v1 : t.v2);
      x[k][w] = double(v.x);
      y[k][w] = double(v.y);
      z[k][w] = double(v.z);
    }
    state[w] = ref::Descent();
    node[w] = tree.root;
    return true;
  };
  for (std::size_t w = 0; w < walks; ++w)
    if (start(w)) live |= WalkBits(1) << w;

  while (live != 0) {
    for (WalkBits bits = live; bits != 0; bits &= bits - 1) {
      const auto w = std::size_t(std::countr_zero(bits));
      const ref::TopNode& n = tree.nodes[node[w]];
      a[w] = double(n.plane[0]);
      b[w] = double(n.plane[1]);
      c[w] = double(n.plane[2]);
      offset[w] = double(n.plane[3]);
      extra_error[w] =
          ref::is_capping_node(node[w]) ? filter.capping_extra_error : filter.edge_extra_error;
    }
    // Per walk: some vertex strictly positive, some strictly negative, every vertex decided.
    WalkBits positive = 0, negative = 0, decided = 0, open[3] = {0, 0, 0};
    for (std::size_t j = 0; j < walks; j += lanes) {
      const auto va = hn::Load(d, a + j), vb = hn::Load(d, b + j), vc = hn::Load(d, c + j),
                 vd = hn::Load(d, offset + j);
      const auto vm = hn::Set(d, m);
      const auto aa = hn::Abs(va), ab = hn::Abs(vb), ac = hn::Abs(vc);
      // geometry::plane_error_bound with p = (M, M, M), operation for operation: one bound for
      // every point of the scene.
      const auto magnitude = hn::Add(
          hn::Add(hn::Add(hn::Add(hn::Mul(aa, vm), hn::Mul(ab, vm)), hn::Mul(ac, vm)), hn::Abs(vd)),
          hn::Mul(hn::Add(hn::Add(aa, ab), ac), vm));
      const auto bound =
          hn::Add(hn::Add(hn::Mul(hn::Set(d, 0x1p-22), magnitude), hn::Set(d, subnormal_error)),
                  hn::Load(d, extra_error + j));
      const auto below = hn::Neg(bound);
      auto any_positive = hn::FirstN(d, 0), any_negative = any_positive;
      auto all_decided = hn::FirstN(d, lanes);
      for (int k = 0; k < 3; ++k) {
        // geometry::plane_value.
        const auto value = hn::Add(
            hn::Add(hn::Add(hn::Mul(va, hn::Load(d, x[k] + j)), hn::Mul(vb, hn::Load(d, y[k] + j))),
                    hn::Mul(vc, hn::Load(d, z[k] + j))),
            vd);
        const auto p = hn::Gt(value, bound), q = hn::Lt(value, below);
        any_positive = hn::Or(any_positive, p);
        any_negative = hn::Or(any_negative, q);
        const auto vertex_decided = hn::Or(p, q);
        all_decided = hn::And(all_decided, vertex_decided);
        open[k] |= lane_bits(d, hn::Not(vertex_decided)) << j;
      }
      positive |= lane_bits(d, any_positive) << j;
      negative |= lane_bits(d, any_negative) << j;
      decided |= lane_bits(d, all_decided) << j;
    }
    // The walks whose corners arrived and that are still open: their open vertices against the
    // plane's defining points.
    // Those found on their planes have a vertex exactly on the plane (ref::triangle_location).
    WalkBits touching = 0;
    if (const WalkBits check = deferred & ~(positive & negative) & ~decided; check != 0) {
      touching = on_their_planes(d, corners, node, x, y, z, open, check, open_vertices);
      decided |= touching;
    }
    for (WalkBits bits = live; bits != 0; bits &= bits - 1) {
      const auto w = std::size_t(std::countr_zero(bits));
      const WalkBits lane = WalkBits(1) << w;
      const bool had_corners = (deferred & lane) != 0;
      deferred &= ~lane;
      int location;
      if ((positive & negative & lane) != 0) {
        location = 0;
      } else if ((decided & lane) != 0) {
        location = geometry::volume_location((positive & lane) != 0, (negative & lane) != 0,
                                             (touching & lane) != 0, ref::is_capping_node(node[w]));
      } else if (!had_corners) {
        // A vertex within the bound: the plane's defining points decide most (a neighbour's
        // shared vertex). Only these walks read them: fetched now, tested next round.
        deferred |= lane;
        // 36 bytes: often across two cache lines.
        const VolumeCorners& corner = corners[ref::volume_of(node[w])];
        __builtin_prefetch(&corner);
        __builtin_prefetch(reinterpret_cast<const char*>(&corner) + sizeof(VolumeCorners) - 1);
        __builtin_prefetch(&tree.sources[ref::volume_of(node[w])]);  // for an exact test
        continue;
      } else {
        const glm::dvec3 t[3] = {
            {x[0][w], y[0][w], z[0][w]}, {x[1][w], y[1][w], z[1][w]}, {x[2][w], y[2][w], z[2][w]}};
        location = planes.triangle_location(tree, node[w], corners[ref::volume_of(node[w])], t);
      }
      node[w] = ref::step_by_location(tree, node[w], location, state[w]);
      if (node[w] != ref::no_node) {
        __builtin_prefetch(&tree.nodes[node[w]]);
        continue;
      }
      out[item[w]] = state[w];
      if (!start(w)) live &= ~lane;
    }
  }
}

}  // namespace shadowcts::simd::psv::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::psv {

HWY_EXPORT(DescendInLanes);

void descend_in_lanes(const ref::TopTree& tree, const VolumeCornerArray& corners,
                      const PlaneSide& planes, const std::vector<Triangle>& scene,
                      const std::uint32_t* triangles, std::size_t first, std::size_t last,
                      ref::Descent* out) {
  HWY_DYNAMIC_DISPATCH(DescendInLanes)
  (tree, corners, planes, scene, triangles, first, last, out);
}

}  // namespace shadowcts::simd::psv
#endif  // HWY_ONCE
