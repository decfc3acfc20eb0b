#pragma once
// The property the geometry fuzzers check: every registered algorithm that supports a case
// agrees with the exact hard-shadow oracle on every sample the oracle calls robust (approximate
// algorithms, whose mismatches are QualityWarnings, are exempt from that part), never
// throws, and (soft output) never answers NaN or a fraction outside [0, 1]. A violation is
// shrunk to a minimal case, written as a reproducer and ends the process with abort(), so
// libFuzzer stores the input too.
#include <cstddef>
#include <string>
#include <vector>

#include "sample_case.h"

namespace shadowcts::fuzzing {

// A documented limit of a peer that a fuzz input exercises: the algorithm still runs (it must not
// crash, throw or answer NaN), but its answers on the samples concerned are not compared with the
// exact oracle. Only for limits the specification states (docs/specification.md), never for our
// own algorithms.
struct KnownLimit {
  std::string algorithm_id;  // e.g. "embree"
  std::string why;
  // The samples it concerns (indices into the case's samples); empty: the whole case.
  std::vector<std::size_t> samples = {};
};

// `target` names the fuzz target in messages and in the reproducer's folder name. Reproducers go
// to $SHADOWCTS_FUZZ_REPRODUCERS (default: ./fuzz-reproducers).
void check_every_algorithm(const SampleCase& sample_case, const std::string& target,
                           const std::vector<KnownLimit>& known_limits = {});

}  // namespace shadowcts::fuzzing
