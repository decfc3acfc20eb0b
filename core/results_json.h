#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "run_record.h"

namespace shadowcts {

// results.json, schema "shadowcts.results/1" (docs/results-schema.md): one record per
// case x algorithm x variant x backend.
void write_results_json(const std::filesystem::path& path, const std::vector<CaseSummary>& cases,
                        const std::vector<RunRecord>& records, std::uint32_t threads);

}  // namespace shadowcts
