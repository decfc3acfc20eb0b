#include "reference/embree/shadow_ray_packets.h"

#include <array>
#include <limits>
#include <stdexcept>

#include <embree3/rtcore.h>

#include "reference/sample_half_space.h"
#include "shadowcts/geometry/receiver_half_space.h"

namespace shadowcts {
namespace {

std::vector<std::uint32_t> shadow_casters(const Case& c) {
  std::vector<std::uint32_t> casters;
  for (std::size_t i = 0; i < c.triangles.size(); ++i)
    if (casts_shadow(c, i)) casters.push_back(std::uint32_t(i));
  return casters;
}

// What the filter needs of each ray of a packet, found through the ray's id (its slot here):
// Embree hands the context pointer back unchanged, but may present the rays to the filter in
// groups other than the packet, so the lane index alone does not name the sample.
struct PacketContext {
  RTCIntersectContext context;  // first member: the filter casts the context pointer back
  const Case* c = nullptr;
  const EmbreeScene* scene = nullptr;
  std::array<std::uint32_t, ShadowRayPackets::width> receiver_primitive{};
  std::array<geometry::ReceiverHalfSpace, ShadowRayPackets::width> half_space{};
  std::array<glm::dvec3, ShadowRayPackets::width> position{};
};

void filter_hits(const RTCFilterFunctionNArguments* args) {
  const auto* packet = reinterpret_cast<const PacketContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned slot = RTCRayN_id(args->ray, args->N, i);
    const unsigned primitive = RTCHitN_primID(args->hit, args->N, i);
    if (primitive == packet->receiver_primitive[slot]) {
      args->valid[i] = 0;
      continue;
    }
    const Triangle& t = packet->c->triangles[packet->scene->triangle_of_primitive(primitive)];
    if (!geometry::caster_counts(packet->half_space[slot], packet->position[slot], glm::dvec3(t.v0),
                                 glm::dvec3(t.v1), glm::dvec3(t.v2)))
      args->valid[i] = 0;
  }
}

}  // namespace

ShadowRayPackets::ShadowRayPackets(const Case& c)
    : case_(c), light_(hard_shadow_light(c)), casters_(c, shadow_casters(c), filter_hits, 0.0) {}

void ShadowRayPackets::trace(const ViewSamples& samples, std::span<const std::uint32_t> indices,
                             std::vector<std::uint8_t>& shadowed) const {
  if (indices.size() > width) throw std::invalid_argument("ShadowRayPackets: packet too wide");
  PacketContext packet;
  rtcInitIntersectContext(&packet.context);
  packet.context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  packet.c = &case_;
  packet.scene = &casters_;
  alignas(64) int valid[width];
  alignas(64) RTCRay16 rays{};
  for (std::size_t k = 0; k < width; ++k) {
    valid[k] = 0;
    if (k >= indices.size()) continue;
    const ViewSample& s = samples.samples[indices[k]];
    valid[k] = -1;
    packet.receiver_primitive[k] = casters_.primitive_of_triangle(s.receiver);
    packet.half_space[k] = sample_half_space(case_, light_, s);
    packet.position[k] = glm::dvec3(s.position);
    rays.org_x[k] = s.position.x;
    rays.org_y[k] = s.position.y;
    rays.org_z[k] = s.position.z;
    rays.tnear[k] = 0.0f;
    if (light_.directional) {
      rays.dir_x[k] = float(light_.direction.x);
      rays.dir_y[k] = float(light_.direction.y);
      rays.dir_z[k] = float(light_.direction.z);
      rays.tfar[k] = std::numeric_limits<float>::infinity();
    } else {
      // The segment is t in [0, 1] along the float-rounded vector to the light.
      rays.dir_x[k] = float(light_.position.x) - s.position.x;
      rays.dir_y[k] = float(light_.position.y) - s.position.y;
      rays.dir_z[k] = float(light_.position.z) - s.position.z;
      rays.tfar[k] = 1.0f;
    }
    rays.mask[k] = 0xffffffffu;
    rays.id[k] = unsigned(k);
    rays.flags[k] = 0;
  }
  rtcOccluded16(valid, casters_.handle(), &packet.context, &rays);
  for (std::size_t k = 0; k < indices.size(); ++k)
    shadowed[indices[k]] = rays.tfar[k] == -std::numeric_limits<float>::infinity() ? 1 : 0;
}

}  // namespace shadowcts
