#pragma once
// The per-sample exact light set: one list per regular sample holding exactly the lights whose
// volume contains it (exact predicates, candidates from the light BVH with the sample as a point
// box). The optimal efficiency of Paper II's "Deferred" baseline, whose stencil test is exact per
// sample.
#include "shadowcts/algorithm.h"

namespace shadowcts {

AlgorithmOutput assign_lights_brute(const Case& c, const ViewSamples& samples);

}  // namespace shadowcts
