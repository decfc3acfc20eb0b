#include "shadowcts/embree_scene.h"

#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "shadowcts/case.h"

namespace shadowcts {
namespace {

void throw_on_error(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                             std::to_string(int(error)) + ")");
}

std::vector<std::uint32_t> every_triangle(const Case& c) {
  std::vector<std::uint32_t> all(c.triangles.size());
  std::iota(all.begin(), all.end(), 0u);
  return all;
}

}  // namespace

EmbreeScene::EmbreeScene(const Case& c, double magnitude)
    : EmbreeScene(c, every_triangle(c), nullptr, magnitude) {}

EmbreeScene::EmbreeScene(const Case& c, std::vector<std::uint32_t> triangles,
                         RTCFilterFunctionN occluded_filter, double magnitude)
    : triangles_(std::move(triangles)), primitives_(c.triangles.size(), absent) {
  if (magnitude > 0.0 && (magnitude < std::ldexp(1.0, embree_min_scale_exponent) ||
                          magnitude > std::ldexp(1.0, embree_max_scale_exponent))) {
    int binary_exponent = 0;
    std::frexp(magnitude, &binary_exponent);  // M = m 2^binary_exponent, m in [1/2, 1)
    factor_ = std::ldexp(1.0, -binary_exponent);
  }
  for (std::size_t i = 0; i < triangles_.size(); ++i) primitives_[triangles_[i]] = std::uint32_t(i);

  device_ = rtcNewDevice("verbose=0");
  if (device_ == nullptr) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  // Robust mode: no ray slips through a shared edge because of the fast path's rounding.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  const std::size_t n = triangles_.size();
  if (n != 0) {  // an empty scene answers every ray with a miss
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Unshared vertices keep the exact float32 inputs per triangle. Four floats per vertex:
    // Embree reads vertices with 16-byte loads.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 4 * sizeof(float), 3 * n));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    throw_on_error(device_, "allocating geometry buffers");
    for (std::size_t i = 0; i < n; ++i) {
      const Triangle& t = c.triangles[triangles_[i]];
      const glm::vec3* corners[3] = {&t.v0, &t.v1, &t.v2};
      for (std::size_t k = 0; k < 3; ++k) {
        float* vertex = vertices + 4 * (3 * i + k);
        const glm::vec3 corner = to_scene(glm::dvec3(*corners[k]));
        vertex[0] = corner.x;
        vertex[1] = corner.y;
        vertex[2] = corner.z;
        vertex[3] = 0.0f;
        indices[3 * i + k] = unsigned(3 * i + k);
      }
    }
    if (occluded_filter) rtcSetGeometryOccludedFilterFunction(geometry, occluded_filter);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(scene_, geometry, 0);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
  throw_on_error(device_, "building the scene");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace shadowcts
