#include "shadowcts/embree_scene.h"

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

}  // namespace

EmbreeScene::EmbreeScene(const Case& c, Contents) {
  device_ = rtcNewDevice("verbose=0");
  if (device_ == nullptr) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  // Robust mode: no triangle edge lets a ray through because of the fast path's rounding.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);

  RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  const std::size_t n = c.triangles.size();
  // Unshared vertices keep primID == triangle index and the exact float32 inputs.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  throw_on_error(device_, "allocating geometry buffers");
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& t = c.triangles[i];
    const glm::vec3* corners[3] = {&t.v0, &t.v1, &t.v2};
    for (int k = 0; k < 3; ++k) {
      vertices[9 * i + 3 * k + 0] = corners[k]->x;
      vertices[9 * i + 3 * k + 1] = corners[k]->y;
      vertices[9 * i + 3 * k + 2] = corners[k]->z;
      indices[3 * i + k] = unsigned(3 * i + k);
    }
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene_, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene_);
  throw_on_error(device_, "building the scene");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

}  // namespace shadowcts
