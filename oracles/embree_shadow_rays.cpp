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

double max_abs(const glm::dvec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

}  // namespace

struct EmbreeShadowRays::Scene {
  HardShadowLight light;
  EmbreeScene casters;
  double extent;  // the triangles' largest absolute coordinate, in the scene's units

  explicit Scene(const Case& c) : Scene(c, c.triangle_scale()) {}
  Scene(const Case& c, double triangle_scale)
      : light(hard_shadow_light(c)),
        casters(c, shadow_casters(c), filter_hits, triangle_scale),
        extent(triangle_scale * casters.factor()) {}
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
  const glm::dvec3 from = glm::dvec3(origin) * s.casters.factor();
  const glm::vec3 start(from);
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
    // Up to the light: t = 1 along the (float-rounded) vector to it.
    const glm::vec3 to_light = s.casters.to_scene(s.light.position) - start;
    ray.dir_x = to_light.x;
    ray.dir_y = to_light.y;
    ray.dir_z = to_light.z;
    ray.tfar = 1.0f;
  }
  // A point light far beyond the triangles (their magnitude sized the scene, not S), or an origin
  // far outside them (the band moves samples by up to 2^-10 S): Embree asserts beyond 1.8e18 and
  // its products overflow. The ray is taken in double instead: its part outside the box of twice
  // the triangles' extent meets none of them, so it starts where it enters that box, and its
  // direction is scaled by a power of two, tfar by the inverse (Embree's tests are linear in the
  // direction: the same decisions).
  constexpr double far = 0x1p40;
  if (!(max_abs(from) <= far && max_abs(glm::dvec3(ray.dir_x, ray.dir_y, ray.dir_z)) <= far)) {
    glm::dvec3 o = from;
    const glm::dvec3 d =
        s.light.directional ? s.light.direction : s.light.position * s.casters.factor() - from;
    double t_end = s.light.directional ? std::numeric_limits<double>::infinity() : 1.0;
    const double half = 2.0 * s.extent;
    double t_in = 0.0, t_out = t_end;
    for (int k = 0; k < 3; ++k) {
      if (d[k] == 0.0) {
        if (std::fabs(o[k]) > half) return false;
        continue;
      }
      const double a = (-half - o[k]) / d[k], b = (half - o[k]) / d[k];
      t_in = std::max(t_in, std::min(a, b));
      t_out = std::min(t_out, std::max(a, b));
    }
    if (!(t_in <= t_out)) return false;
    o += t_in * d;
    t_end -= t_in;
    int exponent = 0;
    std::frexp(max_abs(d), &exponent);
    ray.org_x = float(o.x);
    ray.org_y = float(o.y);
    ray.org_z = float(o.z);
    ray.dir_x = float(std::ldexp(d.x, -exponent));
    ray.dir_y = float(std::ldexp(d.y, -exponent));
    ray.dir_z = float(std::ldexp(d.z, -exponent));
    ray.tfar = float(std::ldexp(t_end, exponent));
  }
  ray.mask = 0xffffffffu;
  ray.flags = 0;
  rtcOccluded1(s.casters.handle(), &context.context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace shadowcts
