#pragma once
// The soft-shadow oracles: ground truth for a sun-disk light (DESIGN.md, "Soft shadow, sun disk").
//
// For every regular view sample p with receiver triangle r, the visible fraction of the sun disk:
// every caster triangle T != r (caster mesh, non-zero area), clipped to the half-space in front of
// p towards the light, is projected centrally from p onto the plane perpendicular to the light
// direction d at unit distance, where the disk has radius tan(a); the fraction is
// 1 - area(disk ∩ union of projections) / area(disk). Samples that are not regular get fraction 1
// and are not compared.
//
// All oracles run on Case::parameters.threads threads (0: all) and give the same result for any
// thread count. A case whose light is not a sun disk throws InputError (validate() already rejects
// an angular radius of 0).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// A sample is robust when its band sensitivity is at most this: moving it anywhere in the
// ambiguity band changes its exact visible fraction by at most 1/64 (see SoftShadowTruth).
inline constexpr double soft_robust_sensitivity = 1.0 / 64.0;

struct SoftShadowTruth {
  std::string method;  // how it was obtained, e.g. "exact: CGAL General_polygon_set_2 ..."
  bool exact = false;  // true: exact oracle; false: sampled (see error_bound)
  double eps_rel = 0.0;
  double tau = 0.0;  // eps_rel * case scale: the band of DESIGN.md, "Tolerance"
  // Per sample: the visible fraction of the disk, in [0, 1]; 1 for samples not compared.
  std::vector<double> visible_fraction;
  // Per sample: |true fraction - visible_fraction| <= error_bound. Exact oracle: 0 (the only
  // approximation is the rounding of the projected coordinates to double and the evaluation of
  // the final area in double, both below 1e-12; docs/soft-shadow-oracle.md). Sampled oracle: the
  // Hoeffding bound at failure probability sampled_oracle_failure_probability per sample.
  std::vector<double> error_bound;
  // Per sample: a certified upper bound on |f(p') - f(p)| over every move p' of the sample with
  // |p' - p|_inf <= tau (this contains the 14 band moves of DESIGN.md at every j); 1 where it
  // cannot be bounded (a caster within about tau of the sample). Both oracles compute it the same
  // way (from the casters near the sample's light cone), so they agree on which samples are robust.
  std::vector<double> band_sensitivity;
  // Per sample: compared (regular) and band_sensitivity <= soft_robust_sensitivity.
  std::vector<std::uint8_t> robust;
  // Per sample: whether the sample is compared at all (regular).
  std::vector<std::uint8_t> compared;
  // Work: caster triangles that reached the exact union (sum over samples), and samples decided by
  // the fast paths (no candidate: fraction 1; one projection covering the disk: fraction 0).
  std::uint64_t candidate_triangles = 0;
  std::uint64_t fast_path_samples = 0;
};

// Exact for the double-rounded projected coordinates: CGAL General_polygon_set_2 with the
// circle-segment traits over exact rationals computes disk ∩ union of the projected (and, for
// triangles crossing the fragment plane, homogeneously clipped) triangles; its area is taken by
// Green's theorem over the resulting line segments and circular arcs. Candidate casters come from a
// conservative cone query. exact = true, error_bound = 0, band_sensitivity and robust filled.
SoftShadowTruth exact_soft_shadow_oracle(const Case& c, const ViewSamples& samples);

// What exact_soft_shadow_oracle would unite, without running it, from the projected casters of
// every `stride`-th regular sample (in sample order; the same cone query and projection), times
// `stride`: k per sample, summed and squared. Its cost grows with both (on the 2-core machines,
// 2026-12-05, one core: 60-100 µs per projection for a closed mesh at every k from 1 to 2,100; for
// crossing grass blades under a 60-degree sun, k about 1,300, 460 µs each, the union's crossings
// growing with k^2), so the runner's automatic oracle choice is made from it.
struct ExactSoftShadowWork {
  std::uint64_t projections = 0;     // sum of k
  double squared_projections = 0.0;  // sum of k^2
};
ExactSoftShadowWork estimate_exact_soft_shadow_work(const Case& c, const ViewSamples& samples,
                                                    std::uint32_t stride);

// The per-sample failure probability the sampled oracle's bound is stated at.
inline constexpr double sampled_oracle_failure_probability = 1e-9;

// Stratified Embree 3 occlusion rays (robust mode) over the disk: rays_per_sample is rounded up to
// a square k x k; stratum (i, j) of the unit square, jittered by a deterministic per-sample random
// number generator (Case::parameters.seed), is mapped to the disk by the equal-area concentric map,
// so every stratum has the same gnomonic area. The estimate is the fraction of unblocked rays.
// error_bound = sqrt(ln(2 / delta) / (2 k^2)) with delta = sampled_oracle_failure_probability
// (Hoeffding: the k^2 stratum indicators are independent), plus the float rounding of the ray
// directions, which is far below it. exact = false; band_sensitivity and robust as the exact
// oracle's.
SoftShadowTruth sampled_soft_shadow_oracle(const Case& c, const ViewSamples& samples,
                                           std::uint32_t rays_per_sample);

// The closed form for one triangle: the visible fraction of the sun disk `light` (kind sun_disk)
// seen from p when the only caster is `t` (analytic area of a convex polygon ∩ disk, the triangle
// clipped homogeneously to the half-space in front of p). The unit-test oracle of the exact one;
// accurate to about 1e-13 for non-degenerate inputs. Throws InputError if light is not a sun disk.
double single_triangle_visible_fraction(const ShadowLight& light, const glm::dvec3& p,
                                        const Triangle& t);

}  // namespace shadowcts
