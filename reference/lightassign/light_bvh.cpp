#include "reference/lightassign/light_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <glm/common.hpp>

#include "shadowcts/float_rounding.h"
#include "shadowcts/geometry/morton.h"

namespace shadowcts {
LightBvh::LightBvh(const std::vector<RangedLight>& lights) {
  const std::size_t n = lights.size();
  if (n == 0) return;

  // Morton codes of the centres, 21 bits per axis over the box around all centres.
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
  for (const RangedLight& l : lights) {
    low = glm::min(low, glm::dvec3(l.centre));
    high = glm::max(high, glm::dvec3(l.centre));
  }
  const glm::dvec3 extent = glm::max(high - low, glm::dvec3(1e-300));
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::uint64_t code = 0;
      for (int k = 0; k < 3; ++k) {
        const double t = (double(lights[i].centre[k]) - low[k]) / extent[k];
        const auto q = std::uint64_t(std::clamp(t * 2097152.0, 0.0, 2097151.0));
        code |= geometry::spread_bits_21(q) << (2 - k);
      }
      keyed[i] = {code, std::uint32_t(i)};
    }
  });
  // Unique (code, index) pairs: the order does not depend on the sort's scheduling.
  tbb::parallel_sort(keyed.begin(), keyed.end());

  order_.resize(n);
  leaf_boxes_.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const auto& r) {
    for (std::size_t leaf = r.begin(); leaf != r.end(); ++leaf) {
      const RangedLight& l = lights[keyed[leaf].second];
      order_[leaf] = keyed[leaf].second;
      for (int k = 0; k < 3; ++k) {
        leaf_boxes_[leaf].min[k] = float_below(double(l.centre[k]) - double(l.range));
        leaf_boxes_[leaf].max[k] = float_above(double(l.centre[k]) + double(l.range));
      }
    }
  });

  // Levels of 32 consecutive children each, until one root.
  const std::vector<Aabb>* children = &leaf_boxes_;
  do {
    std::vector<Aabb> level((children->size() + branching - 1) / branching);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.size(), 256), [&](const auto& r) {
      for (std::size_t node = r.begin(); node != r.end(); ++node) {
        const std::size_t first = node * branching;
        const std::size_t last = std::min(first + branching, children->size());
        Aabb box = (*children)[first];
        for (std::size_t c = first + 1; c < last; ++c) {
          box.min = glm::min(box.min, (*children)[c].min);
          box.max = glm::max(box.max, (*children)[c].max);
        }
        level[node] = box;
      }
    });
    levels_.push_back(std::move(level));
    children = &levels_.back();
  } while (children->size() > 1);
}

}  // namespace shadowcts
