#pragma once
// The receiver half-space rule (DESIGN.md, "Cases and ground truth") in the PTSV traversal. A
// sample inside a caster's closed shadow volume is shadowed by it only where the caster meets the
// sample's segment (ray) strictly on the light's side of the receiver's plane:
// - the per-sample test asks caster_counts() (shadowcts/geometry/receiver_half_space.h) after the
//   volume test, so a rejected caster leaves the sample to the other volumes;
// - a whole node is accepted only when the rule cannot reject the caster for any of its samples.
//   A caster's hit X lies on its own plane, so |X - p| >= the distance of p from that plane. The
//   part of p's segment (ray) that is not strictly on the light's side starts at p and is
//   reject_reach(p) long: 0 unless p lies strictly below its receiver's plane, there
//   |f(p)| |L - p| / (f(L) - f(p)) for the receiver's plane function f. A node whose samples all
//   lie further behind the caster's plane than their reach is accepted as in the paper; otherwise
//   it is refined, so its samples end in the per-sample test. Below-plane samples are rounded
//   positions (|f(p)| ~ 2^-24 scale), so the reach stays below the accept bias unless the light
//   grazes the receiver: the hierarchy, its counters and masks change only there.
#include <cstdint>
#include <vector>

#include "reference/ptsv/triangle_setup.h"
#include "shadowcts/case.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv {

class ReceiverRule {
 public:
  // The half-spaces of the receivers of regular samples, and every sample's reject reach. Throws
  // InputError without a point or directional light; receivers must be checked (check_receivers).
  ReceiverRule(const Case& c, const ViewSamples& samples);

  // For a sample inside the closed shadow volume of `volume`'s caster: whether that caster
  // shadows it under the rule (its own receiver never does).
  bool caster_counts(const ShadowVolume& volume, const ViewSample& sample) const;

  // Per sample (indexed like samples.samples): an upper bound of the length of the part of the
  // segment (ray) from the sample that is not strictly on the light's side of its receiver's
  // plane; infinity where no bound is known (the light in or very near the receiver's plane).
  // 0 for samples that are not regular.
  const std::vector<double>& reject_reach() const { return reach_; }

  const geometry::ReceiverHalfSpace& half_space(std::uint32_t receiver) const;

 private:
  const Case& c_;
  static constexpr std::uint32_t no_slot = 0xFFFFFFFFu;
  std::vector<std::uint32_t> slot_;                       // per triangle: index into half_spaces_
  std::vector<geometry::ReceiverHalfSpace> half_spaces_;  // receivers of regular samples
  geometry::ReceiverHalfSpace no_plane_;                  // no receiver: every caster counts
  std::vector<double> reach_;
};

// The reject reach of p (see ReceiverRule::reject_reach) for its receiver's half-space.
double reject_reach(const geometry::ReceiverHalfSpace& h, const glm::dvec3& p);

}  // namespace shadowcts::ptsv
