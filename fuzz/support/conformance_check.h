#pragma once
// The property the geometry fuzzers check, for every registered algorithm that supports a case
// (approximate algorithms, whose mismatches are QualityWarnings, are exempt): the conformance
// property of runner/conformance_violation.h — never throws, never answers NaN or a soft fraction
// outside [0, 1], agrees with the exact hard-shadow oracle on every robust sample, and lists every
// light the exact light-assignment oracle requires, soundly — and every port (a backend other
// than "reference") answers soft shadows and light lists as its reference does: the same
// fractions bit for bit, the same light set per sample. Soft fractions are judged against the
// exact oracle for gross errors only (a robust sample in full umbra answered more than half lit,
// or in full light more than half shadowed), not against their declared budgets: those are
// calibrated on the fixtures, not bounds (docs/soft-shadow-budgets.md), and the conformance suite
// judges them. A violation is shrunk to a minimal case, written as a reproducer and ends the
// process with abort(), so libFuzzer stores the input too.
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
