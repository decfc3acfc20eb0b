#include "simd/ptsv/triangle_setup.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "shadowcts/geometry/camera_frame.h"

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

PackedPlane pack(const ref::Plane& plane, const ref::ExactVolumePlanes& exact,
                 std::uint8_t& anchor) {
  PackedPlane p;
  for (int k = 0; k < 3; ++k) p.normal[k] = plane.normal[k];
  p.shift = plane.shift;
  for (std::uint32_t v = 0; v < 3; ++v)
    if (glm::dvec3(exact.vertices[v]) == plane.anchor) {
      anchor = std::uint8_t(v);
      return p;
    }
  throw std::logic_error("ptsv simd: a volume plane not anchored at a vertex");
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
  void* p =
      std::aligned_alloc(alignof(PackedVolume), std::max<std::size_t>(1, n) * sizeof(PackedVolume));
  if (p == nullptr) throw std::bad_alloc();
  return static_cast<PackedVolume*>(p);
}

}  // namespace

void FreeVolumes::operator()(PackedVolume* p) const {
  std::free(p);
}

std::vector<bool> front_face_culling_meshes(const PreparedScene& scene, const Hierarchy& h,
                                            const std::vector<double>& sample_reach) {
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  const std::size_t meshes = c.meshes.size();
  // meshes_safe_for_face_culling: closed casters whose box holds no regular sample and no point
  // light. Float boxes; their double images are the double boxes of the reference.
  std::vector<glm::vec3> flo(meshes, glm::vec3(std::numeric_limits<float>::infinity()));
  std::vector<glm::vec3> fhi(meshes, glm::vec3(-std::numeric_limits<float>::infinity()));
  for (const Triangle& t : c.triangles) {
    if (t.mesh >= meshes) continue;  // reported by the setup
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      flo[t.mesh] = glm::min(flo[t.mesh], v);
      fhi[t.mesh] = glm::max(fhi[t.mesh], v);
    }
  }
  std::vector<std::uint8_t> safe(meshes, 0);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, meshes, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t m = r.begin(); m != r.end(); ++m) {
          if (!c.meshes[m].closed || !c.meshes[m].caster) continue;
          const glm::vec3& lo = flo[m];
          const glm::vec3& hi = fhi[m];
          const auto in_box = [&](const glm::vec3& p) {
            return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
                   p.z <= hi.z;
          };
          if (c.light && c.light->kind == ShadowLightKind::point && in_box(c.light->position))
            continue;
          safe[m] = !holds_a_sample(h, lo, hi);
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
    const glm::dvec3 lo(flo[m]), hi(fhi[m]);
    bool clear = false;
    for (int k = 0; k < 3; ++k) clear = clear || eye[k] + reach < lo[k] || eye[k] - reach > hi[k];
    culled[m] = clear;
  }
  if (sample_reach.size() != samples.samples.size())
    throw std::logic_error("ptsv simd: one reject reach per sample expected");
  std::vector<std::size_t> candidates;
  for (std::size_t m = 0; m < meshes; ++m)
    if (culled[m]) candidates.push_back(m);
  for (std::size_t i = 0; i < samples.samples.size() && !candidates.empty(); ++i) {
    const ViewSample& s = samples.samples[i];
    const double r = sample_reach[i];
    if (s.sample_class != SampleClass::regular || !(r > 0.0)) continue;
    const glm::dvec3 p(s.position);
    std::erase_if(candidates, [&](std::size_t m) {
      const glm::dvec3 lo(flo[m]), hi(fhi[m]);
      bool far = false;
      for (int k = 0; k < 3; ++k) far = far || lo[k] - p[k] > r || p[k] - hi[k] > r;
      if (!far) culled[m] = false;
      return !far;
    });
  }
  return culled;
}

void PackedVolume::exact_volume(ref::ShadowVolume& v, bool directional,
                                const glm::vec3& light) const {
  v.triangle = triangle;
  for (int k = 0; k < 3; ++k) {
    v.exact.vertices[std::size_t(k)] = glm::vec3(vertex[k][0], vertex[k][1], vertex[k][2]);
    v.exact.edge_outside[std::size_t(k)] = edge_outside[k];
  }
  for (int k = 0; k < 4; ++k) v.exact.condition[std::size_t(k)] = condition[k];
  v.exact.triangle_outside = triangle_outside;
  v.exact.directional = directional;
  v.exact.light = light;
}

PackedVolumes set_up_shadow_volumes(const Case& c, const std::vector<bool>& culled_meshes,
                                    const ref::SetupOptions& options, double scene_bound) {
  PackedVolumes out;
  const std::size_t n = c.triangles.size();
  out.slot.reset(allocate_volumes(n));  // uninitialized: written in parallel below
  std::vector<std::uint8_t> has(n, 0);
  tbb::combinable<ref::SetupCounts> counts;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
        ref::SetupCounts& local = counts.local();
        ref::ShadowVolume v;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if (!ref::set_up_shadow_volume(c, i, culled_meshes, options, scene_bound, local, v))
            continue;
          PackedVolume& p = out.slot[i];
          for (int k = 0; k < 3; ++k)
            p.plane[k] = pack(v.edges[std::size_t(k)], v.exact, p.anchor_of[k]);
          p.plane[3] = pack(v.triangle_plane, v.exact, p.anchor_of[3]);
          p.extra_count = std::uint8_t(v.extra_count);
          for (int k = 0; k < v.extra_count; ++k)
            p.plane[4 + k] = pack(v.extra[std::size_t(k)], v.exact, p.anchor_of[4 + k]);
          for (int k = 0; k < 3; ++k) {
            for (int a = 0; a < 3; ++a) p.vertex[k][a] = v.exact.vertices[std::size_t(k)][a];
            p.edge_outside[k] = v.exact.edge_outside[std::size_t(k)];
          }
          for (int k = 0; k < 4; ++k) p.condition[k] = v.exact.condition[std::size_t(k)];
          p.triangle_outside = v.exact.triangle_outside;
          p.triangle = v.triangle;
          has[i] = 1;
        }
      });
  counts.combine_each([&](const ref::SetupCounts& local) { add(out.counts, local); });
  for (std::size_t i = 0; i < n; ++i)
    if (has[i]) out.order.push_back(std::uint32_t(i));
  if (c.light) {
    out.directional = c.light->kind == ShadowLightKind::directional;
    out.light = out.directional ? c.light->direction : c.light->position;
  }
  return out;
}

}  // namespace shadowcts::simd::ptsv
