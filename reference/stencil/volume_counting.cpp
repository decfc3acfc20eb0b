#include "reference/stencil/volume_counting.h"

#include "reference/stencil/robust_orientation.h"

namespace shadowcts::stencil {
namespace {

// The contribution of a crossing of the line, moving to the face's outer side when direction > 0,
// given the exact sides of the eye and the sample of the face's plane. A plane through p has p-
// before it.
int placed_crossing(int direction, int eye_side, int sample_side, CountingMode mode) {
  const int p_side = sample_side != 0 ? sample_side : -direction;
  if (mode == CountingMode::z_fail) return p_side == -direction ? direction : 0;
  const int e_side = eye_side != 0 ? eye_side : direction;  // e+ is past the plane
  // Entering the volume (direction < 0) adds one.
  return e_side == -direction && p_side == direction ? -direction : 0;
}

// edge_side of the edge between the exactly extruded points of a and b (extruded_edge_side).
int extruded_side(const glm::dvec3& eye, const glm::dvec3& sample, const glm::dvec3& a,
                  const glm::dvec3& b, const Extrusion& extrusion) {
  const Extrusion::Exact e = extrusion.exact(a);
  return extruded_edge_side(eye, sample, e.origin, e.minuend, e.subtrahend, e.factor, b, a);
}

// One oriented triangle (a cap); `sample_side` is the sample's exact side of its plane. A dark
// cap's edges are those between the exactly extruded points of `dark_base` (its light cap's
// vertices in its order), which its rounded vertices only approximate: a counting line through
// the extruded copy of a shared edge (the eye at the light, the sample on the edge) then passes
// it on the side the tie chose at the edge itself, as in the light caps and side quads.
int triangle_crossing(const VolumeFace& face, int eye_side, int sample_side, CountingMode mode,
                      const glm::dvec3& eye, const glm::dvec3& sample, const Extrusion& extrusion,
                      const std::array<glm::dvec3, 3>* dark_base) {
  // z-pass prefilter: e and p strictly on one side, the segment cannot cross.
  if (mode == CountingMode::z_pass && sample_side != 0 && sample_side == eye_side) return 0;
  const auto side = [&](int k) {
    const int next = (k + 1) % 3;
    if (face.kind != FaceKind::dark_cap) return edge_side(eye, sample, face.v[k], face.v[next]);
    const std::array<glm::dvec3, 3>& base = *dark_base;
    return extruded_side(eye, sample, base[std::size_t(k)], base[std::size_t(next)], extrusion);
  };
  const int direction = side(0);
  if (direction == 0 || side(1) != direction || side(2) != direction) return 0;
  return placed_crossing(direction, eye_side, sample_side, mode);
}

// edge_side of a side quad's lateral edge x -> extrude(x), taken of its exact line: through x and
// the point light, or through x along the directional light. The rounded extruded vertex lies on
// that line only within rounding, and a counting line in the exact plane of a quad next to it
// (the eye and the sample both on that plane) meets the exact line: the rounding then decided on
// which side it passed, against the tie every other face of that plane saw.
int lateral_side(const glm::dvec3& eye, const glm::dvec3& sample, const glm::dvec3& x,
                 const HardShadowLight& light) {
  // extrude(x) - x is a positive multiple of x - L, or of -d.
  if (!light.directional) return edge_side_along(eye, sample, x, x, light.position);
  return edge_side_along(eye, sample, x, glm::dvec3(0.0), light.direction);
}

// A side quad (to, from, extrude(from), extrude(to)) as its two triangles; the sides are of its
// exact plane, shared by both.
int quad_crossing(const VolumeFace& face, int eye_side, int sample_side, CountingMode mode,
                  const glm::dvec3& eye, const glm::dvec3& sample, const HardShadowLight& light,
                  const Extrusion& extrusion) {
  if (mode == CountingMode::z_pass && sample_side != 0 && sample_side == eye_side) return 0;
  // The line lies in the exact plane: the perturbed line (translated, edge_side) runs parallel to
  // it, so it crosses neither triangle, whatever the rounded far vertices say.
  if (sample_side == 0 && eye_side == 0) return 0;
  const glm::dvec3 &to = face.v[0], &from = face.v[1], &far_from = face.v[2];
  const int near = edge_side(eye, sample, to, from);
  const int diagonal = edge_side(eye, sample, far_from, to);
  int count = 0;
  if (near != 0 && lateral_side(eye, sample, from, light) == near && diagonal == near)
    count += placed_crossing(near, eye_side, sample_side, mode);
  // The second triangle: to -> far_from (the diagonal reversed) -> far_to -> to (the lateral
  // edge of `to` reversed). Its far edge is the dark caps' exact edge (triangle_crossing).
  if (diagonal != 0 && extruded_side(eye, sample, from, to, extrusion) == -diagonal &&
      lateral_side(eye, sample, to, light) == diagonal)
    count += placed_crossing(-diagonal, eye_side, sample_side, mode);
  return count;
}

// The side of x of a side quad's exact plane: through its edge (v[0] = to, v[1] = from) and the
// point light, or through the edge parallel to the directional light. Its two triangles lie in
// that plane only up to the rounding of the extruded vertices, so a point on it (a sample exactly
// on a shadow boundary, behind a T-junction's edge covered from both sides) would land on
// arbitrary sides of the rounded triangles of the quads through it; on the exact plane it is on
// every one of them, and the rule for a plane through p holds for all. The sign matches the
// triangles' orientation: an extruded vertex is L + s (x - L) with s > 1, or x - K d / |d|.
int side_quad_plane_side(const VolumeFace& face, const HardShadowLight& light,
                         const glm::dvec3& x) {
  const glm::dvec3& to = face.v[0];
  const glm::dvec3& from = face.v[1];
  if (!light.directional) return -orientation(to, from, light.position, x);
  return -sign_of_determinant(from, to, light.direction, glm::dvec3(0.0), x, to);
}

// The exact side of x of the face's plane (caps: their exact triangle; quads: as above).
int face_side(const VolumeFace& face, const HardShadowLight& light, const glm::dvec3& x) {
  if (face.is_quad()) return side_quad_plane_side(face, light, x);
  return orientation(face.v[0], face.v[1], face.v[2], x);
}

}  // namespace

FaceEyeSides eye_sides(const VolumeFace& face, const glm::dvec3& eye,
                       const HardShadowLight& light) {
  FaceEyeSides s;
  s.side[0] = std::int8_t(face_side(face, light, eye));
  if (face.is_quad()) s.side[1] = s.side[0];
  return s;
}

int count_crossings(const VolumeFace& face, const FaceEyeSides& eye_side, CountingMode mode,
                    const glm::dvec3& eye, const glm::dvec3& sample, const HardShadowLight& light,
                    const Extrusion& extrusion, const std::array<glm::dvec3, 3>* dark_base) {
  const int sample_side = face_side(face, light, sample);
  if (face.is_quad())
    return quad_crossing(face, eye_side.side[0], sample_side, mode, eye, sample, light, extrusion);
  return triangle_crossing(face, eye_side.side[0], sample_side, mode, eye, sample, extrusion,
                           dark_base);
}

int count_own_volume(const LightCap& cap, const Extrusion& extrusion, CountingMode mode,
                     const glm::dvec3& eye, const glm::dvec3& sample, const HardShadowLight& light,
                     FaceTally& tally) {
  int count = 0;
  const std::array<glm::dvec3, 3> base = dark_cap_base(cap);
  for (const VolumeFace& f : own_volume_faces(cap, extrusion)) {
    if (mode == CountingMode::z_pass && f.kind == FaceKind::dark_cap) continue;
    ++tally.faces;
    (f.is_quad() ? tally.quads : tally.caps) += 1;
    count +=
        count_crossings(f, eye_sides(f, eye, light), mode, eye, sample, light, extrusion, &base);
  }
  return count;
}

}  // namespace shadowcts::stencil
