#pragma once
// Two runs compared record by record (`shadowcts report --baseline OLD NEW`): verdict changes,
// new and removed records, median-time ratios flagged only beyond the spread of the repeats, and
// changes of the error figures. Records are matched by their stable name.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "report_data.h"

namespace shadowcts {

struct TimeSpread {
  double median = 0, min = 0, max = 0;  // min/max: of the timed repeats, else the median
};

struct ErrorChange {
  std::string key;            // dotted key inside "error"
  std::string before, after;  // display text; "absent" where one side lacks it
  bool worse = false;         // a figure where more is worse (leaks, misses, errors) grew
};

struct RecordChange {
  std::string name, label, case_name;
  std::string old_verdict, new_verdict;  // empty on the side the record is absent from
  bool verdict_worse = false, verdict_better = false;
  std::optional<TimeSpread> old_time, new_time;
  std::optional<double> time_ratio;  // new median / old median
  bool slower = false, faster = false;
  std::vector<ErrorChange> errors;

  bool added() const { return old_verdict.empty(); }
  bool removed() const { return new_verdict.empty(); }
  // What makes `report --baseline` exit 1 and JUnit carry a failure.
  bool regression() const { return verdict_worse || slower; }
  bool changed() const { return old_verdict != new_verdict || slower || faster || !errors.empty(); }
  // "regression", "fixed", "changed", "new", "removed" or "unchanged".
  std::string kind() const;
};

struct RunComparison {
  std::string old_label, new_label;
  double max_slowdown = 1.5;
  std::vector<RecordChange> records;  // new run's order, then the removed ones

  std::size_t count(const std::string& kind) const;
};

// Verdicts rank Pass < QualityWarning < Fail < Crash = Timeout; a move up is worse. NotSupported
// is unranked: to or from it is a change, except that a NotSupported record that now runs and
// fails or crashes is a regression. Slower (faster) means the median ratio is above max_slowdown
// (below its inverse) and the min–max ranges of the repeats do not overlap, so noise between
// repeats is not reported. `data` holds exactly two directories: the baseline, then the new run.
RunComparison compare_runs(const ReportData& data, double max_slowdown);

// One self-contained page: counts, then tables of regressions, fixes, other changes, new and
// removed records (table ids "regressions", "fixes", "changes", "new-records", "removed-records";
// rows carry data-record and data-kind).
std::string comparison_html(const RunComparison& comparison);

// JUnit XML: one testcase per record of the new run, a <failure> for each regression; removed
// records are <skipped>.
std::string comparison_junit(const RunComparison& comparison);

// The terminal summary: one line per record that is not unchanged, then the counts.
void print_comparison(const RunComparison& comparison, std::ostream& out);

}  // namespace shadowcts
