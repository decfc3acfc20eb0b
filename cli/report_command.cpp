#include "report_command.h"

#include <filesystem>

#include "core/atomic_file.h"
#include "runner/report/html_report.h"
#include "runner/report/run_comparison.h"
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

int compare_report_command(const std::string& baseline_dir,
                           const std::vector<std::string>& new_dirs, const std::string& out,
                           double max_slowdown, std::ostream& log) {
  namespace fs = std::filesystem;
  if (new_dirs.size() != 1)
    throw UsageError("report --baseline OLD: give exactly one new result directory");
  // Not the run folder by default: a run refuses to replace a folder holding foreign files.
  if (out.empty()) throw UsageError("report --baseline: give --out DIR (or --out FILE.html)");
  const fs::path target(out);
  const bool page_given = target.extension() == ".html";
  const fs::path page = page_given ? target : target / "compare.html";
  const fs::path junit = page_given ? target.parent_path() / (target.stem().string() + ".junit.xml")
                                    : target / "compare.junit.xml";
  const ReportData data = load_report_data({fs::path(baseline_dir), fs::path(new_dirs.front())},
                                           fs::absolute(page).parent_path());
  RunComparison comparison = compare_runs(data, max_slowdown);
  // The terminal and the page name the runs as the command line did.
  comparison.old_label = baseline_dir;
  comparison.new_label = new_dirs.front();
  print_comparison(comparison, log);
  std::error_code ec;
  if (!page.parent_path().empty()) fs::create_directories(page.parent_path(), ec);
  write_file_atomically(page, comparison_html(comparison));
  write_file_atomically(junit, comparison_junit(comparison));
  log << "wrote " << page.string() << ", " << junit.string() << "\n";
  return comparison.count("regression") > 0 ? exit_conformance_failure : exit_pass;
}

}  // namespace shadowcts
