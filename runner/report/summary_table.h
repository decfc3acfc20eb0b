#pragma once
// The summary table: one row per case x algorithm x variant x backend (and per directory when a
// record is in several), with verdict, median time and min-max, error figures and work counters.
#include <string>

#include "report_data.h"

namespace shadowcts {

// Every number carries data-record, data-dir, data-field and data-value (the JSON's own spelling)
// so that tests and scripts can read the page back. In a comparison, rows after a record's first
// version mark what differs from it (class "changed", the earlier value in the title).
std::string summary_table_html(const ReportData& data);

// A CSS class suffix made of the verdict's letters only (verdicts come from the input).
std::string verdict_class(const std::string& verdict);

}  // namespace shadowcts
