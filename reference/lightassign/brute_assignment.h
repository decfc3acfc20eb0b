#pragma once
// The per-sample light set: one list per regular sample holding the lights whose volume contains
// it (light_volume_check.h: exact for spheres; a spot is kept where rounding cannot place the
// sample against its cone, counted as cone_tests_undecided), candidates from the light BVH with the
// sample as a point box. The optimal efficiency of Paper II's "Deferred" baseline, whose stencil
// test is exact per sample.
#include "shadowcts/algorithm.h"

namespace shadowcts {

AlgorithmOutput assign_lights_brute(const Case& c, const ViewSamples& samples);

}  // namespace shadowcts
