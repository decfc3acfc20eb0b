#pragma once
// Shrinking a failing case with explicit samples to a minimal reproducer. shrink_case: keep only
// the failing sample, then drop every triangle whose removal keeps the failure; greedy and
// quadratic, for the small cases of the fuzz generators and a test that costs a call.
// shrink_case_in_chunks: for a test that costs a process (a crash or a hang), chunks of samples
// and then of triangles, with a test that may stop the shrinking (its budget ran out).
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

// What a test says of a candidate: it still fails, it does not, or shrinking stops here (the
// candidate's answer is unknown: a budget ran out).
enum class CandidateResult { fails, passes, stop };

struct ChunkShrinking {
  fuzzing::SampleCase best;  // the smallest candidate that failed (or the original)
  std::size_t tests = 0;     // the calls of the test that answered fails or passes
  bool stopped = false;      // the test said stop: `best` is as far as shrinking got
};

// The complement step of delta debugging (Zeller and Hildebrandt, "Simplifying and Isolating
// Failure-Inducing Input", 2002): remove chunks of half the samples, then a quarter, ... down to
// single samples, keeping each removal after which the case still fails; then the same for the
// triangles. About 2 k log2(n / k) tests to keep k of n items, for tests that cost a process each.
// Keeps at least one sample and one triangle and the receiver of every kept sample; samples that
// came from the case's camera (explicit_samples false) are all kept. The original is assumed to
// fail (not tested). Deterministic: the same answers give the same candidates.
ChunkShrinking shrink_case_in_chunks(
    const fuzzing::SampleCase& original,
    const std::function<CandidateResult(const fuzzing::SampleCase&)>& test);

}  // namespace shadowcts
