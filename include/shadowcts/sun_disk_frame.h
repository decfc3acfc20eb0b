#pragma once
// The sun disk of a case as soft-shadow oracles and algorithms place it: the unit direction
// towards the light, an orthonormal pair spanning the disk's plane, and the angular radius. Part
// of the case model (the light's definition), so the judge and the judged validate and orient it
// the same way; the disk is round, so nothing either computes depends on which pair it is.
#include <string>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"

namespace shadowcts {

struct SunDiskFrame {
  glm::dvec3 x_axis{1.0, 0.0, 0.0}, y_axis{0.0, 1.0, 0.0};  // orthonormal, perpendicular to d
  glm::dvec3 direction{0.0, 0.0, 1.0};                      // d, unit, towards the light
  double angular_radius = 0.0;                              // a, radians
  double tan_radius = 0.0;                                  // tan(a): the disk radius at distance 1
};

// Throws InputError (naming `source`) unless the light is a sun disk with a non-zero direction and
// an angular radius in (0, pi/2).
SunDiskFrame sun_disk_frame(const ShadowLight& light, const std::string& source);
// The case's light; InputError when the case has none or it is not a sun disk.
SunDiskFrame sun_disk_frame(const Case& c);

}  // namespace shadowcts
