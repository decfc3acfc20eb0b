#pragma once
// Shadow-volume faces: light caps, side quads extruded from the silhouette edges away from the
// light, and dark caps (the light caps moved away with the same extrusion), together a closed
// boundary (every edge is used once in each direction) of the union of the caps' shadows.
//
// The volumes are cut off far away instead of reaching infinity, but provably beyond every point
// that matters (the eye and the view samples, within distance R of a point light): point light:
// x' = L + k (x - L) with k = 2 R / d_min, d_min the smallest distance from L to a cap, so every
// point of a dark cap is at least 2R from L; directional light: x' = x - K d/|d| with K twice the
// depth range along d from the highest cap to the deepest sample or the eye. One k (or K) for all
// vertices keeps a vertex shared by several quads and caps at one extruded position, so the
// boundary stays closed in double arithmetic too.
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "reference/stencil/silhouette.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::stencil {

enum class FaceKind : std::uint8_t { light_cap, side_quad, dark_cap };

inline constexpr std::uint32_t no_triangle = 0xFFFFFFFFu;

// A triangle, or a quad (v0, v1, v2, v3) split into the triangles (v0, v1, v2) and (v0, v2, v3).
// Oriented so that (v1 - v0) x (v2 - v0) points out of the volume.
struct VolumeFace {
  glm::dvec3 v[4];
  FaceKind kind = FaceKind::light_cap;
  // Light and dark caps: the caster triangle (to know receivers; a dark cap's light cap).
  std::uint32_t triangle = no_triangle;
  bool is_quad() const { return kind == FaceKind::side_quad; }
};

// Where a volume vertex x is extruded to: L + scale (x - L) for a point light, x + shift * away
// for a directional one. One extrusion for every face, so a face built twice is the same bits.
struct Extrusion {
  bool directional = false;
  glm::dvec3 light{0.0};  // point light position
  double scale = 1.0, shift = 0.0;
  glm::dvec3 away{0.0};  // directional: unit vector away from the light
  glm::dvec3 operator()(const glm::dvec3& x) const {
    return directional ? x + shift * away : light + scale * (x - light);
  }
  // The extruded point before rounding, origin + factor (minuend - subtrahend): operator() is
  // that expression evaluated in double. The counting takes the sides of edges between extruded
  // points of these exact points (volume_counting.h).
  struct Exact {
    glm::dvec3 origin, minuend, subtrahend;
    double factor;
  };
  Exact exact(const glm::dvec3& x) const {
    return directional ? Exact{x, away, glm::dvec3(0.0), shift} : Exact{light, x, light, scale};
  }
};

// The vertices a cap's dark cap is extruded from, in the dark cap's order (reversed: it faces
// away from the light).
std::array<glm::dvec3, 3> dark_cap_base(const LightCap& cap);

struct ShadowVolumes {
  std::vector<VolumeFace> faces;
  std::uint64_t silhouette_edges = 0;
  Extrusion extrusion;
};

// The closed volume of one cap on its own: the cap, the side quads of its three edges and its dark
// cap, built with the same extrusion (and so the same bits) as the faces of `volumes`. The faces
// of all caps' own volumes sum, in every count, to those of `volumes` (the side quads of edges
// that two caps share cancel), so subtracting the receiver's own volume leaves the winding of
// every other caster (a receiver never shadows its own sample), and counting them tells whether
// the count included that one cap (the receiver half-space rule removes the caps it rejects).
std::array<VolumeFace, 5> own_volume_faces(const LightCap& cap, const Extrusion& extrusion);

// Smallest distance from the point light to any cap.
double light_to_caps_distance(const Occluders& occluders, const glm::dvec3& light);

// `eye` and the regular samples fix how far the volumes must reach. The point light must not touch
// a cap (light_to_caps_distance > 0).
ShadowVolumes build_shadow_volumes(const Occluders& occluders, const HardShadowLight& light,
                                   const glm::dvec3& eye, const ViewSamples& samples);

}  // namespace shadowcts::stencil
