#include "oracles/light_assignment/light_candidate_grid.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace shadowcts {
namespace {

// Grows every light box by this fraction of the magnitudes involved, far more than the rounding
// of the cell-index computations (a few 2^-53 relative), so that a point inside a grown sphere is
// always in one of the light's cells.
constexpr double index_margin = 0x1p-30;

struct CellRange {
  glm::ivec3 low{0}, high{-1};  // empty when any high < low
  bool empty() const { return high.x < low.x || high.y < low.y || high.z < low.z; }
  std::uint64_t count() const {
    if (empty()) return 0;
    return std::uint64_t(high.x - low.x + 1) * std::uint64_t(high.y - low.y + 1) *
           std::uint64_t(high.z - low.z + 1);
  }
};

}  // namespace

LightCandidateGrid::LightCandidateGrid(const std::vector<ExactLightVolume>& lights,
                                       const glm::dvec3& low, const glm::dvec3& high,
                                       double reach) {
  // About two cells per light, up to 2^22 cells, shaped after the box (flat boxes get one layer).
  const glm::dvec3 extent = glm::max(high - low, glm::dvec3(0.0));
  const double largest = std::max({extent.x, extent.y, extent.z, 1e-30});
  const glm::dvec3 sized = glm::max(extent, glm::dvec3(largest * 1e-3));
  const double target = std::clamp(2.0 * double(lights.size()), 1.0, double(1u << 22));
  const double cell = std::cbrt(sized.x * sized.y * sized.z / target);
  for (int i = 0; i < 3; ++i) {
    dims_[i] = int(std::clamp(std::ceil(extent[i] / cell), 1.0, 1024.0));
    cell_size_[i] = std::max(extent[i] / dims_[i], 1e-300);
  }
  origin_ = low;

  // Each light's cell range, in parallel; then counting and filling in light order.
  std::vector<CellRange> ranges(lights.size());
  const double origin_magnitude = glm::length(glm::abs(origin_));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lights.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const ExactLightVolume& light = lights[i];
      const double grown = light.range + reach +
                           index_margin * (glm::length(glm::abs(light.centre)) + light.range +
                                           origin_magnitude + reach);
      const glm::dvec3 box_low = light.centre - grown, box_high = light.centre + grown;
      if (box_high.x < low.x || box_high.y < low.y || box_high.z < low.z || box_low.x > high.x ||
          box_low.y > high.y || box_low.z > high.z)
        continue;  // cannot reach any query point
      CellRange range;
      for (int k = 0; k < 3; ++k) {
        const double a = std::floor((box_low[k] - origin_[k]) / cell_size_[k]);
        const double b = std::floor((box_high[k] - origin_[k]) / cell_size_[k]);
        range.low[k] = int(std::clamp(a, 0.0, double(dims_[k] - 1)));
        range.high[k] = int(std::clamp(b, 0.0, double(dims_[k] - 1)));
      }
      ranges[i] = range;
    }
  });

  const std::uint64_t cell_count = std::uint64_t(dims_.x) * dims_.y * dims_.z;
  std::vector<std::uint64_t> counts(cell_count + 1, 0);
  auto for_each_cell = [&](const CellRange& r, auto&& f) {
    for (int z = r.low.z; z <= r.high.z; ++z)
      for (int y = r.low.y; y <= r.high.y; ++y)
        for (int x = r.low.x; x <= r.high.x; ++x)
          f((std::uint64_t(z) * dims_.y + std::uint64_t(y)) * dims_.x + std::uint64_t(x));
  };
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const std::uint64_t n = ranges[i].count();
    if (n == 0) continue;
    if (n > max_cells_per_light) {
      everywhere_.push_back(std::uint32_t(i));
      continue;
    }
    for_each_cell(ranges[i], [&](std::uint64_t cell_index) { ++counts[cell_index + 1]; });
  }
  for (std::uint64_t k = 0; k < cell_count; ++k) counts[k + 1] += counts[k];
  cell_offsets_ = counts;
  cell_lights_.resize(cell_offsets_.back());
  std::vector<std::uint64_t> fill(cell_offsets_.begin(), cell_offsets_.end() - 1);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const std::uint64_t n = ranges[i].count();
    if (n == 0 || n > max_cells_per_light) continue;
    for_each_cell(ranges[i], [&](std::uint64_t cell_index) {
      cell_lights_[fill[cell_index]++] = std::uint32_t(i);
    });
  }
}

glm::ivec3 LightCandidateGrid::cell_of(const glm::dvec3& p) const {
  glm::ivec3 cell;
  for (int k = 0; k < 3; ++k)
    cell[k] =
        int(std::clamp(std::floor((p[k] - origin_[k]) / cell_size_[k]), 0.0, double(dims_[k] - 1)));
  return cell;
}

void LightCandidateGrid::candidates(const glm::dvec3& p, std::vector<std::uint32_t>& out) const {
  const glm::ivec3 cell = cell_of(p);
  const std::uint64_t index =
      (std::uint64_t(cell.z) * dims_.y + std::uint64_t(cell.y)) * dims_.x + std::uint64_t(cell.x);
  const std::size_t first = out.size();
  out.insert(out.end(), cell_lights_.begin() + std::ptrdiff_t(cell_offsets_[index]),
             cell_lights_.begin() + std::ptrdiff_t(cell_offsets_[index + 1]));
  const std::size_t middle = out.size();
  out.insert(out.end(), everywhere_.begin(), everywhere_.end());
  // Both runs are ascending and disjoint: merge them in place.
  std::inplace_merge(out.begin() + std::ptrdiff_t(first), out.begin() + std::ptrdiff_t(middle),
                     out.end());
}

}  // namespace shadowcts
