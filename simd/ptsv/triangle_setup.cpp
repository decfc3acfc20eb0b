#include "simd/ptsv/triangle_setup.h"

#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

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

PackedPlane pack(const ref::Plane& plane, const ref::ExactVolumePlanes& exact) {
  PackedPlane p;
  for (int k = 0; k < 3; ++k) p.normal[k] = plane.normal[k];
  p.shift = plane.shift;
  for (std::uint32_t v = 0; v < 3; ++v)
    if (glm::dvec3(exact.vertices[v]) == plane.anchor) {
      p.anchor = v;
      return p;
    }
  throw std::logic_error("ptsv simd: a volume plane not anchored at a vertex");
}

}  // namespace

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
  out.slot.reset(new PackedVolume[n]);  // default-initialized: written in parallel below
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
          for (int k = 0; k < 3; ++k) p.plane[k] = pack(v.edges[std::size_t(k)], v.exact);
          p.plane[3] = pack(v.triangle_plane, v.exact);
          p.extra_count = std::uint32_t(v.extra_count);
          for (int k = 0; k < v.extra_count; ++k)
            p.plane[4 + k] = pack(v.extra[std::size_t(k)], v.exact);
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
