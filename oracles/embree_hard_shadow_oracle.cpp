#include "shadowcts/hard_shadow_oracle.h"

#include <algorithm>
#include <cmath>
#include <vector>

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
  // casters_near_light, in index order: decided by the exact pass, not by Embree.
  const std::vector<std::uint32_t>* near_light;
  ReceiverPlane plane;
  glm::dvec3 position;

  static bool counts(const void* state, std::uint32_t caster) {
    const auto& rule = *static_cast<const ExactRule*>(state);
    if (std::binary_search(rule.near_light->begin(), rule.near_light->end(), caster)) return false;
    const Triangle& t = rule.c->triangles[caster];
    const PlaneReach reach = rule.predicate->reach(rule.plane, t);
    if (reach != PlaneReach::straddles) return reach == PlaneReach::whole;
    return rule.predicate->blocks(t, MovedPoint{rule.position, 0.0, {0, 0, 0}}, rule.plane, reach);
  }
};

// The casters near a point light, whose box lies within 2^-14 S of it, in index order. Embree's
// segment ends at p + (L - p) rounded, within about 2^-21 S of L, so only there can its hit or its
// miss be that rounding, which the band (moving p, not L) does not cover: a light 1e-7 from a
// blocker's face made the oracle wrong on 226 samples it called robust. These casters are decided
// by the exact predicate for every sample; they are none where the light is away from the geometry.
std::vector<std::uint32_t> casters_near_light(const Case& c, double scale) {
  std::vector<std::uint32_t> near;
  if (!c.light || c.light->kind != ShadowLightKind::point) return near;
  const glm::dvec3 light(c.light->position);
  const double reach = std::ldexp(scale, -14);
  for (std::size_t i = 0; i < c.triangles.size(); ++i) {
    if (!oracle_casts_shadow(c, i)) continue;
    const Triangle& t = c.triangles[i];
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) {
      const double low = std::min({t.v0[k], t.v1[k], t.v2[k]}) - reach;
      const double high = std::max({t.v0[k], t.v1[k], t.v2[k]}) + reach;
      inside = low <= light[k] && light[k] <= high;
    }
    if (inside) near.push_back(std::uint32_t(i));
  }
  return near;
}

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
      "for each hit, casters within 2^-14 S of a point light decided by CGAL alone; band from the "
      "14 moves at tau only (moved origins rounded to float); "
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
    const std::vector<std::uint32_t> near = casters_near_light(c, scale);
    phase_progress::begin(n, "view samples");
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 256),
        [&](const tbb::blocked_range<std::size_t>& range) {
          phase_progress::advance(range.size());
          for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const ViewSample& sample = samples.samples[i];
            if (sample.sample_class != SampleClass::regular) continue;
            ExactRule rule{&c, &predicate, &near, {}, glm::dvec3(sample.position)};
            if (sample.receiver != no_receiver)
              rule.plane = predicate.receiver_plane(c.triangles[sample.receiver]);
            const EmbreeShadowRays::CasterRule caster_rule{&rule, &ExactRule::counts};
            const auto occluded = [&](const glm::vec3& origin) {
              for (const std::uint32_t t : near)
                if (t != sample.receiver &&
                    predicate.blocks(c.triangles[t], MovedPoint{glm::dvec3(origin), 0.0, {0, 0, 0}},
                                     rule.plane))
                  return true;
              return rays.occluded(origin, sample.receiver, caster_rule);
            };
            const bool shadowed = occluded(sample.position);
            bool robust = true;
            if (has_moves) {
              for (const glm::ivec3& move : band_moves) {
                const glm::vec3 moved(glm::dvec3(sample.position) + tau * glm::dvec3(move));
                rule.position = glm::dvec3(moved);
                if (occluded(moved) != shadowed) {
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
