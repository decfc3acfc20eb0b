#include "shadowcts/hard_shadow_oracle.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/ambiguity_band.h"
#include "oracles/caster_bvh.h"
#include "oracles/exact_segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

// The oracle's state kept alive for exponents on demand: the candidate tree and the classifier,
// and a cache (a sample's exponent is computed at most once whatever asks for it).
class ExactLazyExponents final : public LazyRobustExponents {
 public:
  ExactLazyExponents(const Case& c, double scale, const ViewSamples& samples,
                     const HardShadowLight& light)
      : case_(c),
        samples_(samples.samples),
        casters_(case_),
        predicate_(light, scale),
        classifier_(case_, scale, light, casters_, predicate_),
        cache_(samples_.size()) {
    for (auto& e : cache_) e.store(robust_exponent_unknown, std::memory_order_relaxed);
  }

  const ExactBandClassifier& classifier() const { return classifier_; }

  void resolve(const std::vector<std::size_t>& samples,
               std::vector<std::int8_t>& out) const override {
    out.assign(samples.size(), robust_exponent_unknown);
    run_with_thread_limit(case_.parameters.threads, [&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, samples.size(), 16),
          [&](const tbb::blocked_range<std::size_t>& range) {
            std::vector<BandCandidate> candidates;
            for (std::size_t k = range.begin(); k != range.end(); ++k) {
              const std::size_t i = samples[k];
              std::int8_t e = cache_[i].load(std::memory_order_relaxed);
              if (e == robust_exponent_unknown) {
                e = classifier_.classify(samples_[i], candidates, true).robust_exponent;
                cache_[i].store(e, std::memory_order_relaxed);
              }
              out[k] = e;
            }
          });
    });
  }

 private:
  // The caller's case and samples, not copies (one copy of the samples per run): they must outlive
  // every resolve (hard_shadow_oracle.h).
  const Case& case_;
  const std::vector<ViewSample>& samples_;
  const CasterBvh casters_;
  const ExactShadowPredicate predicate_;
  const ExactBandClassifier classifier_;
  mutable std::vector<std::atomic<std::int8_t>> cache_;
};

// ExactLazyExponents, built by the first resolve.
class DeferredExactExponents final : public LazyRobustExponents {
 public:
  DeferredExactExponents(const Case& c, const ViewSamples& samples) : case_(c), samples_(samples) {}

  void resolve(const std::vector<std::size_t>& samples,
               std::vector<std::int8_t>& out) const override {
    std::call_once(built_, [&] {
      run_with_thread_limit(case_.parameters.threads, [&] {
        exponents_ = std::make_unique<const ExactLazyExponents>(case_, case_.scale(), samples_,
                                                                hard_shadow_light(case_));
      });
    });
    exponents_->resolve(samples, out);
  }

 private:
  const Case& case_;
  const ViewSamples& samples_;
  mutable std::once_flag built_;
  mutable std::unique_ptr<const ExactLazyExponents> exponents_;
};

}  // namespace

HardShadowTruth exact_hard_shadow_oracle(const Case& c, const ViewSamples& samples) {
  const HardShadowLight light = hard_shadow_light(c);
  check_receivers(c, samples);
  const std::size_t n = samples.samples.size();
  HardShadowTruth truth;
  truth.method =
      "exact: CGAL Epick orientation predicates (exact rationals where a moved point is not a "
      "double), candidates from a conservative BVH with separating-axis bounds; band over the "
      "whole cube of moves (exact for lit samples, conservative for shadowed ones); robust "
      "exponents on demand";
  truth.exact = true;
  truth.eps_rel = c.parameters.eps_rel;
  const double scale = c.scale();
  truth.tau = c.parameters.eps_rel * scale;
  truth.shadowed.assign(n, 0);
  truth.band.assign(n, BandClass::not_compared);
  truth.robust_exponent.assign(n, ambiguous_at_every_exponent);
  std::shared_ptr<const ExactLazyExponents> lazy;
  run_with_thread_limit(c.parameters.threads, [&] {
    lazy = std::make_shared<const ExactLazyExponents>(c, scale, samples, light);
  });
  const ExactBandClassifier& classifier = lazy->classifier();
  run_with_thread_limit(c.parameters.threads, [&] {
    // Every sample is classified on its own: the result does not depend on the partitioning.
    phase_progress::begin(n, "view samples");
    // Neighbouring regular samples in packets: their queries share the tree's nodes.
    constexpr int lanes = CasterBvh::packet_lanes;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        phase_progress::advance(range.size());
                        std::vector<BandCandidate> candidates[lanes];
                        const ViewSample* packet[lanes];
                        std::size_t index[lanes];
                        SampleTruth truths[lanes];
                        int count = 0;
                        const auto classify_packet = [&] {
                          classifier.classify_packet(packet, count, candidates, truths);
                          for (int l = 0; l < count; ++l) {
                            truth.shadowed[index[l]] = truths[l].shadowed ? 1 : 0;
                            truth.band[index[l]] = truths[l].band;
                            truth.robust_exponent[index[l]] = truths[l].robust_exponent;
                          }
                          count = 0;
                        };
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          if (samples.samples[i].sample_class != SampleClass::regular) continue;
                          packet[count] = &samples.samples[i];
                          index[count++] = i;
                          if (count == lanes) classify_packet();
                        }
                        if (count > 0) classify_packet();
                      });
  });
  truth.lazy = lazy;
  return truth;
}

HardShadowTruth exact_hard_shadow_oracle_with_exponents(const Case& c, const ViewSamples& samples) {
  HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  resolve_robust_exponents(truth);
  return truth;
}

std::shared_ptr<const LazyRobustExponents> exact_robust_exponents_on_demand(
    const Case& c, const ViewSamples& samples) {
  return std::make_shared<const DeferredExactExponents>(c, samples);
}

}  // namespace shadowcts
