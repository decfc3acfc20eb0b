#pragma once
// Builds the CSR light lists of AlgorithmOutput from a per-list fill function, in parallel over
// fixed blocks of lists: the result does not depend on the thread count.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "shadowcts/algorithm.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Work a list's assignment reports, summed over all lists.
struct ListWork {
  std::uint64_t nodes_tested = 0;     // light BVH boxes tested (Paper II's traversal)
  std::uint64_t light_tests = 0;      // lights tested against the list's volume
  std::uint64_t backface_culled = 0;  // lights dropped by the normal-cone rule
  ListWork& operator+=(const ListWork& o) {
    nodes_tested += o.nodes_tested;
    light_tests += o.light_tests;
    backface_culled += o.backface_culled;
    return *this;
  }
};

// fill(list, lights) appends list `list`'s lights to `lights` and returns its work.
template <class Fill>
ListWork build_light_lists(std::size_t list_count, LightLists& out, Fill&& fill) {
  constexpr std::size_t block = 64;
  const std::size_t blocks = (list_count + block - 1) / block;
  struct Block {
    std::vector<std::uint32_t> lights, sizes;
    ListWork work;
  };
  std::vector<Block> results(blocks);
  // The assignment, the long part of every variant: lists filled of all.
  phase_progress::begin(list_count, "light lists");
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const auto& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      Block& result = results[b];
      const std::size_t end = std::min(list_count, (b + 1) * block);
      for (std::size_t list = b * block; list < end; ++list) {
        const std::size_t before = result.lights.size();
        result.work += fill(list, result.lights);
        result.sizes.push_back(std::uint32_t(result.lights.size() - before));
      }
      phase_progress::advance(end - b * block);
    }
  });
  ListWork work;
  std::uint64_t total = 0;
  for (const Block& b : results) total += b.lights.size();
  if (total > 0xFFFFFFFFull)
    throw std::length_error("light lists: more than 2^32 - 1 entries in all");
  out.offsets.assign(1, 0);
  out.offsets.reserve(list_count + 1);
  out.lights.clear();
  out.lights.reserve(total);
  for (const Block& b : results) {
    out.lights.insert(out.lights.end(), b.lights.begin(), b.lights.end());
    for (const std::uint32_t size : b.sizes) out.offsets.push_back(out.offsets.back() + size);
    work += b.work;
  }
  return work;
}

// The counters every variant reports, in this order: total list length, lighting computations
// (sum over regular samples of their list's length: Paper I's metric), BVH node boxes tested,
// lists (unique clusters, tiles or samples), cluster key bits, lights tested against list
// volumes, lights dropped by the back-face rule, samples that fell outside their list's implicit
// bounds by rounding and grew them.
inline Counters light_assignment_counters(const LightLists& lists, std::uint64_t lighting,
                                          const ListWork& work, std::uint64_t key_bits,
                                          std::uint64_t bounds_grown) {
  return {{"list_lengths_total", lists.lights.size()},
          {"lighting_computations", lighting},
          {"bvh_nodes_tested", work.nodes_tested},
          {"unique_clusters", lists.offsets.size() - 1},
          {"key_bits", key_bits},
          {"light_tests", work.light_tests},
          {"backface_culled", work.backface_culled},
          {"bounds_grown_samples", bounds_grown}};
}

// The same, the lighting computations summed over the samples.
inline Counters light_assignment_counters(const LightLists& lists, const ViewSamples& samples,
                                          const ListWork& work, std::uint64_t key_bits,
                                          std::uint64_t bounds_grown) {
  std::uint64_t lighting = 0;
  for (std::size_t s = 0; s < samples.samples.size(); ++s) {
    const std::uint32_t list = lists.list_of_sample[s];
    if (list != LightLists::no_list) lighting += lists.offsets[list + 1] - lists.offsets[list];
  }
  return light_assignment_counters(lists, lighting, work, key_bits, bounds_grown);
}

}  // namespace shadowcts
