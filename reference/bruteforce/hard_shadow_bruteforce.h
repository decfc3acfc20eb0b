#pragma once
// Brute-force hard shadows: every regular sample against every caster triangle with the exact
// predicate (oracles/exact_segment_triangle.h), after a float box test with a proven-conservative
// margin, and the receiver half-space rule (shadowcts/geometry/receiver_half_space.h): a caster
// counts only where it meets the segment strictly on the light's side of the receiver's plane.
// The definition of the answer, written as plainly as possible; its own counters are the number
// of sample x caster pairs tested and of exact predicate calls (casters the rule's orientations
// exclude before it are not asked).
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "bruteforce", backend "reference", variants {"exact"}.
std::unique_ptr<Algorithm> make_bruteforce_hard_shadow();

}  // namespace shadowcts
