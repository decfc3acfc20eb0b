#include "simd/lightassign/light_bvh.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "simd/lightassign/lightassign_kernels.h"

namespace shadowcts::simd {
namespace {

constexpr std::size_t block = 1 << 16;  // fixed work blocks: the same result for any thread count

std::size_t padded(std::size_t count) {
  return (count + LightBvh::branching - 1) / LightBvh::branching * LightBvh::branching;
}

constexpr int top_shift = 56;  // the buckets of morton_order: the keys' top 8 bits
constexpr std::size_t buckets = 1 << 8;

// The leaves in Morton order: the light indices of `keys` (the code's upper 32 bits over the
// light index, in index order) sorted by (code, index) into `order`, the lights' spheres laid out
// in that order. One parallel pass moves each key and its light's sphere (from `packed`, read in
// index order) into a bucket by the top 8 bits (few buckets: few write streams; `offsets` holds
// each block's count per bucket); each bucket is then ordered in cache: its keys by the other 24
// bits of the upper half (three 8-bit LSD passes over (bits, position), or std::sort when small),
// runs of equal upper halves by the lower 31 bits of the code (low_bits) and the index. No light
// is read out of order (a gather of the spheres in Morton order from `packed` waits on memory).
void morton_order(const UninitializedVector<float>& packed,
                  const UninitializedVector<std::uint64_t>& keys,
                  const UninitializedVector<std::uint32_t>& low_bits,
                  std::vector<std::uint32_t>& offsets, UninitializedVector<std::uint32_t>& order,
                  UninitializedVector<float>* sphere) {
  const std::size_t n = keys.size();
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<std::uint32_t> bucket_start(buckets + 1, 0);
  std::uint32_t start = 0;
  for (std::size_t bucket = 0; bucket < buckets; ++bucket) {
    bucket_start[bucket] = start;
    for (std::size_t b = 0; b < blocks; ++b)
      start += std::exchange(offsets[b * buckets + bucket], start);
  }
  bucket_start[buckets] = start;
  struct Sphere {
    float x, y, z, range;
  };
  UninitializedVector<std::uint64_t> bucketed(n);
  UninitializedVector<Sphere> bucketed_sphere(n);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    // Plain pointers: the compiler need not reload the vectors' after every store.
    std::uint32_t* const at = offsets.data() + b * buckets;
    const std::uint64_t* const key = keys.data();
    const float* const sphere_of = packed.data();
    std::uint64_t* const to_key = bucketed.data();
    Sphere* const to_sphere = bucketed_sphere.data();
    for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) {
      const std::uint32_t position = at[key[i] >> top_shift]++;
      to_key[position] = key[i];
      const float* from = sphere_of + 4 * i;
      to_sphere[position] = {from[0], from[1], from[2], from[3]};
    }
  });
  tbb::enumerable_thread_specific<std::vector<std::uint64_t>> scratch;
  tbb::enumerable_thread_specific<std::vector<Sphere>> sphere_scratch;
  tbb::parallel_for(std::size_t(0), buckets, [&](std::size_t bucket) {
    const std::size_t first = bucket_start[bucket], count = bucket_start[bucket + 1] - first;
    if (count == 0) return;
    // (the upper half's other 24 bits, light index): the bucket holds its lights in index
    // order, so a stable sort by the bits orders them by (bits, index).
    std::vector<std::uint64_t>& local = scratch.local();
    local.resize(2 * count);
    std::uint64_t* from = local.data();
    std::uint64_t* to = local.data() + count;
    for (std::size_t p = 0; p < count; ++p)
      from[p] = (bucketed[first + p] >> 32 & 0xFFFFFF) << 32 | p;
    // The bucket's spheres copied in order first: read in sorted order from the shared array,
    // each one waited on memory (the per-bucket pass took 7-8 ms at 1 M lights, 6 with the copy).
    std::vector<Sphere>& spheres = sphere_scratch.local();
    spheres.assign(bucketed_sphere.begin() + std::ptrdiff_t(first),
                   bucketed_sphere.begin() + std::ptrdiff_t(first + count));
    if (count <= 128) {
      std::sort(from, from + count);
    } else {
      std::uint32_t histogram[256];
      for (const auto& [shift, mask] :
           {std::pair(32, 255u), std::pair(40, 255u), std::pair(48, 255u)}) {
        std::fill(histogram, histogram + 256, 0u);
        for (std::size_t i = 0; i < count; ++i) ++histogram[(from[i] >> shift) & mask];
        std::uint32_t position = 0;
        for (std::uint32_t& h : histogram) position += std::exchange(h, position);
        for (std::size_t i = 0; i < count; ++i)
          to[histogram[(from[i] >> shift) & mask]++] = from[i];
        std::swap(from, to);
      }
    }
    // Equal upper halves: by the code's lower bits, then the index.
    const auto key_at = [&](std::uint64_t entry) {
      return bucketed[first + (entry & 0xFFFFFFFFu)];
    };
    for (std::size_t i = 0; i < count;) {
      std::size_t end = i + 1;
      while (end < count && from[end] >> 32 == from[i] >> 32) ++end;
      if (end - i > 1)
        std::sort(from + i, from + end, [&](std::uint64_t x, std::uint64_t y) {
          const std::uint64_t kx = key_at(x), ky = key_at(y);
          const std::uint32_t lx = low_bits[kx & 0xFFFFFFFFu], ly = low_bits[ky & 0xFFFFFFFFu];
          return lx != ly ? lx < ly : kx < ky;
        });
      i = end;
    }
    for (std::size_t r = 0; r < count; ++r) {
      const std::size_t p = from[r] & 0xFFFFFFFFu, leaf = first + r;
      order[leaf] = std::uint32_t(bucketed[first + p]);
      sphere[0][leaf] = spheres[p].x;
      sphere[1][leaf] = spheres[p].y;
      sphere[2][leaf] = spheres[p].z;
      sphere[3][leaf] = spheres[p].range;
    }
  });
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

  // The lights' spheres packed (centre x, y, z, range: one 16-byte read per light for the codes
  // and the leaves, instead of the lights' larger records) and the box around the centres, in one
  // pass over the lights (min and max are exact in any order).
  UninitializedVector<float> packed(4 * n);
  std::vector<std::array<float, 6>> block_bounds(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    constexpr float infinity = std::numeric_limits<float>::infinity();
    float low_x = infinity, low_y = infinity, low_z = infinity;
    float high_x = -infinity, high_y = -infinity, high_z = -infinity;
    for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) {
      const RangedLight& l = lights[i];
      float* sphere_of = packed.data() + 4 * i;
      sphere_of[0] = l.centre.x;
      sphere_of[1] = l.centre.y;
      sphere_of[2] = l.centre.z;
      sphere_of[3] = l.range;
      low_x = std::min(low_x, l.centre.x);
      low_y = std::min(low_y, l.centre.y);
      low_z = std::min(low_z, l.centre.z);
      high_x = std::max(high_x, l.centre.x);
      high_y = std::max(high_y, l.centre.y);
      high_z = std::max(high_z, l.centre.z);
    }
    block_bounds[b] = {low_x, low_y, low_z, high_x, high_y, high_z};
  });
  std::array<float, 6> bounds = block_bounds[0];
  for (const std::array<float, 6>& b : block_bounds)
    for (int k = 0; k < 3; ++k) {
      bounds[k] = std::min(bounds[k], b[k]);
      bounds[k + 3] = std::max(bounds[k + 3], b[k + 3]);
    }
  double low[3], extent[3];
  for (int k = 0; k < 3; ++k) {
    low[k] = double(bounds[k]);
    extent[k] = std::max(double(bounds[k + 3]) - low[k], 1e-300);
  }

  // Morton codes in lanes; the sort key holds the code's upper 32 bits over the light index (so
  // equal upper halves stay in index order), the lower 31 bits are kept for the ties.
  UninitializedVector<std::uint64_t> keys(n);
  UninitializedVector<std::uint32_t> low_bits(n);
  std::vector<std::uint32_t> offsets(blocks * buckets, 0);  // [block][bucket]: the key counts
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    const std::size_t first = b * block, count = std::min(n, first + block) - first;
    morton_codes(packed.data() + 4 * first, count, low, extent, keys.data() + first);
    std::uint32_t* in_bucket = offsets.data() + b * buckets;
    for (std::size_t i = first; i < first + count; ++i) {
      low_bits[i] = std::uint32_t(keys[i] & 0x7FFFFFFFu);
      keys[i] = (keys[i] >> 31) << 32 | i;
      ++in_bucket[keys[i] >> top_shift];
    }
  });
  // The leaves: order and spheres, in Morton order, read in order by every query.
  order.resize(n);
  for (int k = 0; k < 4; ++k) {
    sphere[k].resize(padded(n));
    std::fill(sphere[k].begin() + std::ptrdiff_t(n), sphere[k].end(),
              k < 3 ? std::numeric_limits<float>::quiet_NaN() : 0.0f);
  }
  morton_order(packed, keys, low_bits, offsets, order, sphere);

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
