#include "shadowcts/manifest_direction.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace shadowcts {
namespace {

float ulps_away(float x, int ulps) {
  for (; ulps > 0; --ulps) x = std::nextafter(x, INFINITY);
  for (; ulps < 0; ++ulps) x = std::nextafter(x, -INFINITY);
  return x;
}

bool is_stable(const glm::vec3& d) {
  return manifest_direction(glm::dvec3(d)) == d;
}

}  // namespace

glm::vec3 manifest_direction(const glm::dvec3& v) {
  const double largest = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  const glm::dvec3 scaled = v / largest;
  return glm::vec3(scaled / glm::length(scaled));
}

glm::vec3 manifest_stable_direction(const glm::vec3& d) {
  glm::vec3 current = manifest_direction(glm::dvec3(d));
  for (int i = 0; i < 16 && !is_stable(current); ++i)
    current = manifest_direction(glm::dvec3(current));
  // The nearest rings of floats first, in a fixed order: deterministic.
  for (int radius = 0; radius <= 8; ++radius)
    for (int a = -radius; a <= radius; ++a)
      for (int b = -radius; b <= radius; ++b)
        for (int c = -radius; c <= radius; ++c) {
          if (std::max({std::abs(a), std::abs(b), std::abs(c)}) != radius) continue;
          const glm::vec3 candidate(ulps_away(current.x, a), ulps_away(current.y, b),
                                    ulps_away(current.z, c));
          if (is_stable(candidate)) return candidate;
        }
  // Not met in 4 million random directions.
  throw std::logic_error("manifest_stable_direction: no stable direction within 8 ulps");
}

}  // namespace shadowcts
