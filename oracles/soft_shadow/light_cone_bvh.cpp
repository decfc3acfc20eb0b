#include "oracles/soft_shadow/light_cone_bvh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "oracles/exact_segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

constexpr std::uint32_t leaf_size = 4;
// Relative slack of the node test: its double rounding error is a few 1e-16 of the magnitudes.
constexpr double relative_slack = 1e-9;

}  // namespace

struct LightConeBvh::BuildItem {
  glm::dvec3 lo, hi, centroid;
  std::uint32_t triangle;
};

double distance_to_cone(const LightCone& cone, const glm::dvec3& x) {
  const glm::dvec3 v = x - cone.apex;
  const double h = glm::dot(v, cone.axis);
  const double l = glm::length(v - h * cone.axis);
  const double c = std::cos(cone.half_angle), s = std::sin(cone.half_angle);
  // In the (height, lateral) half-plane the cone is the wedge below the ray (cos a, sin a).
  if (h * c + l * s <= 0.0) return glm::length(v);  // nearest point: the apex
  return std::max(0.0, l * c - h * s);
}

bool LightConeBvh::may_meet(const LightCone& cone, const glm::dvec3& centre, double radius,
                            double inflation) {
  const double reach = radius + inflation;
  const double slack = relative_slack * (glm::length(centre - cone.apex) + reach);
  return distance_to_cone(cone, centre) <= reach + slack;
}

LightConeBvh::LightConeBvh(const Case& c) {
  std::vector<BuildItem> items;
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    if (!oracle_casts_shadow(c, i)) continue;
    const Triangle& t = c.triangles[i];
    BuildItem item;
    item.lo = glm::min(glm::dvec3(t.v0), glm::min(glm::dvec3(t.v1), glm::dvec3(t.v2)));
    item.hi = glm::max(glm::dvec3(t.v0), glm::max(glm::dvec3(t.v1), glm::dvec3(t.v2)));
    item.centroid = 0.5 * (item.lo + item.hi);
    item.triangle = std::uint32_t(i);
    items.push_back(item);
  }
  if (items.empty()) return;
  triangles_.resize(items.size());
  triangle_spheres_.resize(items.size());
  nodes_.reserve(2 * items.size());
  nodes_.emplace_back();
  build(items, 0, items.size(), 0);
}

void LightConeBvh::build(std::vector<BuildItem>& items, std::size_t begin, std::size_t end,
                         std::size_t node) {
  glm::dvec3 lo = items[begin].lo, hi = items[begin].hi;
  glm::dvec3 centroid_lo = items[begin].centroid, centroid_hi = centroid_lo;
  for (std::size_t i = begin; i < end; ++i) {
    lo = glm::min(lo, items[i].lo);
    hi = glm::max(hi, items[i].hi);
    centroid_lo = glm::min(centroid_lo, items[i].centroid);
    centroid_hi = glm::max(centroid_hi, items[i].centroid);
  }
  nodes_[node].centre = 0.5 * (lo + hi);
  nodes_[node].radius = 0.5 * glm::length(hi - lo);
  if (end - begin <= leaf_size) {
    nodes_[node].first_or_right = std::uint32_t(begin);
    nodes_[node].count = std::uint32_t(end - begin);
    for (std::size_t i = begin; i < end; ++i) {
      triangles_[i] = items[i].triangle;
      triangle_spheres_[i].centre = 0.5 * (items[i].lo + items[i].hi);
      triangle_spheres_[i].radius = 0.5 * glm::length(items[i].hi - items[i].lo);
    }
    return;
  }
  const glm::dvec3 extent = centroid_hi - centroid_lo;
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::size_t middle = begin + (end - begin) / 2;
  // Ties broken by triangle index: the split is a function of the case alone.
  std::nth_element(
      items.begin() + std::ptrdiff_t(begin), items.begin() + std::ptrdiff_t(middle),
      items.begin() + std::ptrdiff_t(end), [axis](const BuildItem& a, const BuildItem& b) {
        return a.centroid[axis] != b.centroid[axis] ? a.centroid[axis] < b.centroid[axis]
                                                    : a.triangle < b.triangle;
      });
  const std::size_t left = node + 1;
  nodes_.emplace_back();
  build(items, begin, middle, left);
  const std::size_t right = nodes_.size();
  nodes_.emplace_back();
  nodes_[node].first_or_right = std::uint32_t(right);
  nodes_[node].count = 0;
  build(items, middle, end, right);
}

}  // namespace shadowcts
