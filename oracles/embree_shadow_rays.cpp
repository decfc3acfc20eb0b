#include "oracles/embree_shadow_rays.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>

#include "oracles/exact_segment_triangle.h"
#include "shadowcts/embree_scene.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

// Passed through rtcOccluded1 to the filter: Embree hands the context pointer back unchanged, so
// the filter can read the sample's receiver.
struct ReceiverContext {
  RTCIntersectContext context;  // first member: the filter casts the context pointer back
  unsigned receiver_primitive;
  const EmbreeScene* scene;
  EmbreeShadowRays::CasterRule rule;
};

// Rejects hits on the receiver triangle (it never shadows its own sample) and hits on casters
// that the rule does not let count.
void filter_hits(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const ReceiverContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned primitive = RTCHitN_primID(args->hit, args->N, i);
    if (primitive == context->receiver_primitive) {
      args->valid[i] = 0;
    } else if (context->rule.counts &&
               !context->rule.counts(context->rule.state,
                                     context->scene->triangle_of_primitive(primitive))) {
      args->valid[i] = 0;
    }
  }
}

std::vector<std::uint32_t> shadow_casters(const Case& c) {
  // Non-casters and zero-area triangles never shadow: they are left out of the scene instead
  // of being filtered ray by ray.
  std::vector<std::uint32_t> casters;
  for (std::size_t i = 0; i < c.triangles.size(); ++i)
    if (oracle_casts_shadow(c, i)) casters.push_back(std::uint32_t(i));
  return casters;
}

}  // namespace

struct EmbreeShadowRays::Scene {
  HardShadowLight light;
  EmbreeScene casters;

  explicit Scene(const Case& c)
      : light(hard_shadow_light(c)),
        casters(c, shadow_casters(c), filter_hits, c.triangle_scale()) {}
};

EmbreeShadowRays::EmbreeShadowRays(const Case& c) : scene_(std::make_unique<Scene>(c)) {}

EmbreeShadowRays::~EmbreeShadowRays() = default;

bool EmbreeShadowRays::occluded(const glm::vec3& origin, std::uint32_t receiver,
                                const CasterRule& rule) const {
  const Scene& s = *scene_;
  ReceiverContext context;
  rtcInitIntersectContext(&context.context);
  context.receiver_primitive = s.casters.primitive_of_triangle(receiver);
  context.scene = &s.casters;
  context.rule = rule;

  // In the scene's units (EmbreeScene: a power of two away outside Embree's range).
  const glm::vec3 start = s.casters.to_scene(glm::dvec3(origin));
  RTCRay ray{};
  ray.org_x = start.x;
  ray.org_y = start.y;
  ray.org_z = start.z;
  ray.tnear = 0.0f;
  if (s.light.directional) {
    ray.dir_x = float(s.light.direction.x);
    ray.dir_y = float(s.light.direction.y);
    ray.dir_z = float(s.light.direction.z);
    ray.tfar = std::numeric_limits<float>::infinity();
  } else {
    // Up to the light: t = 1 along the (float-rounded) vector to it. A light far beyond the
    // triangles (the scene's magnitude leaves it out) gets that vector scaled by a power of two
    // and tfar = its inverse (Embree's tests are linear in the direction: the same decisions),
    // so the direction stays inside Embree's range (it asserts beyond 1.8e18) and finite.
    const glm::vec3 to_light = s.casters.to_scene(s.light.position) - start;
    ray.dir_x = to_light.x;
    ray.dir_y = to_light.y;
    ray.dir_z = to_light.z;
    ray.tfar = 1.0f;
    if (!(std::max({std::fabs(to_light.x), std::fabs(to_light.y), std::fabs(to_light.z)}) <=
          0x1p40f)) {
      const glm::dvec3 far = s.light.position * s.casters.factor() - glm::dvec3(start);
      int exponent = 0;
      std::frexp(std::max({std::fabs(far.x), std::fabs(far.y), std::fabs(far.z)}), &exponent);
      ray.dir_x = float(std::ldexp(far.x, -exponent));
      ray.dir_y = float(std::ldexp(far.y, -exponent));
      ray.dir_z = float(std::ldexp(far.z, -exponent));
      ray.tfar = float(std::ldexp(1.0, exponent));
    }
  }
  ray.mask = 0xffffffffu;
  ray.flags = 0;
  rtcOccluded1(s.casters.handle(), &context.context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace shadowcts
