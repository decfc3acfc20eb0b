#include "reference/ptsv/receiver_rule.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::ptsv {
namespace {

// n . q for n = e1 x e2, and |e1| x |e2| . |q| (componentwise absolute values): the sum of the
// magnitudes of the products, which bounds the rounding of the double evaluation.
struct PlaneValue {
  double value, magnitude;
};

PlaneValue plane_value(const glm::dvec3& e1, const glm::dvec3& e2, const glm::dvec3& q) {
  const glm::dvec3 n = glm::cross(e1, e2);
  const glm::dvec3 a1 = glm::abs(e1), a2 = glm::abs(e2);
  const glm::dvec3 m(a1.y * a2.z + a1.z * a2.y, a1.z * a2.x + a1.x * a2.z,
                     a1.x * a2.y + a1.y * a2.x);
  return {glm::dot(n, q), glm::dot(m, glm::abs(q))};
}

}  // namespace

double reject_reach(const geometry::ReceiverHalfSpace& h, const glm::dvec3& p) {
  if (!h.has_plane) return 0.0;  // every caster point counts
  constexpr double unknown = std::numeric_limits<double>::infinity();
  if (h.light_side == 0) return unknown;  // no caster counts
  // On or above the plane every point of the segment but p itself is strictly on the light's
  // side, and a hit at p lies on the caster's plane, at distance 0: never in an accepted node.
  if (geometry::light_side_of(h, p) >= 0) return 0.0;
  // f(x) = light_side * det[b - a, c - a, x - a]: f(p) < 0 < f(L) (or < Df, the slope along d).
  // The double evaluation from float inputs errs by a few 2^-53 of the magnitude (three rounded
  // differences, two products, three sums); 2^-48 covers it.
  const glm::dvec3 e1 = h.b - h.a, e2 = h.c - h.a;
  const double side = double(h.light_side);
  const PlaneValue fp = plane_value(e1, e2, p - h.a);
  const PlaneValue fl = plane_value(e1, e2, h.directional ? h.light : h.light - h.a);
  const double below = std::fabs(fp.value) + 0x1p-48 * fp.magnitude;
  const double towards_light = side * fl.value - 0x1p-48 * fl.magnitude;
  if (!(towards_light > 0.0)) return unknown;
  // Point light: the crossing of the plane lies at t = -f(p) / (f(L) - f(p)) < |f(p)| / f(L) of
  // the segment; directional: at t = -f(p) / Df along d.
  const double length = glm::length(h.directional ? h.light : h.light - p);
  const double reach = below / towards_light * length * (1.0 + 0x1p-40);
  return std::isfinite(reach) ? reach : unknown;
}

ReceiverRule::ReceiverRule(const Case& c, const ViewSamples& samples)
    : c_(c), slot_(c.triangles.size(), no_slot), reach_(samples.samples.size(), 0.0) {
  const HardShadowLight light = hard_shadow_light(c);
  const glm::dvec3 towards = light.directional ? light.direction : light.position;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class != SampleClass::regular) continue;
    if (s.receiver != no_receiver && slot_[s.receiver] == no_slot) {
      const Triangle& r = c.triangles[s.receiver];
      slot_[s.receiver] = std::uint32_t(half_spaces_.size());
      half_spaces_.push_back(geometry::receiver_half_space(
          glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2), light.directional, towards));
    }
    reach_[i] = ptsv::reject_reach(half_space(s.receiver), glm::dvec3(s.position));
  }
}

const geometry::ReceiverHalfSpace& ReceiverRule::half_space(std::uint32_t receiver) const {
  if (receiver == no_receiver) return no_plane_;
  if (receiver >= slot_.size() || slot_[receiver] == no_slot)
    throw std::logic_error("ptsv: the receiver of a sample that is not regular");
  return half_spaces_[slot_[receiver]];
}

bool ReceiverRule::caster_counts(const ShadowVolume& volume, const ViewSample& sample) const {
  if (sample.receiver == volume.triangle) return false;
  const Triangle& t = c_.triangles[volume.triangle];
  return geometry::caster_counts(half_space(sample.receiver), glm::dvec3(sample.position),
                                 glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2));
}

}  // namespace shadowcts::ptsv
