#pragma once
// The receiver half-space rule of the simd ptsv: ref::ReceiverRule's half-spaces and reject
// reaches (the same shared functions on the same inputs), built in parallel.
#include <cstdint>
#include <vector>

#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/prepared_scene.h"

namespace shadowcts::simd::ptsv {

class ReceiverRule {
 public:
  // Needs a point or directional light (checked by the caller) and receivers that are triangles.
  explicit ReceiverRule(const PreparedScene& scene);

  // Per regular sample (PreparedScene::samples), as ref::ReceiverRule::reject_reach per view
  // sample.
  const std::vector<double>& reject_reach() const { return reach_; }
  // The half-space of a receiver of a regular sample (no_receiver: no plane).
  const geometry::ReceiverHalfSpace& half_space(std::uint32_t receiver) const {
    return receiver == no_receiver ? no_plane_ : half_spaces_[slot_[receiver]];
  }

 private:
  std::vector<std::uint32_t> slot_;
  std::vector<geometry::ReceiverHalfSpace> half_spaces_;
  geometry::ReceiverHalfSpace no_plane_;
  std::vector<double> reach_;
};

}  // namespace shadowcts::simd::ptsv
