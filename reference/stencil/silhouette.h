#pragma once
// The occluder side of the shadow volumes: which caster triangles become light caps (oriented to
// face the light) and the silhouette edges, found by mesh connectivity keyed by exact vertex
// positions.
//
// Per caster mesh:
//  - closed (is_closed_surface, shadowcts/closed_surface.h: on the exact float positions, every
//    directed edge once and its reverse once, the definition the loaders' Mesh::closed uses) and
//    the light outside the mesh's bounding box: the textbook rule. Caps are the light-facing
//    triangles; an edge is a silhouette edge when exactly one of its two triangles faces the light.
//    Back faces are dropped: a light segment that crosses one crossed a front face before.
//  - otherwise (open meshes such as ground planes and leaves, or a light inside a closed mesh's
//    box): every triangle that is not edge-on to the light is a cap, flipped when it faces away, so
//    each one bounds its own capped volume, as if per-triangle. Edges shared by two caps traversing
//    them in opposite directions carry two opposite side quads that cancel in every count, so they
//    are dropped: only the remaining edges (the open boundary and the creases where the facing
//    flips) are silhouette edges. Open meshes are therefore supported, never declined.
// Triangles edge-on to the light (including zero-area ones) enclose no volume and are dropped, and
// so are the triangles that contain the point light (`excluded`: decided exactly by the caller):
// their volume degenerates, and a mesh that holds one is never closed around the light.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::stencil {

struct LightCap {
  glm::dvec3 v[3];  // counter-clockwise seen from the light: normal (v1-v0)x(v2-v0) towards it
  std::uint32_t triangle = 0;  // index into Case::triangles
};

struct SilhouetteEdge {
  glm::dvec3 from, to;  // directed as in the caps it bounds
};

struct Occluders {
  std::vector<LightCap> caps;
  std::vector<SilhouetteEdge> silhouette;  // with multiplicity
  std::uint64_t closed_meshes = 0;         // caster meshes that used the front-face rule
};

// Sign of the light's side of triangle t: > 0 when its normal points towards the light.
int facing_sign(const Triangle& t, const HardShadowLight& light);

// `excluded`: caster triangles that are not caps whatever they face (sorted indices).
Occluders find_occluders(const Case& c, const HardShadowLight& light,
                         const std::vector<std::uint32_t>& excluded = {});

}  // namespace shadowcts::stencil
