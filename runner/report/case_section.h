#pragma once
// A case's section of the page: its facts (per directory), the left-out list, the two plots and
// the images (oracle mask, each record's mask and mismatch map) with their colour legends.
#include <cstddef>
#include <string>

#include "report_data.h"

namespace shadowcts {

// id="case-<index>", data-case="<name>"; the error-against-time plot is always there (with a note
// when nothing can be drawn), the mismatch curve plot when some record has a curve.
std::string case_section_html(const ReportData& data, std::size_t case_index);

}  // namespace shadowcts
