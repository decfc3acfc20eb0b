#pragma once
// Angular distances on the sphere of directions around a point light (Deves et al. 2018,
// section 5.2: "the angular distance is the apparent distance between two points as seen from the
// light"). Every angle is atan2(|u x v|, u . v): unlike acos(u . v) it keeps full relative
// precision near 0 and near pi, where the dot product saturates at +-1.
//
// A capsule seen from the light has a great-circle arc of directions as its centre element
// (the directions of the points of its segment); the functions below measure a direction against
// such an arc.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace shadowcts::metric {

// Angle between two nonzero vectors, in [0, pi]; they need not be unit.
inline double angle_between(const glm::dvec3& u, const glm::dvec3& v) {
  return std::atan2(glm::length(glm::cross(u, v)), glm::dot(u, v));
}

// Arcs shorter than this are treated as a point (their midpoint) with the half length added to
// the angular radius: the arc's plane normal a x b / |a x b| then keeps a relative error below
// 1e-10 (|a x b| >= 1e-5 against an absolute error of ~1e-16 per component).
inline constexpr double shortest_arc = 1e-5;

// The shorter great-circle arc between two unit directions a and b (angle(a, b) < pi).
struct GreatArc {
  glm::dvec3 a{0.0}, b{0.0};
  glm::dvec3 normal{0.0};    // unit a x b
  glm::dvec3 midpoint{0.0};  // unit (a + b) / 2
  double half_length = 0.0;  // angle(a, b) / 2: every arc point is within it of the midpoint
};

inline GreatArc make_great_arc(const glm::dvec3& a, const glm::dvec3& b) {
  GreatArc arc;
  arc.a = a;
  arc.b = b;
  arc.normal = glm::normalize(glm::cross(a, b));
  arc.midpoint = glm::normalize(a + b);
  arc.half_length = 0.5 * angle_between(a, b);
  return arc;
}

// Whether direction w (in the arc's plane, nonzero) lies between a and b on the arc.
inline bool arc_spans(const GreatArc& arc, const glm::dvec3& w) {
  return glm::dot(glm::cross(arc.a, w), arc.normal) >= 0.0 &&
         glm::dot(glm::cross(w, arc.b), arc.normal) >= 0.0;
}

// Smallest angle between direction u and a point of the arc. The closest point of the whole great
// circle is u projected on the arc's plane; if the arc does not span it, the closest arc point is
// an endpoint (the angle to the circle grows monotonically away from the projection).
inline double distance_to_arc(const glm::dvec3& u, const GreatArc& arc) {
  const double height = glm::dot(u, arc.normal);
  const glm::dvec3 in_plane = u - height * arc.normal;
  const double in_plane_length = glm::length(in_plane);
  if (in_plane_length > 0.0 && arc_spans(arc, in_plane))
    return std::atan2(std::fabs(height), in_plane_length);
  return std::min(angle_between(u, arc.a), angle_between(u, arc.b));
}

// Largest angle between direction u and a point of the arc: at an endpoint, or at the point of
// the circle opposite u's projection when the arc spans it.
inline double max_distance_to_arc(const glm::dvec3& u, const GreatArc& arc) {
  double farthest = std::max(angle_between(u, arc.a), angle_between(u, arc.b));
  const double height = glm::dot(u, arc.normal);
  const glm::dvec3 in_plane = u - height * arc.normal;
  const double in_plane_length = glm::length(in_plane);
  if (in_plane_length > 0.0 && arc_spans(arc, -in_plane))
    farthest =
        std::max(farthest, std::numbers::pi - std::atan2(std::fabs(height), in_plane_length));
  return farthest;
}

}  // namespace shadowcts::metric
