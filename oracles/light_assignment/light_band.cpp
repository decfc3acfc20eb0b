#include "oracles/light_assignment/light_band.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "oracles/band_moves.h"

namespace shadowcts {
namespace {

// sqrt(3) rounded up: the corner moves have length sqrt(3) delta.
constexpr double sqrt3_up = 1.7320508075688775;
// Relative margin for distances evaluated in doubles: their rounding error is a small multiple
// of 2^-53 times the magnitudes involved (coordinates, range, |p - c|); 2^-36 exceeds it by more
// than 10^4.
constexpr double distance_margin = 0x1p-36;

double norm(const glm::dvec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

}  // namespace

LightBandClassifier::LightBandClassifier(double tau, double scale, bool normal_rule)
    : normal_rule_(normal_rule), reach_(sqrt3_up * tau * (1.0 + 0x1p-50)) {
  const double smallest = std::ldexp(scale, -24);
  for (double length = tau; length >= smallest && length > 0.0; length *= 0.5)
    move_lengths_.push_back(length);  // exact: tau times a power of two
  std::reverse(move_lengths_.begin(), move_lengths_.end());
}

bool LightBandClassifier::member_at(const ExactLightVolume& light, const LightQueryPoint& x,
                                    const glm::vec3& normal) const {
  if (!light_volume_contains(light, x)) return false;
  return !normal_rule_ || light_in_front_of(normal, light, x);
}

bool LightBandClassifier::may_reach(const ExactLightVolume& light,
                                    const glm::vec3& position) const {
  const glm::dvec3 p(position);
  const glm::dvec3 v = p - light.centre;
  const double margin =
      distance_margin * (norm(glm::abs(p)) + norm(glm::abs(light.centre)) + light.range);
  const double grown = light.range + reach_ + margin;
  return v.x * v.x + v.y * v.y + v.z * v.z <= grown * grown;
}

// A lower bound on the distance from p to the boundary of the pair's decision region, minus the
// margin for its double evaluation. The boundary of sphere and cone (and half-space) lies in the
// union of their surfaces, so the smallest distance to any of them bounds it from below.
double LightBandClassifier::boundary_distance(const ExactLightVolume& light,
                                              const glm::vec3& position,
                                              const glm::vec3& normal) const {
  const glm::dvec3 p(position);
  const glm::dvec3 v = p - light.centre;
  const double length = norm(v);
  double distance = std::fabs(length - light.range);
  if (light.kind == RangedLightKind::spot) {
    // A point at angle phi from the axis is |v| sin(min(|phi - theta|, pi / 2)) from the cone's
    // surface (the nearest surface ray lies in the point's meridian half-plane).
    const double along = glm::dot(v, light.axis);
    const double across = norm(glm::cross(v, light.axis));
    const double phi = std::atan2(across, along);
    const double separation = std::fabs(phi - double(light.cone_half_angle));
    distance = std::min(distance, length * std::sin(std::min(separation, std::numbers::pi / 2)));
  }
  if (normal_rule_) {
    const glm::dvec3 n(normal);
    const double n_length = norm(n);
    if (n_length > 0.0) distance = std::min(distance, std::fabs(glm::dot(n, v)) / n_length);
  }
  const double margin =
      distance_margin * (norm(glm::abs(p)) + norm(glm::abs(light.centre)) + light.range + length);
  return distance - margin;
}

LightBandAnswer LightBandClassifier::classify(const ExactLightVolume& light,
                                              const glm::vec3& position,
                                              const glm::vec3& normal) const {
  LightBandAnswer answer;
  const glm::dvec3 base(position);
  answer.member = member_at(light, LightQueryPoint{base, 0.0, {0, 0, 0}}, normal);
  // The moves stay inside the ball of radius reach() around p: robust when it holds no boundary.
  if (boundary_distance(light, position, normal) > reach_) return answer;
  answer.tried_moves = true;
  for (const double delta : move_lengths_)
    for (const glm::ivec3& move : band_moves)
      if (member_at(light, LightQueryPoint{base, delta, move}, normal) != answer.member) {
        answer.ambiguous = true;
        return answer;
      }
  return answer;
}

}  // namespace shadowcts
