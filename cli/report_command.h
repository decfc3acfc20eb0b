#pragma once
// `shadowcts report DIR... [--out FILE]`: rebuilds the HTML page from result directories.
#include <ostream>
#include <string>
#include <vector>

namespace shadowcts {

// One directory: the page goes to DIR/report.html unless out_file is given; several directories
// (shards, or runs to compare) need out_file. Throws UsageError or InputError.
int write_report_command(const std::vector<std::string>& result_dirs, const std::string& out_file,
                         std::ostream& log);

}  // namespace shadowcts
