// The triangle setup of the simd ptsv. The arithmetic of ref::set_up_shadow_volume (square roots
// and divisions in a dependent chain, most of its time) runs in Highway lanes, one triangle per
// lane, with the reference's operations in the reference's order (no FMA: -ffp-contract=off), so
// every plane is the reference's bit for bit; the per-triangle decisions before it (mesh, zero
// area, the exact winding, the canonical order) stay scalar.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "simd/ptsv/triangle_setup.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include "reference/closed_mesh_culling.h"
#include "shadowcts/errors.h"
#include "shadowcts/float_rounding.h"
#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/huge_pages.h"

#include "simd/ptsv/triangle_setup.h"

HWY_BEFORE_NAMESPACE();
namespace shadowcts::simd::ptsv::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

struct V3 {
  V x, y, z;
};

HWY_INLINE V3 sub(const V3& a, const V3& b) {
  return {hn::Sub(a.x, b.x), hn::Sub(a.y, b.y), hn::Sub(a.z, b.z)};
}
HWY_INLINE V3 scale(const V& s, const V3& a) {
  return {hn::Mul(s, a.x), hn::Mul(s, a.y), hn::Mul(s, a.z)};
}
// glm::dot: (x + y) + z of the products.
HWY_INLINE V dot(const V3& a, const V3& b) {
  return hn::Add(hn::Add(hn::Mul(a.x, b.x), hn::Mul(a.y, b.y)), hn::Mul(a.z, b.z));
}
// glm::cross, term for term.
HWY_INLINE V3 cross(const V3& a, const V3& b) {
  return {hn::Sub(hn::Mul(a.y, b.z), hn::Mul(b.y, a.z)),
          hn::Sub(hn::Mul(a.z, b.x), hn::Mul(b.z, a.x)),
          hn::Sub(hn::Mul(a.x, b.y), hn::Mul(b.x, a.y))};
}
// Plane::at with the plane's anchor a and shift.
HWY_INLINE V plane_at(const V3& n, const V3& a, const V& shift, const V3& x) {
  return hn::Add(hn::Add(hn::Add(hn::Mul(n.x, hn::Sub(x.x, a.x)), hn::Mul(n.y, hn::Sub(x.y, a.y))),
                         hn::Mul(n.z, hn::Sub(x.z, a.z))),
                 shift);
}

HWY_INLINE V3 load3(D d, const double (*axis)[SetupBatch::capacity], std::size_t at) {
  return {hn::Load(d, axis[0] + at), hn::Load(d, axis[1] + at), hn::Load(d, axis[2] + at)};
}
HWY_INLINE void store3(D d, const V3& v, double (*axis)[SetupBatch::capacity], std::size_t at) {
  hn::Store(v.x, d, axis[0] + at);
  hn::Store(v.y, d, axis[1] + at);
  hn::Store(v.z, d, axis[2] + at);
}
HWY_INLINE void store_mask(D d, const M& m, std::uint8_t* out) {
  alignas(64) double tmp[SetupBatch::capacity];
  hn::Store(hn::IfThenElseZero(m, hn::Set(d, 1.0)), d, tmp);
  for (std::size_t i = 0; i < hn::Lanes(d); ++i) out[i] = tmp[i] != 0.0;
}

// The planes of batch.size triangles (ref::set_up_shadow_volume after its checks): lanes past the
// size repeat the first triangle and are ignored.
void SetUpBatch(SetupBatch& b) {
  const D d;
  const std::size_t lanes = hn::Lanes(d);
  const std::size_t padded = (b.size + lanes - 1) / lanes * lanes;
  for (std::size_t i = b.size; i < padded; ++i) {
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) b.vertex[k][a][i] = b.vertex[k][a][0];
    b.orientation[i] = b.orientation[0];
  }
  const bool directional = b.directional;
  const V3 light = {hn::Set(d, b.light[0]), hn::Set(d, b.light[1]), hn::Set(d, b.light[2])};
  const V zero = hn::Zero(d);
  static constexpr int edge_first[3] = {0, 1, 0}, edge_second[3] = {1, 2, 2};
  static constexpr double edge_parity[3] = {1.0, 1.0, -1.0};
  for (std::size_t at = 0; at < padded; at += lanes) {
    const V3 p[3] = {load3(d, b.vertex[0], at), load3(d, b.vertex[1], at),
                     load3(d, b.vertex[2], at)};
    const V orientation = hn::Load(d, b.orientation + at);
    // LightGeometry::towards_light: L - a, or d.
    const auto towards = [&](const V3& a) { return directional ? light : sub(light, a); };
    // make_plane's length test: positive and finite.
    const auto usable_length = [&](const V& length) {
      return hn::And(hn::Gt(length, zero), hn::IsFinite(length));
    };
    M usable = hn::Not(hn::FirstN(d, 0));
    V3 normal[4];
    for (int e = 0; e < 3; ++e) {
      const V3& a = p[edge_first[e]];
      const V3 ba = sub(p[edge_second[e]], a);
      const V3 to_light = towards(a);
      const V3 n = cross(ba, to_light);
      const V length = hn::Sqrt(dot(n, n));
      usable = hn::And(usable, usable_length(length));
      // outside = -opposite_side = parity * orientation, exactly +-1.
      const V outside = hn::Mul(hn::Set(d, edge_parity[e]), orientation);
      normal[e] = scale(hn::Div(outside, length), n);
      store3(d, normal[e], b.normal[e], at);
      hn::Store(hn::Div(hn::Mul(hn::Sqrt(dot(ba, ba)), hn::Sqrt(dot(to_light, to_light))), length),
                d, b.condition[e] + at);
    }
    {
      const V3 u = sub(p[1], p[0]), v = sub(p[2], p[0]);
      const V3 n = cross(u, v);
      const V length = hn::Sqrt(dot(n, n));
      usable = hn::And(usable, usable_length(length));
      normal[3] = scale(hn::Div(orientation, length), n);
      store3(d, normal[3], b.normal[3], at);
      hn::Store(hn::Div(hn::Mul(hn::Sqrt(dot(u, u)), hn::Sqrt(dot(v, v))), length), d,
                b.condition[3] + at);
    }
    store_mask(d, usable, b.usable + at);
    if (!b.extra_planes) continue;

    // The edge rays and how far along them a sample can lie.
    V3 rays[3];
    V t_max;
    if (directional) {
      for (auto& r : rays) r = {hn::Neg(light.x), hn::Neg(light.y), hn::Neg(light.z)};
      t_max = hn::Set(d, b.directional_t_max);
    } else {
      for (int k = 0; k < 3; ++k) rays[k] = sub(p[k], light);
      const V height = plane_at(normal[3], p[0], zero, light);
      t_max = hn::IfThenElse(hn::Gt(height, zero), hn::Div(hn::Set(d, b.diameter), height),
                             hn::Set(d, HUGE_VAL));
    }
    static constexpr int vertex_edges[3][2] = {{0, 2}, {0, 1}, {1, 2}};
    for (int k = 0; k < 3; ++k) {
      const V3 towards_k = towards(p[k]);
      const V3 to_light =
          scale(hn::Div(hn::Set(d, 1.0), hn::Sqrt(dot(towards_k, towards_k))), towards_k);
      M keep = hn::Not(hn::Lt(hn::Abs(dot(normal[3], to_light)), hn::Set(d, 1e-3)));
      const V3& n0 = normal[vertex_edges[k][0]];
      const V3& n1 = normal[vertex_edges[k][1]];
      V3 half = {hn::Add(n0.x, n1.x), hn::Add(n0.y, n1.y), hn::Add(n0.z, n1.z)};
      const V along = dot(half, to_light);
      half = sub(half, scale(along, to_light));
      const V length = hn::Sqrt(dot(half, half));
      keep = hn::And(keep, hn::Gt(length, hn::Set(d, 1e-2)));
      keep = hn::And(keep, usable_length(length));
      const V3 n = scale(hn::Div(hn::Set(d, 1.0), length), half);
      // contain_volume: the highest value at a vertex plus the steepest rise along a ray.
      V highest = hn::Set(d, -HUGE_VAL), slope = zero;
      for (int i = 0; i < 3; ++i) {
        const V value = plane_at(n, p[k], zero, p[i]);
        highest = hn::IfThenElse(hn::Lt(highest, value), value, highest);
        const V rise = dot(n, rays[i]);
        slope = hn::IfThenElse(hn::Lt(slope, rise), rise, slope);
      }
      const V reach =
          hn::Add(highest, hn::IfThenElse(hn::Gt(slope, zero), hn::Mul(slope, t_max), zero));
      keep = hn::And(keep, hn::IsFinite(reach));
      store3(d, n, b.normal[4 + k], at);
      hn::Store(hn::Sub(zero, reach), d, b.shift[k] + at);
      store_mask(d, keep, b.extra_kept[k] + at);
    }
  }
}

}  // namespace shadowcts::simd::ptsv::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace shadowcts::simd::ptsv {
namespace {

void add(ref::SetupCounts& a, const ref::SetupCounts& b) {
  a.casters += b.casters;
  a.zero_area += b.zero_area;
  a.edge_on += b.edge_on;
  a.front_faces_culled += b.front_faces_culled;
  a.volumes += b.volumes;
  a.extra_planes += b.extra_planes;
  a.silhouette_planes += b.silhouette_planes;
}

// Whether a regular sample lies in the closed box [lo, hi] (float comparisons, exact): the
// nodes whose sample box misses it are skipped, a leaf's tile samples are tested one by one.
bool holds_a_sample(const Hierarchy& h, const glm::vec3& lo, const glm::vec3& hi) {
  const glm::dvec3 dlo(lo), dhi(hi);
  std::vector<std::pair<int, std::uint32_t>> stack = {{0, 0u}};
  while (!stack.empty()) {
    const auto [l, p] = stack.back();
    stack.pop_back();
    const Level& level = h.levels[std::size_t(l)];
    bool meets = true;
    for (std::size_t k = 0; k < 3; ++k)
      meets = meets && level.lo[k][p] <= dhi[int(k)] && level.hi[k][p] >= dlo[int(k)];
    if (!meets) continue;
    if (l == h.leaf_level()) {
      const std::uint32_t tile = h.leaf_tile[p];
      for (std::uint32_t i = h.tile_offsets[tile]; i < h.tile_offsets[tile + 1]; ++i) {
        const glm::vec3 q(float(h.tile_pos[0][i]), float(h.tile_pos[1][i]),
                          float(h.tile_pos[2][i]));
        if (q.x >= lo.x && q.x <= hi.x && q.y >= lo.y && q.y <= hi.y && q.z >= lo.z && q.z <= hi.z)
          return true;
      }
      continue;
    }
    const std::uint32_t children = std::uint32_t(std::popcount(level.child_mask[p]));
    for (std::uint32_t c = 0; c < children; ++c) stack.push_back({l + 1, level.first_child[p] + c});
  }
  return false;
}

PackedVolume* allocate_volumes(std::size_t n) {
  return static_cast<PackedVolume*>(
      allocate_large(n * sizeof(PackedVolume), alignof(PackedVolume)));
}

}  // namespace

void FreeVolumes::operator()(PackedVolume* p) const {
  free_large(p);
}

std::vector<bool> front_face_culling_meshes(const PreparedScene& scene, const Hierarchy& h,
                                            const std::vector<double>& sample_reach) {
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  const std::size_t meshes = c.meshes.size();
  // meshes_safe_for_face_culling: closed casters whose box holds no regular sample and no point
  // light. Float boxes; their double images are the double boxes of the reference.
  const MeshBoxes boxes = mesh_boxes(c);
  std::vector<std::uint8_t> safe(meshes, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, meshes, 1),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t m = r.begin(); m != r.end(); ++m) {
                        if (!c.meshes[m].closed || !c.meshes[m].caster) continue;
                        if (c.light && c.light->kind == ShadowLightKind::point &&
                            boxes.holds(m, c.light->position))
                          continue;
                        safe[m] = !holds_a_sample(h, boxes.lo[m], boxes.hi[m]);
                      }
                    });
  // The rest as the reference does it.
  const std::uint32_t width = samples.width, height = samples.height;
  std::vector<bool> culled(meshes, false);
  const double tan_half_fov = camera_frame(c.camera).tan_half_fov;
  const double aspect = double(width) / double(height);
  const double reach = double(c.camera.near_plane) *
                       std::sqrt(1.0 + tan_half_fov * tan_half_fov * (1.0 + aspect * aspect)) *
                       (1.0 + 0x1p-20);
  const glm::dvec3 eye(c.camera.position);
  for (std::size_t m = 0; m < meshes; ++m) {
    if (!safe[m]) continue;
    const glm::dvec3 lo(boxes.lo[m]), hi(boxes.hi[m]);
    bool clear = false;
    for (int k = 0; k < 3; ++k) clear = clear || eye[k] + reach < lo[k] || eye[k] - reach > hi[k];
    culled[m] = clear;
  }
  const RegularSamples& regular = scene.samples;
  if (sample_reach.size() != regular.size())
    throw std::logic_error("ptsv simd: one reject reach per regular sample expected");
  std::vector<std::size_t> candidates;
  for (std::size_t m = 0; m < meshes; ++m)
    if (culled[m]) candidates.push_back(m);
  if (candidates.empty()) return culled;
  // A mesh keeps its light-facing triangles if any sample comes within its reach of the box:
  // which sample finds it does not matter, so the samples are split over the threads.
  std::vector<std::uint8_t> near(meshes, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, regular.size(), 8192),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::vector<std::size_t> left;
                      for (std::size_t m : candidates)
                        if (!std::atomic_ref<std::uint8_t>(near[m]).load(std::memory_order_relaxed))
                          left.push_back(m);
                      for (std::size_t i = range.begin(); i != range.end() && !left.empty(); ++i) {
                        const double r = sample_reach[i];
                        if (!(r > 0.0)) continue;
                        const glm::dvec3 p(regular.position(i));
                        std::erase_if(left, [&](std::size_t m) {
                          const glm::dvec3 lo(boxes.lo[m]), hi(boxes.hi[m]);
                          bool far = false;
                          for (int k = 0; k < 3; ++k)
                            far = far || lo[k] - p[k] > r || p[k] - hi[k] > r;
                          if (!far)
                            std::atomic_ref<std::uint8_t>(near[m]).store(1,
                                                                         std::memory_order_relaxed);
                          return !far;
                        });
                      }
                    });
  for (std::size_t m : candidates)
    if (near[m]) culled[m] = false;
  return culled;
}

void PackedVolume::exact_volume(ref::ShadowVolume& v, bool directional,
                                const glm::vec3& light) const {
  v.triangle = triangle;
  for (int k = 0; k < 3; ++k) {
    v.exact.vertices[std::size_t(k)] =
        glm::vec3(float(vertex(k, 0)), float(vertex(k, 1)), float(vertex(k, 2)));
    v.exact.edge_outside[std::size_t(k)] = edge_outside[k];
  }
  for (int k = 0; k < 4; ++k) v.exact.condition[std::size_t(k)] = double(condition[k]);
  v.exact.triangle_outside = triangle_outside;
  v.exact.directional = directional;
  v.exact.light = light;
}

HWY_EXPORT(SetUpBatch);

namespace {

// The lane results of batch entry i into its volume slot; false when a plane was unusable. The
// canonical vertices are distinct (the triangle has area), so each plane's anchor is the vertex
// it was built through: the edges' first vertices, p for the triangle, k for culling plane k.
bool store_volume(const SetupBatch& b, std::size_t i, PackedVolume& p, ref::SetupCounts& counts) {
  if (!b.usable[i]) {
    ++counts.edge_on;  // a cross product underflowed: as good as edge-on
    return false;
  }
  static constexpr int edge_parity[3] = {1, 1, -1};
  const int orientation = b.orientation[i] > 0.0 ? 1 : -1;
  for (int a = 0; a < 3; ++a) {
    p.vertex_pq[0][a] = float(b.vertex[0][a][i]);
    p.vertex_pq[1][a] = float(b.vertex[1][a][i]);
    p.vertex_r[a] = float(b.vertex[2][a][i]);
  }
  for (int k = 0; k < 4; ++k)
    for (int a = 0; a < 3; ++a) p.normal[k][a] = b.normal[k][a][i];
  for (int e = 0; e < 3; ++e) p.edge_outside[e] = std::int8_t(edge_parity[e] * orientation);
  std::uint8_t mask = 0;
  for (int k = 0; k < 3; ++k) {
    const bool kept = b.extra_planes && b.extra_kept[k][i];
    for (int a = 0; a < 3; ++a) p.extra[k][a] = kept ? b.normal[4 + k][a][i] : 0.0;
    p.extra[k][3] = kept ? b.shift[k][i] : 0.0;
    if (kept) mask |= std::uint8_t(1u << k);
  }
  p.extra_mask = mask;
  counts.extra_planes += std::uint64_t(std::popcount(mask));
  for (int k = 0; k < 4; ++k) p.condition[k] = float_above(b.condition[k][i]);
  p.triangle_outside = std::int8_t(orientation);
  p.triangle = b.triangle[i];
  ++counts.volumes;
  return true;
}

}  // namespace

PackedVolumes set_up_shadow_volumes(const Case& c, const std::vector<bool>& culled_meshes,
                                    const ref::SetupOptions& options, double scene_bound) {
  if (!c.light || c.light->kind == ShadowLightKind::sun_disk)
    throw InputError(c.source, "light", "ptsv needs a point or directional light");
  PackedVolumes out;
  out.directional = c.light->kind == ShadowLightKind::directional;
  out.light = out.directional ? c.light->direction : c.light->position;
  if (out.directional && out.light == glm::vec3(0.0f))
    throw InputError(c.source, "light.direction", "has zero length");
  const std::size_t n = c.triangles.size();
  out.slot.reset(allocate_volumes(n));  // uninitialized: written in parallel below
  std::vector<std::uint8_t> has(n, 0);
  tbb::combinable<ref::SetupCounts> counts;
  // The reference's constants: any two points within the scene bound are at most `diameter`
  // apart; a directional volume's rays need no longer than diameter / |d|.
  const double diameter = 2.0 * std::sqrt(3.0) * scene_bound;
  const double directional_t_max = diameter / glm::length(glm::dvec3(out.light));
  const auto run_batch = [&](SetupBatch& b, ref::SetupCounts& local) {
    if (b.size == 0) return;
    HWY_DYNAMIC_DISPATCH(SetUpBatch)(b);
    for (std::size_t i = 0; i < b.size; ++i)
      has[b.triangle[i]] = store_volume(b, i, out.slot[b.triangle[i]], local) ? 1 : 0;
    b.size = 0;
  };
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        ref::SetupCounts& local = counts.local();
        const auto batch = std::make_unique<SetupBatch>();
        SetupBatch& b = *batch;
        b.directional = out.directional;
        b.extra_planes = options.extra_planes;
        for (int a = 0; a < 3; ++a) b.light[a] = double(out.light[a]);
        b.diameter = diameter;
        b.directional_t_max = directional_t_max;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::optional<ref::CanonicalCaster> caster =
              ref::canonical_caster(c, i, culled_meshes, out.directional, out.light, local);
          if (!caster) continue;
          const std::size_t at = b.size++;
          for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a)
              b.vertex[k][a][at] = double(caster->vertices[std::size_t(k)][a]);
          b.orientation[at] = double(caster->orientation);
          b.triangle[at] = std::uint32_t(i);
          if (b.size == SetupBatch::capacity) run_batch(b, local);
        }
        run_batch(b, local);
      });
  counts.combine_each([&](const ref::SetupCounts& local) { add(out.counts, local); });
  for (std::size_t i = 0; i < n; ++i)
    if (has[i]) out.order.push_back(std::uint32_t(i));
  return out;
}

}  // namespace shadowcts::simd::ptsv
#endif  // HWY_ONCE
