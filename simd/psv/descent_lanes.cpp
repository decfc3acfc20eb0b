// The build's descents in Highway lanes (descent_lanes.h): compiled once per target.
//
// A descent waits for memory at every node, and its plane tests branch on every vertex; several
// descents in flight hide the first, lanes the second. Each round tests the current nodes of all
// walks at once: the three vertices' plane values against the node's error bound for every point
// of the scene (PlaneSide::node_bound, operation for operation: where it decides, it gives the
// exact side), and steps each walk by its location. A walk whose node leaves a vertex within the
// bound is located with PlaneSide::triangle_location (the scalar descent's tests, exact where
// they must be).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/psv/descent_lanes.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <bit>

#include "simd/psv/descent_lanes.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::psv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Walks in flight per call: as many as one thread's outstanding cache misses profit from (the
// descents of gate_house.1M took 450 ms with 8, 410 with 16, 380 with 32), a multiple of the
// lanes (at most 8 doubles a vector), and at most the bits of the walk masks.
constexpr std::size_t walks = 32;
static_assert(walks <= 32);

template <class D, class M>
HWY_INLINE unsigned lane_bits(D d, M mask) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, mask, bytes);
  return bytes[0];
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
  unsigned live = 0;
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
    if (start(w)) live |= 1u << w;

  while (live != 0) {
    for (unsigned bits = live; bits != 0; bits &= bits - 1) {
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
    unsigned positive = 0, negative = 0, decided = 0;
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
        all_decided = hn::And(all_decided, hn::Or(p, q));
      }
      positive |= lane_bits(d, any_positive) << j;
      negative |= lane_bits(d, any_negative) << j;
      decided |= lane_bits(d, all_decided) << j;
    }
    for (unsigned bits = live; bits != 0; bits &= bits - 1) {
      const auto w = std::size_t(std::countr_zero(bits));
      const unsigned lane = 1u << w;
      int location;
      if ((positive & negative & lane) != 0) {
        location = 0;
      } else if ((decided & lane) != 0) {
        location = (positive & lane) != 0 ? 1 : -1;
      } else {
        const glm::dvec3 t[3] = {
            {x[0][w], y[0][w], z[0][w]}, {x[1][w], y[1][w], z[1][w]}, {x[2][w], y[2][w], z[2][w]}};
        location = planes.triangle_location(tree, node[w], corners[ref::volume_of(node[w])], t);
      }
      node[w] = ref::step_by_location(tree, node[w], location, state[w]);
      if (node[w] != ref::no_node) {
        __builtin_prefetch(&tree.nodes[node[w]]);
        __builtin_prefetch(&corners[ref::volume_of(node[w])]);
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
