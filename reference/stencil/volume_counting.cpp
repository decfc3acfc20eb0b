#include "reference/stencil/volume_counting.h"

#include "reference/stencil/robust_orientation.h"

namespace shadowcts::stencil {
namespace {

// One oriented triangle of a face.
int triangle_crossing(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int eye_side,
                      CountingMode mode, const glm::dvec3& eye, const glm::dvec3& sample) {
  const int sample_side = orientation(a, b, c, sample);
  // z-pass prefilter: e and p strictly on one side, the segment cannot cross.
  if (mode == CountingMode::z_pass && sample_side != 0 && sample_side == eye_side) return 0;
  const int direction = edge_side(eye, sample, a, b);
  if (direction == 0 || edge_side(eye, sample, b, c) != direction ||
      edge_side(eye, sample, c, a) != direction)
    return 0;
  // The line crosses the triangle, moving to its outer side when direction > 0. A plane through
  // p has p- before it.
  const int p_side = sample_side != 0 ? sample_side : -direction;
  if (mode == CountingMode::z_fail) return p_side == -direction ? direction : 0;
  const int e_side = eye_side != 0 ? eye_side : direction;  // e+ is past the plane
  // Entering the volume (direction < 0) adds one.
  return e_side == -direction && p_side == direction ? -direction : 0;
}

}  // namespace

FaceEyeSides eye_sides(const VolumeFace& face, const glm::dvec3& eye) {
  FaceEyeSides s;
  s.side[0] = std::int8_t(orientation(face.v[0], face.v[1], face.v[2], eye));
  if (face.is_quad()) s.side[1] = std::int8_t(orientation(face.v[0], face.v[2], face.v[3], eye));
  return s;
}

int count_crossings(const VolumeFace& face, const FaceEyeSides& eye_side, CountingMode mode,
                    const glm::dvec3& eye, const glm::dvec3& sample) {
  int count =
      triangle_crossing(face.v[0], face.v[1], face.v[2], eye_side.side[0], mode, eye, sample);
  if (face.is_quad())
    count +=
        triangle_crossing(face.v[0], face.v[2], face.v[3], eye_side.side[1], mode, eye, sample);
  return count;
}

}  // namespace shadowcts::stencil
