#pragma once
// Legends for the colours of the hard-shadow images (core/hard_shadow_images.cpp paints them) and
// the verdict colours of the page.
#include <string>
#include <vector>

namespace shadowcts {

struct LegendEntry {
  const char* meaning;
  unsigned char r, g, b;
};

// Mask: lit, shadowed, sky, back-facing.
const std::vector<LegendEntry>& shadow_mask_legend();

// Mismatch map: leaks, false shadows, ambiguous (differs / agrees), agreement, sky, back-facing.
const std::vector<LegendEntry>& mismatch_map_legend();

// A legend as a row of colour swatches with their meaning.
std::string legend_html(const std::string& title, const std::vector<LegendEntry>& entries);

}  // namespace shadowcts
