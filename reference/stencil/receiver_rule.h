#pragma once
// The receiver half-space rule (DESIGN.md, "Cases and ground truth") in the stencil count. The
// count of all volumes is the sum, over the caps, of each cap's own closed volume
// (own_volume_faces): for a closed mesh the side quads between two front caps cancel, so its one
// silhouette volume stands for its front caps, and an open mesh's merged volumes for all its
// caps. The rule removes the caps it rejects: sample p of receiver r is shadowed iff
//   count(p) - own(r, p) - sum of own(T, p) over the caps T != r with !caster_counts(h_p, p, T)
// is non-zero. Only caps that meet the segment (ray) from p towards the light count at all, and a
// rejected one meets it at no point strictly on the light's side of plane(r): within the part of
// the segment from p to where it crosses that plane, which is empty when p lies strictly on the
// light's side and tiny for a rounded sample (about an ulp below its plane) unless the light
// grazes the plane. A box around that part (reject_box) and the cap tree give every cap that may
// be rejected; caster_reach() sorts them out first, and own(T, p) and hit_on_light_side() are
// asked only for those that are not hit strictly on the light's side throughout.
//
// Closed meshes keep only their front caps: where a back face B of a closed mesh (light outside
// its box) meets the segment strictly on the light's side, at q, the segment enters the mesh
// there and must leave it through a front face F between q and L, hence also strictly on the
// light's side (the half-space is convex), and F != r (r lies in the plane). So the front caps
// alone decide the rule too. For a sample one ulp inside a convex closed mesh beside its
// receiver's edge, the next face is met below plane(r): rejected, the sample is lit; for a closed
// box standing on a floor, the box's side faces straddle the floor's plane and
// hit_on_light_side() decides where the segment meets them.
//
// Only samples the count calls shadowed are asked: every own(T, p) is 0 or 1 for z-fail (and for
// z-pass with the eye outside every volume), so a zero count stays zero.
#include <cstdint>

#include <glm/vec3.hpp>

#include "reference/stencil/cap_tree.h"
#include "reference/stencil/shadow_volume.h"
#include "reference/stencil/silhouette.h"
#include "reference/stencil/volume_counting.h"
#include "shadowcts/case.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts::stencil {

// A closed box containing the part of p's segment (ray) towards the light that is not strictly
// on the light's side of h's plane, for p not strictly on that side. `bounded` is false where no
// finite box is known (a directional light within rounding of the receiver's plane).
struct RejectBox {
  bool bounded = false;
  glm::dvec3 lo{0.0}, hi{0.0};
};
RejectBox reject_box(const geometry::ReceiverHalfSpace& h, const glm::dvec3& p);

struct RuleOutcome {
  int rejected = 0;                 // sum of own(T, p) over the rejected caps T != r
  bool every_cap_rejected = false;  // the light lies in the receiver's plane: none counts
  std::uint32_t candidates = 0;     // caps whose boxes met the reject box
};

class StencilReceiverRule {
 public:
  StencilReceiverRule(const Case& c, const HardShadowLight& light, const Occluders& occluders,
                      const Extrusion& extrusion, CountingMode mode, const glm::dvec3& eye);

  // For a regular sample with a receiver (check_receivers) at p.
  RuleOutcome rejected(std::uint32_t receiver, const glm::dvec3& p, FaceTally& tally) const;

 private:
  const Case& c_;
  HardShadowLight light_;
  const Occluders& occluders_;
  Extrusion extrusion_;
  CountingMode mode_;
  glm::dvec3 eye_;
  CapTree tree_;
};

}  // namespace shadowcts::stencil
