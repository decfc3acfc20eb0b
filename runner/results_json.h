#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "machine_info.h"
#include "run_record.h"

namespace shadowcts {

// The schema results.json declares (docs/results-schema.md); the report also reads version 1.
inline constexpr const char* results_schema = "shadowcts.results/2";

// results.json (docs/results-schema.md): one record per case x algorithm x variant x backend.
void write_results_json(const std::filesystem::path& path, const std::vector<CaseSummary>& cases,
                        const std::vector<RunRecord>& records, std::uint32_t threads,
                        const MachineInfo& machine);

}  // namespace shadowcts
