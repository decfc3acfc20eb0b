#pragma once
// The top of the page: a verdict matrix (rows algorithm:variant [backend], columns cases) and one
// overview plot per output kind across all cases (error against time, log-log, Pareto front).
#include <cstddef>
#include <string>
#include <vector>

#include "report_data.h"
#include "svg_plot.h"

namespace shadowcts {

// The id of the summary-table row of a record's first version, which matrix cells link to.
std::string record_anchor(std::size_t case_index, std::size_t record_index);

// <table id="verdict-matrix">: one row per label with at least one record that is not
// NotSupported, one cell per case (class "cell m-<verdict>", data-record, data-verdict, a link to
// the record's row), showing the median time and, where it is not zero, the key error figure. A
// record in several directories shows its last version, outlined (class "changed-verdict") when
// its verdict differs from the first directory's. Labels that are NotSupported on every case
// are folded below the table into one line per algorithm with their reasons (ul.not-supported).
std::string verdict_matrix_html(const ReportData& data);

// Per output kind with timed records (hard, soft, lights, in that order): the record's plotted
// error (case_plots.h) against median time over every judged record (not NotSupported, Crash or
// Timeout) of every case, both axes log10, one series per
// algorithm, the Pareto front over all of them. Zero errors cannot lie on a log axis: they are
// drawn one decade below the smallest non-zero error (or at 1e-6), and the axis label says so.
std::vector<Plot> overview_plots(const ReportData& data);

}  // namespace shadowcts
