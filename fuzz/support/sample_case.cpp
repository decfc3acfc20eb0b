#include "sample_case.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace shadowcts::fuzzing {

std::uint32_t SampleCase::begin_mesh(const std::string& name, bool closed, bool caster) {
  c.meshes.push_back(Mesh{name, closed, caster});
  mesh_ = std::uint32_t(c.meshes.size() - 1);
  return mesh_;
}

std::uint32_t SampleCase::add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& d) {
  c.triangles.push_back(Triangle{a, b, d, mesh_});
  return std::uint32_t(c.triangles.size() - 1);
}

glm::dvec3 towards_light(const ShadowLight& light, const glm::vec3& position) {
  return light.kind == ShadowLightKind::point ? glm::dvec3(light.position) - glm::dvec3(position)
                                              : glm::dvec3(light.direction);
}

void SampleCase::add_sample(const glm::vec3& position, std::uint32_t receiver) {
  ViewSample s;
  s.position = position;
  // Any normal with a positive dot product with the light direction makes a regular sample; the
  // dominant axis of that direction has one, and it is exact.
  const glm::dvec3 to_light = towards_light(*c.light, position);
  const glm::dvec3 magnitude = glm::abs(to_light);
  const int axis = magnitude.x >= magnitude.y && magnitude.x >= magnitude.z ? 0
                   : magnitude.y >= magnitude.z                             ? 1
                                                                            : 2;
  s.normal[axis] = to_light[axis] >= 0.0 ? 1.0f : -1.0f;
  s.receiver = receiver;
  s.pixel_x = std::uint32_t(samples.samples.size());
  s.pixel_y = 0;
  s.sample_class = SampleClass::regular;
  samples.samples.push_back(s);
}

void SampleCase::finish() {
  if (!explicit_samples) {
    classify_samples(c, samples, c.source);
    return;
  }
  samples.width = std::uint32_t(samples.samples.size());
  samples.height = 1;
  // The camera matters to algorithms that count shadow volumes from the eye (z-pass is wrong by
  // design when the eye is in shadow), so it sits where no shadow volume reaches: near the point
  // light, or beyond the whole scene towards a directional light. It looks at the scene's centre
  // and its near/far planes scale with the scene.
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const Triangle& t : c.triangles)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo = glm::min(lo, glm::dvec3(v));
      hi = glm::max(hi, glm::dvec3(v));
    }
  for (const ViewSample& s : samples.samples) {
    lo = glm::min(lo, glm::dvec3(s.position));
    hi = glm::max(hi, glm::dvec3(s.position));
  }
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double extent = std::max(glm::length(hi - lo), 1e-30);
  Camera& camera = c.camera;
  if (c.light->kind == ShadowLightKind::point) {
    // Between the light and the scene, closer to the light than any caster's box: not behind
    // any caster, and off the light itself (where every volume's side planes meet).
    const glm::dvec3 light(c.light->position);
    double nearest = INFINITY;
    for (const Triangle& t : c.triangles) {
      if (!c.meshes[t.mesh].caster) continue;
      const glm::dvec3 box_lo =
          glm::min(glm::dvec3(t.v0), glm::min(glm::dvec3(t.v1), glm::dvec3(t.v2)));
      const glm::dvec3 box_hi =
          glm::max(glm::dvec3(t.v0), glm::max(glm::dvec3(t.v1), glm::dvec3(t.v2)));
      nearest = std::min(nearest, glm::length(glm::max(glm::dvec3(0.0),
                                                       glm::max(box_lo - light, light - box_hi))));
    }
    const glm::dvec3 towards = centre - light;
    const double length = glm::length(towards);
    const double step = std::min(0.5 * nearest, 0.5 * length);
    camera.position = length > 0.0 && std::isfinite(step)
                          ? glm::vec3(light + step * (towards / length))
                          : c.light->position;
  } else {
    camera.position =
        glm::vec3(centre + 2.0 * extent * glm::normalize(glm::dvec3(c.light->direction)));
  }
  camera.target = glm::vec3(centre);
  if (camera.target == camera.position)
    camera.target = glm::vec3(centre - glm::dvec3(0, 0, extent));
  const glm::dvec3 forward = glm::dvec3(camera.target) - glm::dvec3(camera.position);
  camera.up = glm::length(glm::cross(glm::normalize(forward), glm::dvec3(0, 1, 0))) > 1e-3
                  ? glm::vec3(0.0f, 1.0f, 0.0f)
                  : glm::vec3(1.0f, 0.0f, 0.0f);
  camera.near_plane = float(extent * 1e-6);
  camera.far_plane = float(extent * 1e3);
  camera.width = samples.width;
  camera.height = 1;
  classify_samples(c, samples, c.source);
}

}  // namespace shadowcts::fuzzing
