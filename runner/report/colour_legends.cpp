#include "colour_legends.h"

#include <cstdio>

#include "html_text.h"

namespace shadowcts {

// The same colours as core/hard_shadow_images.cpp; tests/report checks them against real images.
const std::vector<LegendEntry>& shadow_mask_legend() {
  static const std::vector<LegendEntry> entries = {
      {"lit", 235, 235, 235},
      {"shadowed", 40, 40, 40},
      {"sky (no surface)", 110, 150, 200},
      {"back-facing (unlit by orientation)", 45, 50, 70},
  };
  return entries;
}

const std::vector<LegendEntry>& mismatch_map_legend() {
  static const std::vector<LegendEntry> entries = {
      {"leak (lit, should be shadowed)", 255, 0, 0},
      {"false shadow (shadowed, should be lit)", 0, 70, 255},
      {"ambiguous, differs from the exact answer", 255, 220, 0},
      {"ambiguous, agrees", 170, 150, 40},
      {"agrees, shadowed", 120, 120, 120},
      {"agrees, lit", 200, 200, 200},
      {"sky", 110, 150, 200},
      {"back-facing / not compared", 45, 50, 70},
  };
  return entries;
}

std::string legend_html(const std::string& title, const std::vector<LegendEntry>& entries) {
  std::string out =
      "<div class=\"legend\"><span class=\"legend-title\">" + html_escape(title) + "</span>";
  for (const LegendEntry& e : entries) {
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", e.r, e.g, e.b);
    out += "<span class=\"legend-entry\"><span class=\"swatch\" style=\"background:";
    out += colour;
    out += "\"></span>" + html_escape(e.meaning) + "</span>";
  }
  return out + "</div>\n";
}

}  // namespace shadowcts
