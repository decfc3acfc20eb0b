#pragma once
// The exact hard-shadow predicate: does a closed triangle meet the shadow segment (point light) or
// the shadow ray (directional light) of a sample position that may have been moved by the band?
// Exact for float triangle vertices, float lights and exactly represented moved positions: CGAL's
// orientation predicates decide, no plane or intersection point is ever constructed in floating
// point, and no coordinate is ever rounded.
#include <cstdint>
#include <memory>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {

// The point base + delta * direction, with direction's components in {-1, 0, 1}: a sample
// position moved by the ambiguity band. Its coordinates are exact: the predicate evaluates the sum
// in doubles only where that is provably exact, and in exact rationals otherwise.
struct MovedPoint {
  glm::dvec3 base{0.0};
  double delta = 0.0;
  glm::ivec3 direction{0};
};

// Whether the three vertices are exactly collinear (the triangle has zero area and casts no
// shadow).
bool is_zero_area(const Triangle& t);

// The exact sign of CGAL's orientation(a, b, c, d), the sign of det(b - a, c - a, d - a): 0 when
// the four points lie in one plane.
int exact_orientation(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                      const glm::dvec3& d);

// Whether triangle i of the case casts a shadow by the oracles' own tests: its mesh is a caster
// and is_zero_area() says no (the algorithms ask shadowcts/hard_shadow_inputs.h instead). Throws
// InputError when its mesh id is out of range.
bool oracle_casts_shadow(const Case& c, std::size_t i);

// The receiver half-space rule (DESIGN.md, "Cases and ground truth"): a caster shadows a sample
// only where it meets the sample's segment (ray) strictly on the light's side of the receiver's
// supporting plane. The plane stays fixed while the band moves the sample.
struct ReceiverPlane {
  bool active = false;  // the sample has a receiver of non-zero area; otherwise the rule is void
  glm::dvec3 a{0.0}, b{0.0}, c{0.0};  // the receiver's vertices
  // The sign of orientation(a, b, c, .) on the light's side; 0 when the light lies in the plane
  // (then no point is strictly on its side and no caster shadows the sample).
  int light_side = 0;
};

// Where a caster lies against a receiver's plane, by the exact sides of its vertices.
enum class PlaneReach : std::uint8_t {
  whole,      // every vertex strictly on the light's side (or the rule is void): no hit is removed
  none,       // no vertex strictly on the light's side: the caster shadows no point of the sample
  straddles,  // some vertices on each side: each hit is decided on its own
};

class ExactShadowPredicate {
 public:
  // scene_bound must be >= every |coordinate| of every triangle passed to blocks(): directional
  // rays are cut where they leave that cube.
  ExactShadowPredicate(const HardShadowLight& light, double scene_bound);

  // Does the closed triangle t meet the closed segment from x to the point light, or the closed
  // ray from x towards the directional light? False for zero-area triangles. The caller excludes
  // the receiver and non-caster triangles.
  bool blocks(const Triangle& t, const MovedPoint& x) const;

  // The same under the receiver half-space rule: does t meet the segment (ray) of x at a point
  // strictly on the light's side of the plane? `reach` must be reach(plane, t).
  bool blocks(const Triangle& t, const MovedPoint& x, const ReceiverPlane& plane,
              PlaneReach reach) const;

  bool blocks(const Triangle& t, const MovedPoint& x, const ReceiverPlane& plane) const {
    return blocks(t, x, plane, reach(plane, t));
  }

  // The plane of a sample's receiver (inactive for a zero-area receiver), oriented by the light.
  ReceiverPlane receiver_plane(const Triangle& receiver) const;
  PlaneReach reach(const ReceiverPlane& plane, const Triangle& t) const;

  // The side of x of the plane that holds the segment ab and the light: the plane through L, a
  // and b (point light) or through a and b parallel to d (directional). +1 or -1, consistently
  // for one (a, b); 0 when x lies on the plane or there is no such plane (L on the line ab, or
  // ab parallel to d). Two triangles sharing the edge ab with third vertices on opposite sides
  // cover, seen from the light, both sides of the edge. Exact.
  int light_plane_side(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& x) const;

  const HardShadowLight& light() const { return light_; }
  double scene_bound() const { return scene_bound_; }

 private:
  HardShadowLight light_;
  double scene_bound_;
};

// The closed cube B of half-width h around a sample (all its moves of length <= h), and exact
// tests of how the pieces of a caster's shadow volume meet it. With V_T the shadow volume of a
// closed caster triangle T (the points whose segment to the light, or ray towards it, meets T):
//
// - V_T is bounded by T itself and by the wedges behind T's edges, W_ab = {L + s (x - L): x in ab,
//   s >= 1} (point light) or {x - t d: x in ab, t >= 0} (directional light);
// - W_ab meets B iff the segment ab meets B's light hull H: conv(L, B) for a point light, B swept
//   towards a directional light (B + t d, t >= 0); likewise the ray behind a vertex v
//   ({L + s (v - L): s >= 1}, or {v - t d}) meets B iff v lies in H, and V_T meets B iff T meets H.
//
// H is a convex polyhedron: the faces of B that do not face the light, and one lateral face per
// silhouette edge e of B (the triangle conv(L, e), or the strip e + t d cut beyond the scene
// bound, where no caster lies). Every test runs CGAL's exact predicates on exactly represented
// points (exact rationals where a swept point is not a double). The cube's bounds p +- h are
// rounded outwards to doubles where they are not doubles, so every test answers for a cube that
// contains B: "does not meet" is always certain for B itself.
class ExactCubeQuery {
 public:
  ExactCubeQuery(const ExactShadowPredicate& predicate, const glm::dvec3& centre,
                 double half_width);
  ~ExactCubeQuery();
  ExactCubeQuery(const ExactCubeQuery&) = delete;
  ExactCubeQuery& operator=(const ExactCubeQuery&) = delete;

  // Does the closed triangle meet B?
  bool meets_triangle(const Triangle& t) const;
  // Does the shadow ray behind x meet B (x in H)?
  bool shadow_ray_meets(const glm::dvec3& x) const;
  // Does the shadow wedge behind the segment ab meet B (ab meets H)? a != b.
  bool shadow_wedge_meets(const glm::dvec3& a, const glm::dvec3& b) const;
  // Does the shadow volume of the non-degenerate triangle t meet B (t meets H)? Exactly when
  // some point of B is shadowed by t.
  bool shadow_volume_meets(const Triangle& t) const;
  // For a caster that straddles the receiver's plane: does the shadow wedge behind the piece of
  // the caster that lies in the plane (a segment or a point, which the rule makes an open edge of
  // the caster's shadowing part) meet B?
  bool clip_wedge_meets(const Triangle& t, const ReceiverPlane& plane) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace shadowcts
