#pragma once
// simd `psv`: the oneTBB + Highway port of reference/psv (Mora 2016): the reference's TOP tree
// built in parallel, the four queries in packets of samples with node tests in vector lanes.
#include <memory>

#include "shadowcts/algorithm.h"

namespace shadowcts {

// id "psv", backend "simd"; the reference's variants (psv::psv_variants()).
std::unique_ptr<Algorithm> make_simd_psv();

}  // namespace shadowcts
