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

struct PackedPlane {
  double normal[3];
  double shift;
};

// Trivially constructible: a slot per triangle is allocated without being written first. What
// the node tests load comes first (about four cache lines), the exact definition after it.
struct alignas(64) PackedVolume {
  PackedPlane plane[7];       // edges (p,q), (q,r), (p,r), the triangle, then the extra planes
  float vertex[3][3];         // canonical order
  std::uint8_t anchor_of[7];  // each plane's anchor: a canonical vertex
  std::uint8_t extra_count;
  std::uint32_t triangle;
  double condition[4];
  std::int8_t edge_outside[3];
  std::int8_t triangle_outside;

  double anchor(int k, int axis) const { return double(vertex[anchor_of[k]][axis]); }
  // The reference volume's exact part (and triangle), for ref::outside_plane_exactly.
  void exact_volume(ref::ShadowVolume& v, bool directional, const glm::vec3& light) const;
};

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
// sample, one mesh per task. sample_reach: per view sample (ReceiverRule::reject_reach).
std::vector<bool> front_face_culling_meshes(const PreparedScene& scene, const Hierarchy& h,
                                            const std::vector<double>& sample_reach);

PackedVolumes set_up_shadow_volumes(const Case& c, const std::vector<bool>& culled_meshes,
                                    const ref::SetupOptions& options, double scene_bound);

}  // namespace shadowcts::simd::ptsv
