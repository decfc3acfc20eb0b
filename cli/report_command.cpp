#include "report_command.h"

#include <filesystem>

#include "core/report/html_report.h"
#include "shadowcts/errors.h"
#include "shadowcts/runner.h"

namespace shadowcts {

int write_report_command(const std::vector<std::string>& result_dirs, const std::string& out_file,
                         std::ostream& log) {
  if (result_dirs.empty()) throw UsageError("report: give at least one result directory");
  if (result_dirs.size() > 1 && out_file.empty())
    throw UsageError("report: several directories need --out FILE (which of them would hold it?)");
  const std::vector<std::filesystem::path> dirs(result_dirs.begin(), result_dirs.end());
  const std::filesystem::path out =
      out_file.empty() ? dirs.front() / "report.html" : std::filesystem::path(out_file);
  write_html_report(dirs, out);
  log << "wrote " << out.string() << "\n";
  return exit_pass;
}

}  // namespace shadowcts
