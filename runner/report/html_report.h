#pragma once
// DIR/report.html: one self-contained page (inline CSS and SVG, no script, no network; images
// referenced relative to the page) built from one or several result directories.
#include <filesystem>
#include <string>
#include <vector>

#include "report_data.h"

namespace shadowcts {

// The page for a loaded model. Deterministic: the same results.json files and page location give
// the same bytes.
std::string render_html_report(const ReportData& data);

// Reads results.json of every directory, merges them (shards: union of cases; a record present in
// several directories: shown side by side, differences marked) and writes out_file completely or
// not at all. Throws InputError for unreadable or malformed results.json, std::runtime_error when
// out_file cannot be written.
void write_html_report(const std::vector<std::filesystem::path>& result_dirs,
                       const std::filesystem::path& out_file);

}  // namespace shadowcts
