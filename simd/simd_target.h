#pragma once
// Which Highway target the simd backends dispatch to on this machine, for records and benchmarks.
#include <string>

namespace shadowcts::simd {

// E.g. "AVX3" or "AVX2": the best target this build has code for and this CPU runs.
std::string dispatched_target_name();

}  // namespace shadowcts::simd
