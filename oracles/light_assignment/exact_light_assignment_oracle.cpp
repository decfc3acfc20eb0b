// The exact light-assignment oracle: candidate lights from a uniform grid, the exact set and the
// band per (sample, light) pair, assembled into per-sample CSR lists.
#include <algorithm>
#include <atomic>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "oracles/light_assignment/light_band.h"
#include "oracles/light_assignment/light_candidate_grid.h"
#include "oracles/light_assignment/light_volume_predicates.h"
#include "shadowcts/errors.h"
#include "shadowcts/light_assignment_oracle.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

// Samples are processed in fixed blocks, each writing its own lists: the assembled result does
// not depend on which thread ran which block.
constexpr std::size_t block_size = 1024;

struct BlockResult {
  std::vector<std::uint32_t> set_sizes, ambiguous_sizes;  // per sample of the block
  std::vector<std::uint32_t> lights, ambiguous;
  std::uint64_t candidate_pairs = 0, band_move_pairs = 0;
};

}  // namespace

LightAssignmentTruth exact_light_assignment_oracle(const Case& c, const ViewSamples& samples,
                                                   bool normal_rule) {
  if (c.ranged_lights.empty())
    throw InputError(c.source, "ranged_lights", "the light-assignment oracle needs ranged lights");
  if (c.ranged_lights.size() > std::numeric_limits<std::uint32_t>::max())
    throw InputError(c.source, "ranged_lights", "more than 2^32 - 1 lights");
  if (samples.samples.size() != std::size_t(samples.width) * samples.height)
    throw std::invalid_argument(
        "exact_light_assignment_oracle: sample count is not width x height");

  LightAssignmentTruth truth;
  truth.normal_rule = normal_rule;
  truth.eps_rel = c.parameters.eps_rel;
  const double scale = c.scale();
  truth.tau = truth.eps_rel * scale;
  truth.method =
      "exact: double filters with proven error bounds, GMP rationals (CGAL::Exact_rational) and "
      "MPFR cosine enclosures behind them; uniform light grid; band of 14 moves";
  if (normal_rule) truth.method += "; normal rule n.(c-p) > 0";

  const std::size_t n = samples.samples.size();
  const std::size_t blocks = (n + block_size - 1) / block_size;
  std::vector<BlockResult> results(blocks);

  run_with_thread_limit(c.parameters.threads, [&] {
    std::vector<ExactLightVolume> lights(c.ranged_lights.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lights.size(), 1024), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i)
        lights[i] = prepare_light_volume(c.ranged_lights[i]);
    });

    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
    for (const ViewSample& s : samples.samples) {
      if (s.sample_class != SampleClass::regular) continue;
      low = glm::min(low, glm::dvec3(s.position));
      high = glm::max(high, glm::dvec3(s.position));
    }
    if (!(low.x <= high.x)) low = high = glm::dvec3(0.0);  // no regular sample

    const LightBandClassifier band(truth.tau, scale, normal_rule);
    const LightCandidateGrid grid(lights, low, high, band.reach());

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks, 1), [&](const auto& r) {
      std::vector<std::uint32_t> candidates;
      for (std::size_t b = r.begin(); b != r.end(); ++b) {
        BlockResult& out = results[b];
        const std::size_t first = b * block_size, last = std::min(n, first + block_size);
        out.set_sizes.assign(last - first, 0);
        out.ambiguous_sizes.assign(last - first, 0);
        for (std::size_t s = first; s < last; ++s) {
          const ViewSample& sample = samples.samples[s];
          if (sample.sample_class != SampleClass::regular) continue;
          candidates.clear();
          grid.candidates(glm::dvec3(sample.position), candidates);
          out.candidate_pairs += candidates.size();
          for (const std::uint32_t light : candidates) {
            if (!band.may_reach(lights[light], sample.position)) continue;
            const LightBandAnswer answer =
                band.classify(lights[light], sample.position, sample.normal);
            out.band_move_pairs += answer.tried_moves;
            if (answer.member) {
              out.lights.push_back(light);
              ++out.set_sizes[s - first];
            }
            if (answer.ambiguous) {
              out.ambiguous.push_back(light);
              ++out.ambiguous_sizes[s - first];
            }
          }
        }
      }
    });
  });

  // Assemble in sample order.
  std::uint64_t total = 0, total_ambiguous = 0;
  for (const BlockResult& r : results) {
    total += r.lights.size();
    total_ambiguous += r.ambiguous.size();
    truth.candidate_pairs += r.candidate_pairs;
    truth.band_move_pairs += r.band_move_pairs;
  }
  truth.offsets.assign(n + 1, 0);
  truth.ambiguous_offsets.assign(n + 1, 0);
  truth.lights.reserve(total);
  truth.ambiguous_lights.reserve(total_ambiguous);
  std::size_t s = 0;
  for (const BlockResult& r : results) {
    truth.lights.insert(truth.lights.end(), r.lights.begin(), r.lights.end());
    truth.ambiguous_lights.insert(truth.ambiguous_lights.end(), r.ambiguous.begin(),
                                  r.ambiguous.end());
    for (std::size_t k = 0; k < r.set_sizes.size(); ++k, ++s) {
      truth.offsets[s + 1] = truth.offsets[s] + r.set_sizes[k];
      truth.ambiguous_offsets[s + 1] = truth.ambiguous_offsets[s] + r.ambiguous_sizes[k];
    }
  }
  return truth;
}

}  // namespace shadowcts
