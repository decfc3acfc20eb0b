#pragma once
// The two hard-shadow oracles: ground truth for point and directional lights.
//
// Both answer, for every regular view sample p with receiver triangle r: does some caster
// triangle T != r (closed, non-zero area, of a mesh with caster == true) meet the closed segment
// from p to the point light, or the closed ray from p towards a directional light? Both also
// classify each sample in the ambiguity band (DESIGN.md, "Tolerance: the ambiguity band").
// Samples that are not regular get shadowed = 0 and band = not_compared.
//
// Both run on Case::parameters.threads threads (0: all) and give the same result for any
// thread count. A case without a point or directional light throws InputError.
#include <memory>

#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_truth.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Exact for the float inputs: CGAL exact predicates on a provably conservative candidate set;
// moved sample positions keep exact coordinates. exact = true.
// robust_exponent is robust_exponent_unknown for every regular sample: truth.lazy computes it on
// demand (compare_hard_shadows does, for the samples an implementation answers differently). For
// that truth.lazy refers to `c` and `samples`: they must outlive every use of it (reset it to
// drop that dependence; an unknown exponent then throws std::logic_error where it is needed).
HardShadowTruth exact_hard_shadow_oracle(const Case& c, const ViewSamples& samples);
// The same with every robust_exponent computed (the whole mismatch-curve data; slower).
HardShadowTruth exact_hard_shadow_oracle_with_exponents(const Case& c, const ViewSamples& samples);
// The exact oracle's exponents on demand for a truth obtained earlier (the runner's truth cache):
// the candidate tree is built on the first resolve only, so a cached truth costs nothing until an
// implementation answers differently. Same lifetime rule for `c` and `samples` as truth.lazy.
std::shared_ptr<const LazyRobustExponents> exact_robust_exponents_on_demand(
    const Case& c, const ViewSamples& samples);

// Embree 3 occlusion rays in robust mode. The band is estimated: the 14 moves are traced by
// Embree (moved origins rounded to float) at the run's tau only, so robust_exponent records only
// the class at the run's eps_rel (see the definition). exact = false.
HardShadowTruth embree_hard_shadow_oracle(const Case& c, const ViewSamples& samples);

}  // namespace shadowcts
