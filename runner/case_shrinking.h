#pragma once
// Shrinking a failing case with explicit samples to a minimal reproducer: keep only the failing
// sample, then drop every triangle whose removal keeps the failure. Greedy and quadratic, for the
// small cases of the fuzz generators.
#include <cstddef>
#include <functional>
#include <optional>

#include "fixtures/fuzz/sample_case.h"

namespace shadowcts {

// `still_fails` answers whether a candidate still shows the failure; `failing_sample` (an index
// into the samples), when known, is tried alone first. A receiver of a kept sample is never
// removed; a mesh that loses a triangle is marked open (the reproducer's loader agrees).
fuzzing::SampleCase shrink_case(const fuzzing::SampleCase& original,
                                std::optional<std::size_t> failing_sample,
                                const std::function<bool(const fuzzing::SampleCase&)>& still_fails);

}  // namespace shadowcts
