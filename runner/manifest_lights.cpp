#include "manifest_lights.h"

#include <cmath>

namespace shadowcts {
namespace {

using Json = nlohmann::ordered_json;

// The loader's conversion (case_manifest.cpp).
constexpr double degrees_to_radians = 3.14159265358979323846 / 180.0;

// JSON numbers are written as doubles with round-trip precision, so a float survives exactly.
Json vec3_json(const glm::vec3& v) {
  return Json::array({double(v.x), double(v.y), double(v.z)});
}

// Degrees that the loader turns back into exactly `radians`: the quotient, stepped by ulps of the
// double until float(degrees * degrees_to_radians) is the float again (a step or two at most).
double degrees_of(float radians) {
  double degrees = double(radians) / degrees_to_radians;
  for (int step = 0; step < 64; ++step) {
    const float back = static_cast<float>(degrees * degrees_to_radians);
    if (back == radians) break;
    degrees = std::nextafter(degrees, back < radians ? INFINITY : -INFINITY);
  }
  return degrees;
}

}  // namespace

Json shadow_light_json(const ShadowLight& light) {
  switch (light.kind) {
    case ShadowLightKind::point:
      return {{"type", "point"}, {"position", vec3_json(light.position)}};
    case ShadowLightKind::directional:
      return {{"type", "directional"}, {"direction", vec3_json(light.direction)}};
    case ShadowLightKind::sun_disk:
      return {{"type", "sun"},
              {"direction", vec3_json(light.direction)},
              {"angular_radius_degrees", degrees_of(light.angular_radius)}};
  }
  return {};
}

Json ranged_lights_json(const std::vector<RangedLight>& lights) {
  Json ranged = Json::array();
  for (const RangedLight& r : lights) {
    Json light = {{"type", r.kind == RangedLightKind::sphere ? "sphere" : "spot"},
                  {"centre", vec3_json(r.centre)},
                  {"range", double(r.range)}};
    if (r.kind == RangedLightKind::spot) {
      light["direction"] = vec3_json(r.direction);
      light["cone_half_angle_degrees"] = degrees_of(r.cone_half_angle);
    }
    ranged.push_back(light);
  }
  return ranged;
}

}  // namespace shadowcts
