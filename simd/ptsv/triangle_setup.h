#pragma once
// Triangle setup of the simd ptsv: the reference's volumes (ref::set_up_shadow_volume, the same
// checks and the same arithmetic, the latter in lanes across triangles), packed for the lanes of
// the traversal. Every plane's anchor is one of the canonical vertices, so a packed plane keeps
// its normal and shift and names its vertex; the lanes broadcast them. The exact definition
// (ref::ExactVolumePlanes) stays beside them for the samples within rounding of a plane.
#include <cstdint>
#include <memory>
#include <vector>

#include "reference/ptsv/triangle_setup.h"
#include "shadowcts/case.h"
#include "shadowcts/prepared_scene.h"
#include "simd/ptsv/hierarchy.h"

namespace shadowcts::simd::ptsv {

namespace ref = ::shadowcts::ptsv;

// Trivially constructible: a slot per triangle is allocated without being written first. Four
// cache lines: the first two hold all that a node's reject and accept tests read (the four planes,
// whose shift is 0 and whose anchors are p or q), the last two what refinement (the culling
// planes) and the leaves (r, the filter's condition, the exact definition) read besides. The
// node tests are bound by the memory they stream: 1M volumes visited per hierarchy level.
struct alignas(64) PackedVolume {
  double normal[4][3];    // unit normals: edges (p,q), (q,r), (p,r), then the triangle
  float vertex_pq[2][3];  // canonical p and q
  std::int8_t edge_outside[3];
  std::int8_t triangle_outside;
  std::uint8_t extra_mask;  // bit k: culling plane k exists
  float vertex_r[3];        // canonical r
  std::uint32_t triangle;
  double extra[3][4];  // culling plane k: normal and shift, anchored at canonical vertex k
  // ref::ExactVolumePlanes::condition rounded up: it only scales the error bound of a filter
  // whose unsure samples are decided exactly, and a larger bound only sends more of them there.
  float condition[4];

  // Planes 0-3 are anchored at canonical vertex anchor[k] (ref::set_up_shadow_volume).
  static constexpr int anchor[4] = {0, 1, 0, 0};
  double vertex(int v, int axis) const {
    return double(v < 2 ? vertex_pq[v][axis] : vertex_r[axis]);
  }
  // The reference volume's exact part (and triangle), for ref::outside_plane_exactly.
  void exact_volume(ref::ShadowVolume& v, bool directional, const glm::vec3& light) const;
};
static_assert(sizeof(PackedVolume) == 256);

struct FreeVolumes {
  void operator()(PackedVolume* p) const;
};

struct PackedVolumes {
  // Per triangle; valid where `order` names it (aligned_alloc: not written before the setup).
  std::unique_ptr<PackedVolume[], FreeVolumes> slot;
  std::vector<std::uint32_t> order;  // triangles with a volume, in index order
  ref::SetupCounts counts;
  bool directional = false;
  glm::vec3 light{0.0f};  // the point light, or the direction towards the light
};

// A batch of triangles for the lanes of set_up_shadow_volumes (structure of arrays, one triangle
// per entry): the canonical vertices and orientation in, the planes out (normals: edges, the
// triangle, then the three candidate culling planes, each kept or not).
struct SetupBatch {
  static constexpr std::size_t capacity = 64;  // a multiple of any target's double lanes
  std::size_t size = 0;
  bool directional = false;
  bool extra_planes = false;
  double light[3] = {};
  double diameter = 0.0;
  double directional_t_max = 0.0;
  alignas(64) double vertex[3][3][capacity];
  alignas(64) double orientation[capacity];
  alignas(64) double normal[7][3][capacity];
  alignas(64) double shift[3][capacity];  // the culling planes'
  alignas(64) double condition[4][capacity];
  std::uint32_t triangle[capacity];
  std::uint8_t usable[capacity];
  std::uint8_t extra_kept[3][capacity];
};

// ref::front_face_culling_meshes, the same meshes: whether a mesh's box holds a regular sample
// (meshes_safe_for_face_culling) is asked of the hierarchy's explicit boxes instead of every
// sample, one mesh per task. sample_reach: per regular sample (ReceiverRule::reject_reach).
std::vector<bool> front_face_culling_meshes(const PreparedScene& scene, const Hierarchy& h,
                                            const std::vector<double>& sample_reach);

PackedVolumes set_up_shadow_volumes(const Case& c, const std::vector<bool>& culled_meshes,
                                    const ref::SetupOptions& options, double scene_bound);

}  // namespace shadowcts::simd::ptsv
