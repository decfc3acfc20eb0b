#include "shadowcts/case.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <glm/geometric.hpp>

#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double max_abs(const glm::vec3& v) {
  return std::max({std::fabs(double(v.x)), std::fabs(double(v.y)), std::fabs(double(v.z))});
}

// Zero length in the sense that the direction cannot be normalized: exactly zero, or so small
// that its squared length underflows.
bool unusable_direction(const glm::vec3& d) {
  const double len2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
  return !(len2 > 0.0) || !std::isfinite(len2);
}

void require_vec(const Case& c, const std::string& element, const glm::vec3& v) {
  if (!finite(v)) throw InputError(c.source, element, "coordinate is NaN or infinite");
}

void validate_camera(const Case& c) {
  const Camera& cam = c.camera;
  require_vec(c, "camera.position", cam.position);
  require_vec(c, "camera.target", cam.target);
  require_vec(c, "camera.up", cam.up);
  const glm::dvec3 forward = glm::dvec3(cam.target) - glm::dvec3(cam.position);
  if (!(glm::length(forward) > 0.0))
    throw InputError(c.source, "camera.target", "coincides with camera.position");
  if (unusable_direction(cam.up)) throw InputError(c.source, "camera.up", "has zero length");
  const glm::dvec3 up = glm::normalize(glm::dvec3(cam.up));
  if (glm::length(glm::cross(glm::normalize(forward), up)) < 1e-6)
    throw InputError(c.source, "camera.up", "is parallel to the viewing direction");
  if (!(cam.vertical_fov_degrees > 0.0f && cam.vertical_fov_degrees < 180.0f))
    throw InputError(c.source, "camera.fov_y_degrees",
                     "must lie in (0, 180), got " + std::to_string(cam.vertical_fov_degrees));
  if (!(std::isfinite(cam.near_plane) && std::isfinite(cam.far_plane) && cam.near_plane > 0.0f &&
        cam.far_plane > cam.near_plane))
    throw InputError(c.source, "camera.near/far", "need 0 < near < far, both finite");
  constexpr std::uint32_t max_side = 16384;
  if (cam.width == 0 || cam.height == 0 || cam.width > max_side || cam.height > max_side)
    throw InputError(c.source, "camera.width/height",
                     "resolution must be between 1 and " + std::to_string(max_side));
}

void validate_shadow_light(const Case& c, const ShadowLight& light) {
  switch (light.kind) {
    case ShadowLightKind::point:
      require_vec(c, "light.position", light.position);
      break;
    case ShadowLightKind::sun_disk:
      if (!(light.angular_radius > 0.0f && light.angular_radius < 1.5707963f))
        throw InputError(c.source, "light.angular_radius", "must lie in (0, 90) degrees");
      [[fallthrough]];
    case ShadowLightKind::directional:
      require_vec(c, "light.direction", light.direction);
      if (unusable_direction(light.direction))
        throw InputError(c.source, "light.direction", "has zero length");
      break;
  }
}

void validate_ranged_light(const Case& c, std::size_t index, const RangedLight& light) {
  const std::string element = "ranged_lights[" + std::to_string(index) + "]";
  require_vec(c, element + ".centre", light.centre);
  if (!(std::isfinite(light.range) && light.range > 0.0f))
    throw InputError(c.source, element + ".range", "must be finite and positive");
  if (light.kind == RangedLightKind::spot) {
    require_vec(c, element + ".direction", light.direction);
    if (unusable_direction(light.direction))
      throw InputError(c.source, element + ".direction", "has zero length");
    if (!(light.cone_half_angle > 0.0f && light.cone_half_angle < 3.1415926f))
      throw InputError(c.source, element + ".cone_half_angle", "must lie in (0, 180) degrees");
  }
}

void validate_parameters(const Case& c) {
  const RunParameters& p = c.parameters;
  if (!(std::isfinite(p.eps_rel) && p.eps_rel >= 0x1p-24 && p.eps_rel <= 0x1p-4))
    throw InputError(c.source, "parameters.eps_rel", "must lie in [2^-24, 2^-4]");
  if (p.repeats == 0 || p.repeats > 1000)
    throw InputError(c.source, "parameters.repeats", "must lie in [1, 1000]");
  if (p.threads > 4096) throw InputError(c.source, "parameters.threads", "is larger than 4096");
}

}  // namespace

double Case::triangle_scale() const {
  // A maximum of float magnitudes: exact in float, and independent of how the reduction splits
  // (a NaN coordinate is never taken, as in a sequential std::max). Read by every algorithm and
  // oracle at 1M triangles, so in parallel.
  const float largest = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, triangles.size(), 16384), 0.0f,
      [&](const tbb::blocked_range<std::size_t>& range, float m) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const Triangle& t = triangles[i];
          for (int k = 0; k < 3; ++k)
            m = std::max({m, std::fabs(t.v0[k]), std::fabs(t.v1[k]), std::fabs(t.v2[k])});
        }
        return m;
      },
      [](float a, float b) { return std::max(a, b); });
  return largest;
}

double Case::scale() const {
  double s = triangle_scale();
  s = std::max(s, max_abs(camera.position));
  if (light && light->kind == ShadowLightKind::point) s = std::max(s, max_abs(light->position));
  return s;
}

void validate(const Case& c) {
  if (c.meshes.empty()) throw InputError(c.source, "meshes", "the case has no mesh");
  if (c.triangles.empty()) throw InputError(c.source, "triangles", "the case has no triangle");
  for (std::size_t i = 0; i < c.meshes.size(); ++i)
    if (c.meshes[i].name.empty())
      throw InputError(c.source, "meshes[" + std::to_string(i) + "]", "has no name");
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    const Triangle& t = c.triangles[i];
    if (!finite(t.v0) || !finite(t.v1) || !finite(t.v2))
      throw InputError(c.source, "triangles[" + std::to_string(i) + "]",
                       "vertex coordinate is NaN or infinite");
    if (t.mesh >= c.meshes.size())
      throw InputError(c.source, "triangles[" + std::to_string(i) + "].mesh",
                       "mesh id " + std::to_string(t.mesh) + " out of range (" +
                           std::to_string(c.meshes.size()) + " meshes)");
  }
  validate_camera(c);
  if (c.light) validate_shadow_light(c, *c.light);
  for (std::size_t i = 0; i < c.ranged_lights.size(); ++i)
    validate_ranged_light(c, i, c.ranged_lights[i]);
  if (!c.light && c.ranged_lights.empty())
    throw InputError(c.source, "light", "the case has no light");
  validate_parameters(c);
  // Coordinates so large that float32 differences overflow make every predicate meaningless.
  const std::string beyond = "lies beyond 1e30 (the largest coordinate a case accepts)";
  if (max_abs(c.camera.position) > 1e30) throw InputError(c.source, "camera.position", beyond);
  if (c.light && c.light->kind == ShadowLightKind::point && max_abs(c.light->position) > 1e30)
    throw InputError(c.source, "light.position", beyond);
  if (c.triangle_scale() > 1e30)
    for (std::size_t i = 0; i < c.triangles.size(); ++i) {
      const Triangle& t = c.triangles[i];
      if (std::max({max_abs(t.v0), max_abs(t.v1), max_abs(t.v2)}) > 1e30)
        throw InputError(c.source, "triangles[" + std::to_string(i) + "]", "a corner " + beyond);
    }
}

}  // namespace shadowcts
