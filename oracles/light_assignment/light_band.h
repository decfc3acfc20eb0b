#pragma once
// The ambiguity band for one (sample, light) pair: the exact membership at the sample and whether
// some band move changes it (see include/shadowcts/light_assignment_oracle.h for the definition).
#include <vector>

#include <glm/vec3.hpp>

#include "oracles/light_assignment/light_volume_predicates.h"

namespace shadowcts {

struct LightBandAnswer {
  bool member = false;     // exact answer at the unmoved sample
  bool ambiguous = false;  // some band move changes it
  bool tried_moves = false;
};

class LightBandClassifier {
 public:
  // tau = eps_rel * scale; the moves have lengths tau 2^-j >= 2^-24 scale.
  LightBandClassifier(double tau, double scale, bool normal_rule);

  // The longest move: sqrt(3) tau (a cube corner at the largest length), rounded up.
  double reach() const { return reach_; }

  // Exact membership at p, and whether a move changes it. A pair whose distance from the
  // boundary (of the sphere, the cone, and the normal rule's plane) exceeds reach() with a margin
  // for the double evaluation is robust without trying moves.
  LightBandAnswer classify(const ExactLightVolume& light, const glm::vec3& position,
                           const glm::vec3& normal) const;

  // Whether the light's sphere, grown by reach() and a rounding margin, may contain p (double,
  // conservative): a light that fails it is a robust non-member.
  bool may_reach(const ExactLightVolume& light, const glm::vec3& position) const;

  bool member_at(const ExactLightVolume& light, const LightQueryPoint& x,
                 const glm::vec3& normal) const;

 private:
  double boundary_distance(const ExactLightVolume& light, const glm::vec3& position,
                           const glm::vec3& normal) const;

  bool normal_rule_;
  double reach_;
  std::vector<double> move_lengths_;  // ascending
};

}  // namespace shadowcts
