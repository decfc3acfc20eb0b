#pragma once
// Where along a sample's counting line a face's counted crossing can lie, so that a structure can
// skip faces that are far from the part of the line the count looks at (view_grid.h).
//
// count_crossings (volume_counting.h) counts a face triangle when a perturbed line through the
// eye e and the sample p crosses it, and the exact sides of e and p of the face's plane say the
// crossing is before p (z-pass) or beyond it (z-fail). The unperturbed line e + t (p - e) then
// meets the closed triangle at some t. For a cap (light or dark), whose plane is its own
// triangle's, that t is in (0, 1) (z-pass) or [1, inf) (z-fail) whenever e is off the plane. A side
// quad's sides are taken of its exact plane P (edge and light), which its triangles only
// approximate: their extruded vertices lie within `delta` of P. With a >= the eye's distance from P
// (> 0), a counted crossing lies at t in [-delta/a, 1 + delta/a] (z-pass) or [1 - delta/a, inf)
// (z-fail); for z-fail this needs, besides, that a line counted with the triangle's normal and P's
// disagreeing in sign cannot reach the triangle, which holds once a > delta + tilt * reach (tilt:
// a bound on the angle between the triangles and P, reach: the farthest of the line's and the
// face's points from the eye). Faces for which no such bound is proven are tested everywhere.
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/stencil/shadow_volume.h"
#include "reference/stencil/volume_counting.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::stencil {

struct CrossingReach {
  enum class Kind : std::uint8_t {
    never,     // the mode never counts it (z-pass, eye exactly in its plane)
    bounded,   // counted crossings lie within `slack` (in t) of the counted part of the line
    anywhere,  // no bound: test it for every sample
  };
  Kind kind = Kind::anywhere;
  double slack = 0.0;         // delta / a; at most max_slack when bounded
  double eye_distance = 0.0;  // a lower bound on the distance from the eye to the face (0: none)
};

// Bounded faces have a slack of at most this (larger ones are tested everywhere).
inline constexpr double max_slack = 0.5;

// `sample_reach`: an upper bound on |p - e| over the samples that will be counted.
CrossingReach crossing_reach(const VolumeFace& face, const FaceEyeSides& eye_side,
                             CountingMode mode, const Extrusion& extrusion,
                             const HardShadowLight& light, const glm::dvec3& eye,
                             double sample_reach);

}  // namespace shadowcts::stencil
