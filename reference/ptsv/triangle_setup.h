#pragma once
// Triangle setup (Sintorn 2014, Section 2 "Triangle Setup"; Sintorn 2011, Section 3): the shadow
// volume of one caster triangle as planes, outside positive.
//
// - Three edge planes, each through an edge and the light (containing the light direction for a
//   directional light), and the triangle's own plane. A point lies in the volume iff it is on no
//   plane's positive side: the set of points whose segment to the light (ray towards it) meets the
//   closed triangle, boundary included, as the exact oracle defines it.
// - Shared edges: every plane is built from the vertices in one total order (lexicographic on
//   x, y, z), so two triangles that share an edge compute bit-identical edge planes and only the
//   orientation differs: no sample can fall outside both (Sintorn 2011, "robust" paragraph).
// - Orientation: every side decision is one exact orientation sign (exact_orientation.h); a
//   triangle exactly edge-on to the light casts nothing but its own plane and is skipped.
// - Triangle-plane bias: the paper biases the triangle plane so that a triangle does not shadow
//   its own samples. The sample test knows each sample's receiver and excludes it exactly, so here
//   the bias guards only the trivial accept of whole nodes (a node holding the triangle's own
//   samples is never accepted); the closed sample test itself stays unbiased.
// - Extra culling planes (Sintorn 2014): per vertex, the half vector of its two edge planes'
//   normals, made orthogonal to the vertex-to-light direction; skipped where unstable.
// - Silhouette planes (Sintorn 2011, Section 3.5): the planes through the eye that hold the two
//   2D silhouette edges of the projected volume, for the hierarchical-depth-buffer variant.
// Culling planes only ever reject. Each is pushed outwards until the triangle's vertices and the
// volume's three edge rays (up to the scene bound) lie on its inside, so rounding in its normal
// can cost culling, never a shadow.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

struct Plane {
  glm::dvec3 normal{0.0};  // unit
  glm::dvec3 anchor{0.0};  // a point the plane was built through
  double shift = 0.0;      // added to the signed distance: the plane moved outwards by -shift
  double at(const glm::dvec3& x) const {
    return normal.x * (x.x - anchor.x) + normal.y * (x.y - anchor.y) + normal.z * (x.z - anchor.z) +
           shift;
  }
};

// The exact definition of a volume's four planes, so that a sample within rounding of one is
// decided by an exact orientation sign (sample_in_volume): the canonical vertices p < q < r, the
// outside signs and the light. Two triangles whose edges lie on one line but do not share both
// ends (a T-junction) build that plane from different vertices and round it differently; without
// the exact decision a sample on it can fall outside both volumes.
struct ExactVolumePlanes {
  std::array<glm::vec3, 3> vertices{};        // canonical order
  std::array<std::int8_t, 3> edge_outside{};  // edges (p,q), (q,r), (p,r)
  std::int8_t triangle_outside = 0;
  bool directional = false;
  glm::vec3 light{0.0f};  // the point light, or the direction towards the light
  // Per plane (edges, then the triangle): |a||b| / |a x b| of the two vectors its normal was
  // crossed from, which scales the rounding of the unit normal.
  std::array<double, 4> condition{};
};

struct ShadowVolume {
  std::uint32_t triangle = 0;
  std::array<Plane, 3> edges;
  Plane triangle_plane;  // positive on the light's side
  ExactVolumePlanes exact;
  int extra_count = 0;  // Sintorn 2014 per-vertex culling planes
  std::array<Plane, 3> extra;
  int silhouette_count = 0;  // Sintorn 2011 planes through the eye
  std::array<Plane, 3> silhouette;
};

struct SetupOptions {
  bool extra_planes = false;
  bool silhouette_planes = false;
};

struct SetupCounts {
  std::uint64_t casters = 0;             // triangles whose mesh casts
  std::uint64_t zero_area = 0;           // cast nothing
  std::uint64_t edge_on = 0;             // light exactly in the triangle's plane
  std::uint64_t front_faces_culled = 0;  // closed meshes only (front_face_culling_meshes)
  std::uint64_t volumes = 0;             // shadow volumes set up
  std::uint64_t extra_planes = 0;        // culling planes kept
  std::uint64_t silhouette_planes = 0;
};

// Which meshes may drop their light-facing triangles (Sintorn 2011, Section 3.5; 2014, Section
// 3): closed meshes only, and only when neither a view sample nor a point light can lie inside one
// (meshes_safe_for_face_culling: no regular sample and no point light in the mesh's bounding box —
// samples come from G-buffers too, so the camera alone does not decide), and whose bounding box
// keeps clear of the camera's near region. A segment from outside a closed surface to a light
// outside it crosses one face of each orientation; one from inside leaves only through faces
// turned towards the light. Under the receiver half-space rule the face it enters by (turned away
// from the light) is the hit nearer the sample and may be rejected while the one it leaves by
// counts: that happens only within the sample's reject reach (receiver_rule.h), so a mesh whose
// bounding box comes within a sample's reach keeps its light-facing triangles.
// sample_reach: per sample (ReceiverRule::reject_reach).
std::vector<bool> front_face_culling_meshes(const Case& c, const ViewSamples& samples,
                                            const std::vector<double>& sample_reach);

// A caster triangle's vertices in the canonical order p < q < r (lexicographic on x, y, z: the
// order both triangles of a shared edge build its planes from) and its orientation in that order
// towards the light: +1 or -1.
struct CanonicalCaster {
  std::array<glm::vec3, 3> vertices;
  int orientation = 0;
};

// set_up_shadow_volume's checks, in its order and with its counts: nullopt, the reason counted,
// when triangle i casts no volume (its mesh casts nothing, zero area, edge-on to the light, a
// culled front face). light: the point light's position, or the direction towards a directional
// light.
std::optional<CanonicalCaster> canonical_caster(const Case& c, std::size_t i,
                                                const std::vector<bool>& culled_meshes,
                                                bool directional, const glm::vec3& light,
                                                SetupCounts& counts);

// The volume of triangle i, as set_up_shadow_volumes makes it (for ports that set triangles up in
// parallel): false, with the reason counted, when the triangle casts none.
bool set_up_shadow_volume(const Case& c, std::size_t i, const std::vector<bool>& culled_meshes,
                          const SetupOptions& options, double scene_bound, SetupCounts& counts,
                          ShadowVolume& volume);

// The volumes of every caster triangle in index order. scene_bound: >= every |coordinate| of
// every sample (it bounds how far the volume's edge rays need to be followed).
std::vector<ShadowVolume> set_up_shadow_volumes(const Case& c,
                                                const std::vector<bool>& culled_meshes,
                                                const SetupOptions& options, double scene_bound,
                                                SetupCounts& counts);

// The triangle-plane bias of the trivial accept (see above): larger than the distance of any
// sample from its own receiver's plane (float rounding of the position, < 2^-22 scale) and far
// below the ambiguity band (2^-16 scale by default), so it costs only a few refinements.
double trivial_accept_bias(double scene_bound);

}  // namespace shadowcts::ptsv
