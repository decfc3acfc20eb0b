#pragma once
// The texels of one square light-space depth map that are read, and the closest caster depth seen
// through each: exactly what a full map holds there. A full map is every texel; the algorithm
// keeps only those its samples look up (a 8192^2 map is 256 MB to clear, its samples read a few
// hundred thousand texels).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace shadowcts::shadowmap {

struct DepthMap {
  std::uint32_t resolution = 0;
  // The kept texels, row-major: row r's are [row_start[r], row_start[r + 1]), columns ascending.
  std::vector<std::uint32_t> row_start;
  std::vector<std::uint32_t> column;
  std::vector<float> depth;  // per kept texel; +infinity where no caster was rasterized

  // Every texel of an n x n map (depth is then row-major n x n).
  void reset_full(std::uint32_t n) {
    resolution = n;
    row_start.resize(std::size_t(n) + 1);
    column.resize(std::size_t(n) * n);
    for (std::uint32_t r = 0; r <= n; ++r) row_start[r] = r * n;
    for (std::size_t t = 0; t < column.size(); ++t) column[t] = std::uint32_t(t % n);
    depth.assign(column.size(), std::numeric_limits<float>::infinity());
  }
  // The texels row * n + column of `texels`, which is sorted and has no repeats.
  void reset(std::uint32_t n, const std::vector<std::uint64_t>& texels) {
    resolution = n;
    row_start.assign(std::size_t(n) + 1, 0);
    column.resize(texels.size());
    for (std::size_t k = 0; k < texels.size(); ++k) {
      column[k] = std::uint32_t(texels[k] % n);
      ++row_start[texels[k] / n + 1];
    }
    for (std::uint32_t r = 0; r < n; ++r) row_start[r + 1] += row_start[r];
    depth.assign(texels.size(), std::numeric_limits<float>::infinity());
  }
  // The depth of a kept texel.
  float at(std::uint32_t column_index, std::uint32_t row) const {
    const auto first = column.begin() + row_start[row], last = column.begin() + row_start[row + 1];
    return depth[std::size_t(std::lower_bound(first, last, column_index) - column.begin())];
  }
};

}  // namespace shadowcts::shadowmap
