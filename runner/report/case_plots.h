#pragma once
// The two plots of a case: error against median run time (with its Pareto front) and robust
// mismatches against eps_rel, built from the records' "time_ms" and "error".
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "report_data.h"
#include "svg_plot.h"

namespace shadowcts {

struct ErrorFigure {
  std::string key;  // dotted key inside "error"
  double value = 0;
};

// The figure that stands for a record's error on the error-against-time plot: the robust mismatch
// rate for hard shadows, the mean |e| for soft shadows, the lighting-computation overhead for light
// lists (lighting_ratio: lighting computations over the exact minimum); for kinds not known here,
// the first number whose key speaks of an error, rate or overhead, else the first number. Empty
// when "error" holds no number.
std::optional<ErrorFigure> plotted_error(const std::string& output,
                                         const nlohmann::ordered_json& error);

// Error against median time, x on a log scale; one series per record, marker shape per directory.
Plot error_against_time_plot(const ReportData& data, const ReportCase& c);

// Robust mismatches against log2 eps_rel from "error.mismatch_curve", one line per record and
// directory. Empty when no record of the case has a curve.
std::optional<Plot> mismatch_curve_plot(const ReportData& data, const ReportCase& c);

}  // namespace shadowcts
