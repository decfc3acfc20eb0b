#include "shadowcts/hard_shadow_oracle.h"

#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/ambiguity_band.h"
#include "oracles/caster_bvh.h"
#include "oracles/exact_segment_triangle.h"
#include "oracles/hard_shadow_inputs.h"
#include "oracles/thread_limit.h"

namespace shadowcts {

HardShadowTruth exact_hard_shadow_oracle(const Case& c, const ViewSamples& samples) {
  const HardShadowLight light = hard_shadow_light(c);
  check_receivers(c, samples);
  const std::size_t n = samples.samples.size();

  HardShadowTruth truth;
  truth.method =
      "exact: CGAL Epick orientation predicates (exact rationals where a moved point is not a "
      "double), candidates from a conservative BVH with separating-axis bounds; band over the "
      "whole cube of moves (exact for lit samples, conservative for shadowed ones)";
  truth.exact = true;
  truth.eps_rel = c.parameters.eps_rel;
  truth.tau = c.parameters.eps_rel * c.scale();
  truth.shadowed.assign(n, 0);
  truth.band.assign(n, BandClass::not_compared);
  truth.robust_exponent.assign(n, ambiguous_at_every_exponent);

  run_with_thread_limit(c.parameters.threads, [&] {
    const CasterBvh casters(c);
    const ExactShadowPredicate predicate(light, c.scale());
    const ExactBandClassifier classifier(c, light, casters, predicate);
    // Every sample is classified on its own: the result does not depend on the partitioning.
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<BandCandidate> candidates;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const ViewSample& sample = samples.samples[i];
                          if (sample.sample_class != SampleClass::regular) continue;
                          const SampleTruth t = classifier.classify(sample, candidates);
                          truth.shadowed[i] = t.shadowed ? 1 : 0;
                          truth.band[i] = t.band;
                          truth.robust_exponent[i] = t.robust_exponent;
                        }
                      });
  });
  return truth;
}

}  // namespace shadowcts
