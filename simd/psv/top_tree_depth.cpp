// The light depths of new volumes in Highway lanes (top_tree_depth.h): compiled once per target.
//
// ref::triangle_light_depth of a point light, eight triangles a vector: every IEEE operation
// rounds once in a lane as in a scalar, and each one is the reference's, in its order (glm's
// cross and dot products, std::min, std::max and std::clamp as selects with the same comparisons),
// so every depth is the reference's to the bit. A directional light's depth is a few operations:
// the reference computes it.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/psv/top_tree_depth.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <cmath>

#include "reference/psv/top_tree_depth.h"
#include "simd/psv/top_tree_depth.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::psv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::CappedTag<double, 8>;  // at most eight triangles a vector
using V = hn::Vec<D>;

struct Vec3 {
  V x, y, z;
};

Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}
// glm::cross, operand for operand.
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {hn::Sub(hn::Mul(a.y, b.z), hn::Mul(b.y, a.z)),
          hn::Sub(hn::Mul(a.z, b.x), hn::Mul(b.z, a.x)),
          hn::Sub(hn::Mul(a.x, b.y), hn::Mul(b.x, a.y))};
}
// glm::dot: (x + y) + z of the products.
V dot(const Vec3& a, const Vec3& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}
V norm1(const Vec3& a) {
  return hn::Add(hn::Add(hn::Abs(a.x), hn::Abs(a.y)), hn::Abs(a.z));
}
// std::min(a, b) and std::max(a, b): b only where the comparison holds.
V min_of(V a, V b) {
  return hn::IfThenElse(hn::Lt(b, a), b, a);
}
V max_of(V a, V b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}
// std::max({|x|, |y|, |z|}).
V max_abs(const Vec3& a) {
  return max_of(max_of(hn::Abs(a.x), hn::Abs(a.y)), hn::Abs(a.z));
}

// The reference's segment_distance: from q to the segment [a, a + e].
V segment_distance(const D d, const Vec3& q, const Vec3& a, const Vec3& e) {
  const V length2 = dot(e, e);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const V along = hn::Div(dot(q - a, e), length2);
  // std::clamp(along, 0, 1): (v < lo) ? lo : (hi < v) ? hi : v.
  const V clamped =
      hn::IfThenElse(hn::Lt(along, zero), zero, hn::IfThenElse(hn::Lt(one, along), one, along));
  const V t = hn::IfThenElse(hn::Gt(length2, zero), clamped, zero);
  const Vec3 foot{hn::Add(a.x, hn::Mul(t, e.x)), hn::Add(a.y, hn::Mul(t, e.y)),
                  hn::Add(a.z, hn::Mul(t, e.z))};
  const Vec3 to_foot = q - foot;
  return hn::Sqrt(dot(to_foot, to_foot));
}

// The reference's point_light_triangle_distance_lower_bound, then max(0, .), for the lanes'
// triangles.
V point_light_depth(const D d, const Vec3& light, const Vec3 (&v)[3]) {
  V m = max_abs(light);
  for (int i = 0; i < 3; ++i) m = max_of(m, max_abs(v[i]));
  const V normal_error = hn::Mul(hn::Mul(hn::Set(d, 0x1p-44), m), m);
  const Vec3 normal = cross(v[1] - v[0], v[2] - v[0]);
  const V normal_length = hn::Sqrt(dot(normal, normal));
  auto surely_outside = hn::FirstN(d, 0);
  for (int k = 0; k < 3; ++k) {
    const Vec3 edge = v[(k + 1) % 3] - v[k];
    const Vec3 to_light = light - v[k];
    const V inside = dot(cross(edge, to_light), normal);
    const V error = hn::Mul(hn::Mul(norm1(edge), norm1(to_light)),
                            hn::Add(hn::Mul(norm1(normal), hn::Set(d, 0x1p-44)), normal_error));
    surely_outside = hn::Or(surely_outside, hn::Lt(inside, hn::Neg(error)));
  }
  V edge_distance = hn::Set(d, INFINITY);
  for (int k = 0; k < 3; ++k)
    edge_distance = min_of(edge_distance, segment_distance(d, light, v[k], v[(k + 1) % 3] - v[k]));
  const V distance_error = hn::Mul(hn::Set(d, 0x1p-40), m);
  const V zero = hn::Zero(d);
  const Vec3 to_light = light - v[0];
  const V numerator = hn::Sub(
      hn::Abs(dot(normal, to_light)),
      hn::Mul(norm1(to_light), hn::Add(normal_error, hn::Mul(hn::Set(d, 0x1p-44), norm1(normal)))));
  const V denominator = hn::Add(hn::Add(normal_length, hn::Mul(hn::Set(d, 2.0), normal_error)),
                                hn::Mul(hn::Set(d, 0x1p-44), normal_length));
  const V plane_distance = hn::Div(max_of(zero, numerator), denominator);
  const V inside_bound = hn::Sub(min_of(plane_distance, edge_distance), distance_error);
  const V outside_bound = hn::Sub(edge_distance, distance_error);
  const V flat = hn::IfThenElse(hn::Gt(normal_length, zero), inside_bound, zero);
  return max_of(zero, hn::IfThenElse(surely_outside, outside_bound, flat));
}

void TriangleLightDepths(const HardShadowLight& light, const std::vector<Triangle>& scene,
                         const std::uint32_t* triangles, const ref::Descent* descents,
                         std::size_t first, std::size_t last, ref::BatchVolume* volumes) {
  if (light.directional) {
    for (std::size_t i = first; i != last; ++i)
      if (!descents[i].dropped)
        volumes[i].depth = ref::triangle_light_depth(light, scene[triangles[i]]);
    return;
  }
  const D d;
  const hn::Rebind<float, D> f;
  const std::size_t lanes = hn::Lanes(d);
  constexpr std::size_t most = 8;
  HWY_ALIGN double coordinate[3][3][most];  // [vertex][axis][lane]
  HWY_ALIGN float depth[most];
  std::size_t item[most];
  const Vec3 at_light{hn::Set(d, light.position.x), hn::Set(d, light.position.y),
                      hn::Set(d, light.position.z)};
  std::size_t next = first;
  while (true) {
    std::size_t count = 0;
    for (; next != last && count < lanes; ++next) {
      if (descents[next].dropped) continue;
      const Triangle& t = scene[triangles[next]];
      const glm::vec3* vertex[3] = {&t.v0, &t.v1, &t.v2};
      for (int k = 0; k < 3; ++k)
        for (int axis = 0; axis < 3; ++axis)
          coordinate[k][axis][count] = double((*vertex[k])[axis]);
      item[count++] = next;
    }
    if (count == 0) return;
    // Lanes past the last triangle repeat the first: computed and unused.
    for (std::size_t lane = count; lane < lanes; ++lane)
      for (int k = 0; k < 3; ++k)
        for (int axis = 0; axis < 3; ++axis) coordinate[k][axis][lane] = coordinate[k][axis][0];
    Vec3 v[3];
    for (int k = 0; k < 3; ++k)
      v[k] = {hn::Load(d, coordinate[k][0]), hn::Load(d, coordinate[k][1]),
              hn::Load(d, coordinate[k][2])};
    const V bound = point_light_depth(d, at_light, v);
    // round_down_to_float: the nearest float, one step down where it lies above (bound >= 0).
    const auto nearest = hn::DemoteTo(f, bound);
    const hn::RebindToSigned<decltype(f)> fi;
    const auto lowered = hn::BitCast(f, hn::Sub(hn::BitCast(fi, nearest), hn::Set(fi, 1)));
    const V nearest_value = hn::PromoteTo(d, nearest);
    const V rounded =
        hn::IfThenElse(hn::Gt(nearest_value, bound), hn::PromoteTo(d, lowered), nearest_value);
    hn::Store(hn::DemoteTo(f, rounded), f, depth);  // a float: exact
    for (std::size_t lane = 0; lane < count; ++lane) volumes[item[lane]].depth = depth[lane];
  }
}

}  // namespace shadowcts::simd::psv::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::psv {

HWY_EXPORT(TriangleLightDepths);

void triangle_light_depths(const HardShadowLight& light, const std::vector<Triangle>& scene,
                           const std::uint32_t* triangles, const ref::Descent* descents,
                           std::size_t first, std::size_t last, ref::BatchVolume* volumes) {
  HWY_DYNAMIC_DISPATCH(TriangleLightDepths)
  (light, scene, triangles, descents, first, last, volumes);
}

}  // namespace shadowcts::simd::psv
#endif  // HWY_ONCE
