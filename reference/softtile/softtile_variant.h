#pragma once
// The variants of the reference `softtile`: which disk bitmask, whether the grid is rotated per
// pixel, and how disk space is normalized. Names: "grid16", "grid16+rot", "rows<N>" and
// "rows<N>+rot" for N in {3, 5, 7, 15, 31}, and "post".
#include <string>
#include <vector>

namespace shadowcts::softtile {

struct Variant {
  int rows = 16;        // scanlines of the disk bitmask
  int columns = 16;     // bits per scanline: 16 (the post's 16 x 16 grid) or 31 (its N x 31 rows)
  bool rotate = false;  // per-pixel random rotation of the grid (seeded, deterministic)
  // false: disk space = light-space xy / (tan(a) z), the disk exactly the unit disk (cone-exact);
  // true: the post's xy / (sin(a) z), whose unit disk is the slightly smaller tan = sin(a) disk.
  bool sine_normalization = false;
};

// The registered variant names, the default first.
const std::vector<std::string>& variant_names();

// Throws std::invalid_argument for a name not in variant_names().
Variant parse_variant(const std::string& name);

}  // namespace shadowcts::softtile
