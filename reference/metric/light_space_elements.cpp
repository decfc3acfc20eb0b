#include "reference/metric/light_space_elements.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace shadowcts::metric {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// A volume whose enlarged radius reaches within this relative distance of the light is treated as
// containing it: asin(R / D) then needs no care near R = D.
constexpr double containment_tolerance = 1e-12;

// Angular radius asin(R / D) for D > R, written with atan2 so that it stays accurate near pi/2.
double angular_radius(double radius, double distance) {
  return std::atan2(radius, std::sqrt((distance - radius) * (distance + radius)));
}

double closest_parameter(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double length_squared = glm::dot(ab, ab);
  return length_squared > 0.0 ? std::clamp(glm::dot(p - a, ab) / length_squared, 0.0, 1.0) : 0.0;
}

double distance_to_segment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  return glm::length(p - (a + closest_parameter(p, a, b) * (b - a)));
}

glm::dvec3 in_plane(const LightFrame& frame, const glm::dvec3& x) {
  return {glm::dot(x, frame.plane_x), glm::dot(x, frame.plane_y), 0.0};
}

double directional_light_distance(const LightFrame& frame, const glm::dvec3& x) {
  return -glm::dot(x, frame.towards_light);
}

// Distance from a query position (unit direction or plane point) to the element's centre.
double distance_to_centre(const LightFrame& frame, const LightSpaceElement& e,
                          const glm::dvec3& x) {
  if (frame.directional)
    return e.centre == CentreKind::point ? glm::length(x - e.a) : distance_to_segment(x, e.a, e.b);
  return e.centre == CentreKind::point ? angle_between(x, e.a) : distance_to_arc(x, e.arc);
}

double max_distance_to_centre(const LightFrame& frame, const LightSpaceElement& e,
                              const glm::dvec3& x) {
  if (frame.directional)
    return e.centre == CentreKind::point
               ? glm::length(x - e.a)
               : std::max(glm::length(x - e.a), glm::length(x - e.b));  // convex in the plane
  return e.centre == CentreKind::point ? angle_between(x, e.a) : max_distance_to_arc(x, e.arc);
}

}  // namespace

LightFrame make_light_frame(const Case& c) {
  return make_light_frame(c, c.scale());
}

LightFrame make_light_frame(const Case& c, double scale) {
  if (!c.light) throw std::invalid_argument("metric: the case has no shadow light");
  LightFrame frame;
  frame.scale = scale;
  frame.margin = 0x1p-18 * frame.scale;
  frame.depth_slack = 1e-10 * frame.scale;
  if (c.light->kind == ShadowLightKind::point) {
    frame.light_position = glm::dvec3(c.light->position);
    frame.slack = 1e-10;
    return frame;
  }
  frame.directional = true;
  frame.slack = 1e-10 * frame.scale;
  frame.towards_light = glm::normalize(glm::dvec3(c.light->direction));
  const glm::dvec3 helper =
      std::fabs(frame.towards_light.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  frame.plane_x = glm::normalize(glm::cross(frame.towards_light, helper));
  frame.plane_y = glm::cross(frame.towards_light, frame.plane_x);
  return frame;
}

LightSpaceElement make_light_space_element(const LightFrame& frame, const ClusterVolume& volume,
                                           std::uint32_t cluster) {
  LightSpaceElement e;
  e.cluster = cluster;
  const double reach = volume.radius + frame.margin;
  const bool is_capsule = volume.shape == VolumeShape::capsule;
  if (frame.directional) {
    e.a = in_plane(frame, volume.axis_begin);
    e.b = in_plane(frame, volume.axis_end);
    e.centre = is_capsule ? CentreKind::segment : CentreKind::point;
    e.radius = reach + frame.slack;
    e.light_distance = std::min(directional_light_distance(frame, volume.axis_begin),
                                directional_light_distance(frame, volume.axis_end)) -
                       reach - frame.depth_slack;
    return e;
  }
  const glm::dvec3& light = frame.light_position;
  // The point of the centre closest to the light: where the capsule looks largest (Fig. 6c).
  const double closest = distance_to_segment(light, volume.axis_begin, volume.axis_end);
  e.light_distance = closest - reach - frame.depth_slack;
  if (closest <= reach * (1.0 + containment_tolerance)) {
    e.covers_everything = true;
    return e;
  }
  const double radius = angular_radius(reach, closest);
  e.a = glm::normalize(volume.axis_begin - light);
  e.b = glm::normalize(volume.axis_end - light);
  const double arc_length = angle_between(e.a, e.b);
  if (!is_capsule || arc_length < shortest_arc) {
    // A sphere, or a capsule seen end-on: a cone around the middle direction.
    e.centre = CentreKind::point;
    e.a = e.b = is_capsule ? glm::normalize(e.a + e.b) : e.a;
    e.radius = radius + (is_capsule ? 0.5 * arc_length : 0.0) + frame.slack;
    return e;
  }
  e.centre = CentreKind::segment;
  e.arc = make_great_arc(e.a, e.b);
  e.radius = radius + frame.slack;
  return e;
}

LightSpaceQuery make_light_space_query(const LightFrame& frame, const glm::dvec3& sample) {
  LightSpaceQuery q;
  if (frame.directional) {
    q.position = in_plane(frame, sample);
    q.light_distance = directional_light_distance(frame, sample);
    return q;
  }
  const glm::dvec3 from_light = sample - frame.light_position;
  q.light_distance = glm::length(from_light);
  q.at_light = !(q.light_distance > 0.0);
  if (!q.at_light) q.position = from_light / q.light_distance;
  return q;
}

double pivot_distance(const LightFrame& frame, const LightSpaceElement& pivot,
                      const LightSpaceQuery& query) {
  if (pivot.covers_everything) return -infinity;
  return distance_to_centre(frame, pivot, query.position) - pivot.radius;
}

DistanceBounds element_distance_bounds(const LightFrame& frame, const LightSpaceElement& pivot,
                                       const LightSpaceElement& element) {
  if (pivot.covers_everything) return {-infinity, -infinity};
  if (element.covers_everything) return {-infinity, infinity};
  double nearest_centre, farthest_centre;
  if (element.centre == CentreKind::point) {
    nearest_centre = farthest_centre = distance_to_centre(frame, pivot, element.a);
  } else if (pivot.centre == CentreKind::point) {
    // The pivot's point against the element's whole segment or arc.
    nearest_centre = distance_to_centre(frame, element, pivot.a);
    farthest_centre = max_distance_to_centre(frame, element, pivot.a);
  } else {
    // Segment against segment: every point of the element's centre is within its half length of
    // its midpoint, and a distance to a set changes by at most the distance moved.
    const glm::dvec3 midpoint =
        frame.directional ? 0.5 * (element.a + element.b) : element.arc.midpoint;
    const double half_length =
        frame.directional ? 0.5 * glm::length(element.b - element.a) : element.arc.half_length;
    const double to_midpoint = distance_to_centre(frame, pivot, midpoint);
    nearest_centre = std::max(0.0, to_midpoint - half_length);
    farthest_centre = to_midpoint + half_length;
  }
  return {nearest_centre - pivot.radius - element.radius,
          farthest_centre - pivot.radius + element.radius};
}

}  // namespace shadowcts::metric
