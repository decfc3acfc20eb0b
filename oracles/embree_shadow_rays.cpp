#include "oracles/embree_shadow_rays.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "oracles/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

constexpr unsigned no_primitive = std::numeric_limits<unsigned>::max();

// Passed through rtcOccluded1 to the filter: Embree hands the context pointer back unchanged, so
// the filter can read the sample's receiver.
struct ReceiverContext {
  RTCIntersectContext context;  // first member: the filter casts the context pointer back
  unsigned receiver_primitive;
};

// Rejects hits on the receiver triangle: it never shadows its own sample.
void ignore_receiver(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const ReceiverContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (RTCHitN_primID(args->hit, args->N, i) == context->receiver_primitive) args->valid[i] = 0;
  }
}

void throw_on_error(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                             std::to_string(int(error)) + ")");
}

}  // namespace

struct EmbreeShadowRays::Scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  HardShadowLight light;
  std::vector<unsigned> primitive_of_triangle;  // no_primitive for non-casters

  ~Scene() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

EmbreeShadowRays::EmbreeShadowRays(const Case& c) : scene_(std::make_unique<Scene>()) {
  Scene& s = *scene_;
  s.light = hard_shadow_light(c);
  // Non-casters and zero-area triangles never shadow: they are left out of the scene instead
  // of being filtered ray by ray.
  std::vector<std::uint32_t> casters;
  s.primitive_of_triangle.assign(c.triangles.size(), no_primitive);
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    if (casts_shadow(c, i)) {
      s.primitive_of_triangle[i] = unsigned(casters.size());
      casters.push_back(std::uint32_t(i));
    }
  }

  s.device = rtcNewDevice("verbose=0");
  if (s.device == nullptr) throw std::runtime_error("Embree: cannot create a device");
  s.scene = rtcNewScene(s.device);
  rtcSetSceneFlags(s.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(s.scene, RTC_BUILD_QUALITY_HIGH);
  const std::size_t n = casters.size();
  if (n == 0) {  // nothing casts a shadow: an empty scene answers every ray with "lit"
    rtcCommitScene(s.scene);
    throw_on_error(s.device, "building the scene");
    return;
  }
  RTCGeometry geometry = rtcNewGeometry(s.device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Four floats per vertex: Embree reads vertices with 16-byte loads.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 4 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  throw_on_error(s.device, "allocating geometry buffers");
  for (std::size_t i = 0; i < n; ++i) {
    const Triangle& t = c.triangles[casters[i]];
    const glm::vec3* corners[3] = {&t.v0, &t.v1, &t.v2};
    for (std::size_t k = 0; k < 3; ++k) {
      float* vertex = vertices + 4 * (3 * i + k);
      vertex[0] = corners[k]->x;
      vertex[1] = corners[k]->y;
      vertex[2] = corners[k]->z;
      vertex[3] = 0.0f;
      indices[3 * i + k] = unsigned(3 * i + k);
    }
  }
  rtcSetGeometryOccludedFilterFunction(geometry, ignore_receiver);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(s.scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(s.scene);
  throw_on_error(s.device, "building the scene");
}

EmbreeShadowRays::~EmbreeShadowRays() = default;

bool EmbreeShadowRays::occluded(const glm::vec3& origin, std::uint32_t receiver) const {
  const Scene& s = *scene_;
  ReceiverContext context;
  rtcInitIntersectContext(&context.context);
  context.receiver_primitive =
      receiver < s.primitive_of_triangle.size() ? s.primitive_of_triangle[receiver] : no_primitive;

  RTCRay ray{};
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.tnear = 0.0f;
  if (s.light.directional) {
    ray.dir_x = float(s.light.direction.x);
    ray.dir_y = float(s.light.direction.y);
    ray.dir_z = float(s.light.direction.z);
    ray.tfar = std::numeric_limits<float>::infinity();
  } else {
    // Up to the light: t = 1 along the (float-rounded) vector to it.
    ray.dir_x = float(s.light.position.x) - origin.x;
    ray.dir_y = float(s.light.position.y) - origin.y;
    ray.dir_z = float(s.light.position.z) - origin.z;
    ray.tfar = 1.0f;
  }
  ray.mask = 0xffffffffu;
  ray.flags = 0;
  rtcOccluded1(s.scene, &context.context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace shadowcts
