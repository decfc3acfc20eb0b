#pragma once
#include <filesystem>
#include <vector>

#include "run_record.h"

namespace shadowcts {

// JUnit XML for CI: one testsuite per case, one testcase per record; Fail and Crash are
// failures, NotSupported is skipped, QualityWarning passes with a system-out note.
void write_junit_xml(const std::filesystem::path& path, const std::vector<RunRecord>& records);

}  // namespace shadowcts
