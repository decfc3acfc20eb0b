#include "reference/stencil/receiver_rule.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

#include "reference/stencil/robust_orientation.h"

namespace shadowcts::stencil {

RejectBox reject_box(const geometry::ReceiverHalfSpace& h, const glm::dvec3& p) {
  // With D(x) = det[b - a, c - a, x - a] (a, b, c the receiver), the segment p + t (L - p) crosses
  // the plane at t0 = D(p) / (D(p) - D(L)), and D(p), D(L) have opposite signs (or D(p) = 0):
  // t0 <= |D(p)| / |D(L)|. The ray p + t d crosses it at t0 = |D(p)| / |D(d)|. Upper bounds of the
  // numerators and lower bounds of the denominators come from the determinants' error bounds.
  constexpr double epsilon = std::numeric_limits<double>::epsilon();
  const glm::dvec3 zero(0.0);
  const DeterminantEstimate dp = estimate_determinant(h.b, h.a, h.c, h.a, p, h.a);
  const DeterminantEstimate dl = h.directional
                                     ? estimate_determinant(h.b, h.a, h.c, h.a, h.light, zero)
                                     : estimate_determinant(h.b, h.a, h.c, h.a, h.light, h.a);
  const double numerator = std::fabs(dp.value) + dp.error;
  const double denominator = std::fabs(dl.value) - dl.error;
  // Each rounding above and the division's is at most epsilon / 2 relative.
  double t = denominator > 0.0 ? numerator / denominator * (1.0 + 8.0 * epsilon)
                               : std::numeric_limits<double>::infinity();
  glm::dvec3 step;
  if (h.directional) {
    if (!std::isfinite(t)) return {};
    step = t * h.light;
  } else {
    if (!(t <= 1.0)) t = 1.0;  // the segment ends at L
    step = t * (h.light - p);
  }
  const glm::dvec3 q = p + step;
  // The exact end p + t (L - p) (or p + t d) lies within a few roundings of q.
  const glm::dvec3 margin = 8.0 * epsilon * (glm::abs(step) + glm::abs(q)) +
                            glm::dvec3(std::numeric_limits<double>::denorm_min());
  RejectBox box;
  box.lo = glm::min(p, q) - margin;
  box.hi = glm::max(p, q) + margin;
  box.bounded = std::isfinite(box.lo.x) && std::isfinite(box.lo.y) && std::isfinite(box.lo.z) &&
                std::isfinite(box.hi.x) && std::isfinite(box.hi.y) && std::isfinite(box.hi.z);
  return box;
}

StencilReceiverRule::StencilReceiverRule(const Case& c, const HardShadowLight& light,
                                         const Occluders& occluders, const Extrusion& extrusion,
                                         CountingMode mode, const glm::dvec3& eye)
    : c_(c),
      light_(light),
      occluders_(occluders),
      extrusion_(extrusion),
      mode_(mode),
      eye_(eye),
      tree_(occluders.caps) {}

RuleOutcome StencilReceiverRule::rejected(std::uint32_t receiver, const glm::dvec3& p,
                                          FaceTally& tally) const {
  RuleOutcome out;
  const Triangle& r = c_.triangles[receiver];
  const geometry::ReceiverHalfSpace h = geometry::receiver_half_space(
      glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2), light_.directional,
      light_.directional ? light_.direction : light_.position);
  if (!h.has_plane) return out;  // no plane, no rule
  if (h.light_side == 0) {
    out.every_cap_rejected = true;
    return out;
  }
  // The whole segment (ray) lies strictly on the light's side: the rule rejects nothing.
  if (geometry::light_side_of(h, p) > 0) return out;
  const auto consider = [&](std::uint32_t k) {
    const LightCap& cap = occluders_.caps[k];
    if (cap.triangle == receiver) return;  // subtracted by the caller
    ++out.candidates;
    const geometry::CasterReach reach = geometry::caster_reach(h, cap.v[0], cap.v[1], cap.v[2]);
    if (reach == geometry::CasterReach::every_hit) return;
    const int own = count_own_volume(cap, extrusion_, mode_, eye_, p, light_, tally);
    if (own == 0) return;
    // Counted, so the cap meets the segment: hit_on_light_side's precondition.
    if (reach == geometry::CasterReach::straddles &&
        geometry::hit_on_light_side(h, p, cap.v[0], cap.v[1], cap.v[2]))
      return;
    out.rejected += own;
  };
  const RejectBox box = reject_box(h, p);
  if (box.bounded)
    tree_.for_each_overlapping(box.lo, box.hi, consider);
  else
    for (std::uint32_t k = 0; k < occluders_.caps.size(); ++k) consider(k);
  return out;
}

}  // namespace shadowcts::stencil
