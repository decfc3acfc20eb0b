#include "shadowcts/hard_shadow_oracle.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/band_moves.h"
#include "oracles/embree_shadow_rays.h"
#include "oracles/exact_segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/phase_progress.h"
#include "shadowcts/thread_limit.h"

namespace shadowcts {
namespace {

// The receiver half-space rule for one sample position, decided exactly (CGAL) for the casters
// Embree reports: casters whose vertices are all on the light's side count, those with none there
// never do, and a straddling one counts where the exact predicate finds its hit on that side.
struct ExactRule {
  const Case* c;
  const ExactShadowPredicate* predicate;
  ReceiverPlane plane;
  glm::dvec3 position;

  static bool counts(const void* state, std::uint32_t caster) {
    const auto& rule = *static_cast<const ExactRule*>(state);
    const Triangle& t = rule.c->triangles[caster];
    const PlaneReach reach = rule.predicate->reach(rule.plane, t);
    if (reach != PlaneReach::straddles) return reach == PlaneReach::whole;
    return rule.predicate->blocks(t, MovedPoint{rule.position, 0.0, {0, 0, 0}}, rule.plane, reach);
  }
};

// robust_exponent of a sample the estimate finds robust at eps_rel: the largest level 2^e <=
// eps_rel (its moves are a subset of eps_rel's), within the level range; none below it.
std::int8_t exponent_of_robust_estimate(double eps_rel) {
  const int e = int(std::floor(std::log2(eps_rel)));
  if (e < band_min_exponent) return ambiguous_at_every_exponent;
  return std::int8_t(std::min(e, band_max_exponent));
}

}  // namespace

HardShadowTruth embree_hard_shadow_oracle(const Case& c, const ViewSamples& samples) {
  check_receivers(c, samples);
  const std::size_t n = samples.samples.size();
  const double scale = c.scale();
  const double tau = c.parameters.eps_rel * scale;
  // The band's moves exist only while tau >= 2^-24 S; below that every sample is robust.
  const bool has_moves = tau > 0.0 && tau >= std::ldexp(scale, band_min_exponent);
  const std::int8_t robust_exponent = exponent_of_robust_estimate(c.parameters.eps_rel);

  HardShadowTruth truth;
  truth.method =
      "estimated: Embree 3 robust occlusion rays, the receiver half-space rule decided by CGAL "
      "for each hit; band from the 14 moves at tau only (moved origins rounded to float); "
      "robust_exponent records only the class at eps_rel";
  truth.exact = false;
  truth.eps_rel = c.parameters.eps_rel;
  truth.tau = tau;
  truth.shadowed.assign(n, 0);
  truth.band.assign(n, BandClass::not_compared);
  truth.robust_exponent.assign(n, ambiguous_at_every_exponent);

  run_with_thread_limit(c.parameters.threads, [&] {
    const EmbreeShadowRays rays(c);
    const ExactShadowPredicate predicate(hard_shadow_light(c), scale);
    phase_progress::begin(n, "view samples");
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 256),
        [&](const tbb::blocked_range<std::size_t>& range) {
          phase_progress::advance(range.size());
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const ViewSample& sample = samples.samples[i];
            if (sample.sample_class != SampleClass::regular) continue;
            ExactRule rule{&c, &predicate, {}, glm::dvec3(sample.position)};
            if (sample.receiver != no_receiver)
              rule.plane = predicate.receiver_plane(c.triangles[sample.receiver]);
            const EmbreeShadowRays::CasterRule caster_rule{&rule, &ExactRule::counts};
            const bool shadowed = rays.occluded(sample.position, sample.receiver, caster_rule);
            bool robust = true;
            if (has_moves) {
              for (const glm::ivec3& move : band_moves) {
                const glm::vec3 moved(glm::dvec3(sample.position) + tau * glm::dvec3(move));
                rule.position = glm::dvec3(moved);
                if (rays.occluded(moved, sample.receiver, caster_rule) != shadowed) {
                  robust = false;
                  break;
                }
              }
            }
            truth.shadowed[i] = shadowed ? 1 : 0;
            truth.band[i] = !robust    ? BandClass::ambiguous
                            : shadowed ? BandClass::robust_shadowed
                                       : BandClass::robust_lit;
            truth.robust_exponent[i] = robust ? robust_exponent : ambiguous_at_every_exponent;
          }
        });
  });
  return truth;
}

}  // namespace shadowcts
