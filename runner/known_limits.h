#pragma once
// The documented limits of the suite's own algorithms and peers: records that fail by design.
// A Fail stays a Fail (docs/specification.md: a robust mismatch is one, whoever errs); the record
// also says which limit explains it, so a reader tells a method's known limit from a regression.
// Two sources: the stiff cases built to show a method's limit (a table over record names, below),
// and the limits a fuzz generator declares for the case it built (fixtures/fuzz/generated_case.h).
#include <cstddef>
#include <string>
#include <vector>

#include "fixtures/fuzz/generated_case.h"

namespace shadowcts {

struct RecordLimit {
  const char* records;  // glob over record names, e.g. "hard.embree.*.stiff.light_at_caster_vertex"
  const char* why;
};

// Every entry of the table, for the tests that check each still fails.
const std::vector<RecordLimit>& stiff_record_limits();

// The table's entry whose glob matches the record name, or null.
const RecordLimit* stiff_record_limit(const std::string& record_name);

// Why a failed record is a known limit, or "" when none explains it: the table's entry for its
// name, or a limit the case's generator declared for its algorithm (and variant, where the limit
// names one) that covers every sample it got wrong (`wrong_samples`: the robust mismatches; a
// limit without samples covers them all).
std::string known_limit(const std::string& record_name, const std::string& algorithm_id,
                        const std::string& variant,
                        const std::vector<fuzzing::KnownLimit>& case_limits,
                        const std::vector<std::size_t>& wrong_samples);

}  // namespace shadowcts
