#pragma once
// Brute-force hard shadows: every regular sample against every caster triangle with the exact
// predicate (oracles/exact_segment_triangle.h), after a float box test with a proven-conservative
// margin. The definition of the answer, written as plainly as possible; its own counters are the
// number of sample x caster pairs tested and of exact predicate calls.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "bruteforce", backend "reference", variants {"exact"}.
std::unique_ptr<Algorithm> make_bruteforce_hard_shadow();

}  // namespace shadowcts
