#include "simd/lightassign/light_bvh.h"

#include <algorithm>
#include <array>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "simd/lightassign/lightassign_kernels.h"

namespace shadowcts::simd {
namespace {

constexpr std::size_t block = 1 << 16;  // fixed work blocks: the same result for any thread count

std::size_t padded(std::size_t count) {
  return (count + LightBvh::branching - 1) / LightBvh::branching * LightBvh::branching;
}

// Stable LSD radix sort of `keys` by their upper 32 bits in three passes (11, 11 and 10 bits)
// over fixed blocks; the histograms of all passes come from one read, and a pass whose digit is
// the same for every key is skipped.
void sort_by_high_half(UninitializedVector<std::uint64_t>& keys) {
  const std::size_t n = keys.size();
  const std::size_t blocks = (n + block - 1) / block;
  constexpr int shifts[3] = {32, 43, 54};
  constexpr std::size_t radix = 1 << 11;
  std::vector<std::uint32_t> offsets(blocks * 3 * radix, 0);  // [block][pass][digit]
  auto offset = [&](std::size_t b, int pass, std::uint64_t digit) -> std::uint32_t& {
    return offsets[(b * 3 + std::size_t(pass)) * radix + digit];
  };
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i)
      for (int pass = 0; pass < 3; ++pass)
        ++offset(b, pass, (keys[i] >> shifts[pass]) & (radix - 1));
  });
  UninitializedVector<std::uint64_t> other(n);
  for (int pass = 0; pass < 3; ++pass) {
    std::uint32_t start = 0;
    bool constant = false;
    for (std::size_t digit = 0; digit < radix; ++digit)
      for (std::size_t b = 0; b < blocks; ++b) {
        std::uint32_t& at = offset(b, pass, digit);
        const std::uint32_t count = at;
        constant = constant || count == n;
        at = start;
        start += count;
      }
    if (constant) continue;
    // The digits of this pass were counted on the keys' first order: recount per block on the
    // current one.
    if (pass > 0) {
      tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
        for (std::size_t digit = 0; digit < radix; ++digit) offset(b, pass, digit) = 0;
        for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i)
          ++offset(b, pass, (keys[i] >> shifts[pass]) & (radix - 1));
      });
      std::uint32_t restart = 0;
      for (std::size_t digit = 0; digit < radix; ++digit)
        for (std::size_t b = 0; b < blocks; ++b) {
          std::uint32_t& at = offset(b, pass, digit);
          const std::uint32_t count = at;
          at = restart;
          restart += count;
        }
    }
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
      for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i)
        other[offset(b, pass, (keys[i] >> shifts[pass]) & (radix - 1))++] = keys[i];
    });
    keys.swap(other);
  }
}

}  // namespace

void BoxArrays::resize(std::size_t boxes) {
  count = boxes;
  for (int k = 0; k < 3; ++k) {
    min[k].resize(padded(boxes));
    max[k].resize(padded(boxes));
    std::fill(min[k].begin() + std::ptrdiff_t(boxes), min[k].end(),
              std::numeric_limits<float>::infinity());
    std::fill(max[k].begin() + std::ptrdiff_t(boxes), max[k].end(),
              -std::numeric_limits<float>::infinity());
  }
}

LightBvhLanes::LightBvhLanes(const std::vector<RangedLight>& lights) {
  const std::size_t n = lights.size();
  if (n == 0) return;
  const std::size_t blocks = (n + block - 1) / block;

  // The box around the centres (min and max are exact in any order).
  struct Bounds {
    std::array<float, 3> low, high;
  };
  const Bounds bounds = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, block),
      Bounds{{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
              std::numeric_limits<float>::infinity()},
             {-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
              -std::numeric_limits<float>::infinity()}},
      [&](const auto& r, Bounds b) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          for (int k = 0; k < 3; ++k) {
            b.low[k] = std::min(b.low[k], lights[i].centre[k]);
            b.high[k] = std::max(b.high[k], lights[i].centre[k]);
          }
        return b;
      },
      [](Bounds a, const Bounds& b) {
        for (int k = 0; k < 3; ++k) {
          a.low[k] = std::min(a.low[k], b.low[k]);
          a.high[k] = std::max(a.high[k], b.high[k]);
        }
        return a;
      });
  double low[3], extent[3];
  for (int k = 0; k < 3; ++k) {
    low[k] = double(bounds.low[k]);
    extent[k] = std::max(double(bounds.high[k]) - low[k], 1e-300);
  }

  // Morton codes in lanes; the sort key holds the code's upper 32 bits over the light index (so
  // equal upper halves stay in index order), the lower 31 bits are kept for the ties.
  UninitializedVector<std::uint64_t> keys(n);
  UninitializedVector<std::uint32_t> low_bits(n);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    const std::size_t first = b * block, count = std::min(n, first + block) - first;
    morton_codes(lights.data() + first, count, low, extent, keys.data() + first);
    for (std::size_t i = first; i < first + count; ++i) {
      low_bits[i] = std::uint32_t(keys[i] & 0x7FFFFFFFu);
      keys[i] = (keys[i] >> 31) << 32 | i;
    }
  });
  sort_by_high_half(keys);
  // Runs of equal upper halves in (code, index) order; each block sorts the runs starting in it.
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    const auto high = [&](std::size_t i) { return keys[i] >> 32; };
    std::size_t i = b * block;
    while (i > 0 && i < n && high(i) == high(i - 1)) ++i;
    while (i < std::min(n, (b + 1) * block)) {
      std::size_t end = i + 1;
      while (end < n && high(end) == high(i)) ++end;
      if (end - i > 1)
        std::sort(keys.begin() + std::ptrdiff_t(i), keys.begin() + std::ptrdiff_t(end),
                  [&](std::uint64_t x, std::uint64_t y) {
                    const std::uint32_t lx = low_bits[x & 0xFFFFFFFFu],
                                        ly = low_bits[y & 0xFFFFFFFFu];
                    return lx != ly ? lx < ly : x < y;
                  });
      i = end;
    }
  });

  // The leaves: order and spheres, gathered once here and read in order by every query.
  order.resize(n);
  for (int k = 0; k < 4; ++k) {
    sphere[k].resize(padded(n));
    std::fill(sphere[k].begin() + std::ptrdiff_t(n), sphere[k].end(),
              k < 3 ? std::numeric_limits<float>::quiet_NaN() : 0.0f);
  }
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    for (std::size_t leaf = b * block; leaf < std::min(n, (b + 1) * block); ++leaf) {
      // The lights are read in Morton order, far apart: ask for one a few leaves ahead.
      if (leaf + 16 < n) __builtin_prefetch(&lights[std::uint32_t(keys[leaf + 16])]);
      const std::uint32_t index = std::uint32_t(keys[leaf]);
      const RangedLight& l = lights[index];
      order[leaf] = index;
      sphere[0][leaf] = l.centre.x;
      sphere[1][leaf] = l.centre.y;
      sphere[2][leaf] = l.centre.z;
      sphere[3][leaf] = l.range;
    }
  });

  // Levels of 32 consecutive children each, until one root.
  do {
    const std::size_t children = levels.empty() ? n : levels.back().count;
    BoxArrays level;
    level.resize((children + branching - 1) / branching);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, level.count, 256), [&](const auto& r) {
      if (levels.empty())
        leaf_node_boxes(*this, r.begin(), r.size(), level);
      else
        node_boxes(levels.back(), r.begin(), r.size(), level);
    });
    levels.push_back(std::move(level));
  } while (levels.back().count > 1);
}

}  // namespace shadowcts::simd
