#include "shadowcts/view_samples.h"
#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/geometry/exact_orientation.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "shadowcts/case.h"
#include "shadowcts/embree_scene.h"
#include "shadowcts/errors.h"
#include "shadowcts/phase_progress.h"

namespace shadowcts {
namespace {

// Orientation against the shadow light. Without a shadow light (light-assignment cases) every
// hit is regular; the light-assignment normal rule works per light. A light exactly in the
// receiver's plane (decided exactly) is grazing: no point is strictly on its side of the plane,
// so the receiver half-space rule has nothing to say, and the sample is not compared.
SampleClass classify(const Case& c, const glm::vec3& position, const glm::vec3& normal,
                     const Triangle& receiver) {
  if (!c.light) return SampleClass::regular;
  glm::dvec3 to_light;
  const bool point = c.light->kind == ShadowLightKind::point;
  if (point)
    to_light = glm::dvec3(c.light->position) - glm::dvec3(position);
  else
    to_light = glm::dvec3(c.light->direction);
  if (!(glm::dot(glm::dvec3(normal), to_light) > 0.0)) return SampleClass::back_facing;
  const glm::dvec3 a(receiver.v0), b(receiver.v1), cc(receiver.v2);
  const int side = point ? geometry::orientation(a, b, cc, glm::dvec3(c.light->position))
                         : geometry::orientation_towards(a, b, cc, glm::dvec3(c.light->direction));
  return side != 0 ? SampleClass::regular : SampleClass::back_facing;
}

}  // namespace

std::size_t ViewSamples::count(SampleClass c) const {
  std::size_t n = 0;
  for (const ViewSample& s : samples) n += s.sample_class == c;
  return n;
}

ViewSamples generate_view_samples(const Case& c) {
  const Camera& cam = c.camera;
  const CameraFrame frame = camera_frame(cam);
  // The rays start at the eye: it and the triangles set the scene's magnitude (not a far point
  // light, which no primary ray reaches).
  const glm::dvec3& eye = frame.origin;
  const EmbreeScene scene(
      c, std::max({c.triangle_scale(), std::fabs(eye.x), std::fabs(eye.y), std::fabs(eye.z)}));

  ViewSamples out;
  out.width = cam.width;
  out.height = cam.height;
  out.samples.resize(std::size_t(cam.width) * cam.height);

  // Rays in the scene's units (a power of two away from the case's outside Embree's range): the
  // barycentrics and the triangle hit are the same.
  const glm::vec3 origin = scene.to_scene(frame.origin);
  // Rows are independent and every sample is written by exactly one task: deterministic.
  phase_progress::begin(cam.height, "pixel rows");
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, cam.height), [&](const auto& rows) {
    phase_progress::advance(rows.size());
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::uint32_t y = rows.begin(); y != rows.end(); ++y) {
      for (std::uint32_t x = 0; x < cam.width; ++x) {
        const double sx = (2.0 * (x + 0.5) / cam.width - 1.0) * frame.tan_half_fov * frame.aspect;
        const double sy = (1.0 - 2.0 * (y + 0.5) / cam.height) * frame.tan_half_fov;
        const glm::dvec3 dir = glm::normalize(frame.forward + sx * frame.right + sy * frame.up);
        // Primary rays start at the near plane and end at the far plane along the view axis.
        const double cos_axis = glm::dot(dir, frame.forward);

        RTCRayHit hit{};
        hit.ray.org_x = origin.x;
        hit.ray.org_y = origin.y;
        hit.ray.org_z = origin.z;
        hit.ray.dir_x = float(dir.x);
        hit.ray.dir_y = float(dir.y);
        hit.ray.dir_z = float(dir.z);
        hit.ray.tnear = scene.to_scene(cam.near_plane / cos_axis);
        hit.ray.tfar = scene.to_scene(cam.far_plane / cos_axis);
        hit.ray.mask = 0xFFFFFFFFu;
        hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene.handle(), &context, &hit);

        ViewSample& s = out.samples[std::size_t(y) * cam.width + x];
        s.pixel_x = x;
        s.pixel_y = y;
        if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;  // sky

        const std::uint32_t tri_index = scene.triangle_of_primitive(hit.hit.primID);
        const Triangle& t = c.triangles[tri_index];
        // The position is interpolated from the receiver's own vertices (not o + t d), so it lies
        // on the receiver within float rounding of the barycentric combination.
        const double u = hit.hit.u, v = hit.hit.v;
        const glm::dvec3 p =
            (1.0 - u - v) * glm::dvec3(t.v0) + u * glm::dvec3(t.v1) + v * glm::dvec3(t.v2);
        glm::dvec3 n =
            glm::cross(glm::dvec3(t.v1) - glm::dvec3(t.v0), glm::dvec3(t.v2) - glm::dvec3(t.v0));
        const double len = glm::length(n);
        if (!(len > 0.0)) continue;  // Embree does not report zero-area hits; keep it sky if so
        n /= len;
        if (glm::dot(n, dir) > 0.0) n = -n;  // face the camera
        s.position = glm::vec3(p);
        s.normal = glm::vec3(n);
        s.receiver = tri_index;
        s.sample_class = classify(c, s.position, s.normal, t);
      }
    }
  });
  return out;
}

void classify_samples(const Case& c, ViewSamples& samples, const std::string& source) {
  if (samples.width != c.camera.width || samples.height != c.camera.height)
    throw InputError(source, "resolution",
                     std::to_string(samples.width) + "x" + std::to_string(samples.height) +
                         " differs from the case camera's " + std::to_string(c.camera.width) + "x" +
                         std::to_string(c.camera.height));
  for (ViewSample& s : samples.samples) {
    if (s.sample_class == SampleClass::sky) continue;
    if (s.receiver >= c.triangles.size())
      throw InputError(source,
                       "channel id, pixel (" + std::to_string(s.pixel_x) + ", " +
                           std::to_string(s.pixel_y) + ")",
                       "receiver id " + std::to_string(s.receiver) + " out of range (" +
                           std::to_string(c.triangles.size()) + " triangles)");
    s.sample_class = classify(c, s.position, s.normal, c.triangles[s.receiver]);
  }
}

}  // namespace shadowcts
