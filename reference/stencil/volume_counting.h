#pragma once
// Counting shadow-volume crossings along a view sample's eye line: the software stencil buffer.
//
// Both variants evaluate the point p- just in front of the sample towards the eye (the depth test
// of a stencil pass: a volume face exactly at the sample's depth is "behind" for z-pass and counted
// by z-fail). A face is crossed by the line through the eye e and the sample p when its three edge
// sides (edge_side, exact with simulation of simplicity) agree; their common sign is the direction
// of the crossing relative to the face's outward normal. Where along the line it is crossed follows
// from the exact sides of e and p relative to the face's plane (a zero side is decided by the
// perturbation: p- lies on the eye side of anything through p, e+ on the sample side).
//  - z-pass: winding(p-) = winding(e) + (entries - exits) on the segment (e+, p-), with
//    winding(e) taken to be 0: wrong exactly when the eye is inside a shadow volume. Side quads
//    and light caps (a sample need not be the first surface seen from the eye: the segment may
//    pass through a caster in front of it), never the dark caps, which the extrusion puts beyond
//    the eye and every sample (shadow_volume.h), hence beyond every point of the segment.
//  - z-fail: winding(p-) = (exits - entries) on the ray from p- away from the eye, which leaves
//    every (bounded) volume: no assumption about the eye; light caps, side quads and dark caps.
// A receiver never shadows its own sample (the oracle's rule), although the sample lies on it (or,
// its float position rounded, just off its plane, even inside its volume next to a side quad): the
// algorithm subtracts the count of the receiver's own closed volume (own_volume_faces), counted
// by the same rules, from the sample's winding.
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/stencil/shadow_volume.h"

namespace shadowcts::stencil {

enum class CountingMode { z_pass, z_fail };

// The eye's exact side of each face triangle, computed once per run (quads: both triangles).
// Sides of a side quad are taken of its exact plane (through its edge and the light), which its
// rounded extruded vertices only approximate, and its lateral edges (an end of the edge to its
// extruded copy) are their exact lines from the light; caps are exact triangles. So a line that
// lies in a quad's plane (the eye and the sample on it) crosses nothing in it and passes the
// quads around it by the perturbation alone, never by how the extruded vertices rounded.
struct FaceEyeSides {
  std::int8_t side[2] = {0, 0};
};
FaceEyeSides eye_sides(const VolumeFace& face, const glm::dvec3& eye, const HardShadowLight& light);

// The face's contribution to the sample's winding number (a quad counts as its two triangles).
// Edges between extruded vertices are the exact lines between the exactly extruded points
// (`extrusion`; a dark cap's from `dark_base`, dark_cap_base of its light cap: required for dark
// caps), not between their rounded copies.
int count_crossings(const VolumeFace& face, const FaceEyeSides& eye_side, CountingMode mode,
                    const glm::dvec3& eye, const glm::dvec3& sample, const HardShadowLight& light,
                    const Extrusion& extrusion,
                    const std::array<glm::dvec3, 3>* dark_base = nullptr);

// Crossing tests made, for the counters.
struct FaceTally {
  std::uint64_t quads = 0, caps = 0;
  std::uint32_t faces = 0;
};

// The contribution of one cap to the sample's winding: the count of its own closed volume
// (own_volume_faces; z-pass without the dark cap), by the same rules and bits as the count of all
// volumes, which is the sum of these over the caps.
int count_own_volume(const LightCap& cap, const Extrusion& extrusion, CountingMode mode,
                     const glm::dvec3& eye, const glm::dvec3& sample, const HardShadowLight& light,
                     FaceTally& tally);

}  // namespace shadowcts::stencil
