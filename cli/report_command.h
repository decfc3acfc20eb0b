#pragma once
// `shadowcts report DIR... [--out FILE]`: rebuilds the HTML page from result directories.
// `shadowcts report --baseline OLD NEW --out DIR|FILE.html`: compares two runs.
#include <ostream>
#include <string>
#include <vector>

namespace shadowcts {

// One directory: the page goes to DIR/report.html unless out_file is given; several directories
// (shards, or runs to compare) need out_file. Throws UsageError or InputError.
int write_report_command(const std::vector<std::string>& result_dirs, const std::string& out_file,
                         std::ostream& log);

// The regression page and its JUnit XML: `out` is a folder (created; compare.html and
// compare.junit.xml in it) or a file ending in .html (the JUnit beside it as <stem>.junit.xml).
// Prints the changes; returns exit_conformance_failure (1) when a verdict got worse or a time
// regressed beyond max_slowdown (see run_comparison.h), exit_pass otherwise. Throws UsageError or
// InputError.
int compare_report_command(const std::string& baseline_dir,
                           const std::vector<std::string>& new_dirs, const std::string& out,
                           double max_slowdown, std::ostream& log);

}  // namespace shadowcts
