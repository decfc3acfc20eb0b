#pragma once
// The property the geometry fuzzers check: every registered algorithm that supports a case keeps
// the conformance property (runner/conformance_violation.h: agrees with the exact hard-shadow
// oracle on every robust sample — approximate algorithms, whose mismatches are QualityWarnings,
// are exempt — never throws, and never answers NaN or a soft fraction outside [0, 1]). A
// violation is shrunk to a minimal case, written as a reproducer and ends the process with
// abort(), so libFuzzer stores the input too.
#include <string>
#include <vector>

#include "fixtures/fuzz/generated_case.h"

namespace shadowcts::fuzzing {

// `target` names the fuzz target in messages and in the reproducer's folder name. Reproducers go
// to $SHADOWCTS_FUZZ_REPRODUCERS (default: ./fuzz-reproducers). `known_limits` (from the
// generator) leave a peer's answers uncompared where the specification documents its limits.
void check_every_algorithm(const SampleCase& sample_case, const std::string& target,
                           const std::vector<KnownLimit>& known_limits = {});

}  // namespace shadowcts::fuzzing
