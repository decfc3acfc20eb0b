#include "reference/softtile/softtile_variant.h"

#include <stdexcept>

namespace shadowcts::softtile {

const std::vector<std::string>& variant_names() {
  static const std::vector<std::string> names{
      "grid16", "grid16+rot", "rows3", "rows5", "rows7", "rows15", "rows31", "rows31+rot", "post"};
  return names;
}

Variant parse_variant(const std::string& name) {
  Variant v;
  if (name == "grid16" || name == "grid16+rot") {
    v.rotate = name == "grid16+rot";
    return v;
  }
  if (name == "post") {
    // The post's configuration: the 16 x 16 grid, rotated, disk space normalized by sin(a).
    v.rotate = true;
    v.sine_normalization = true;
    return v;
  }
  for (int rows : {3, 5, 7, 15, 31}) {
    const std::string base = "rows" + std::to_string(rows);
    if (name == base || name == base + "+rot") {
      v.rows = rows;
      v.columns = 31;
      v.rotate = name != base;
      return v;
    }
  }
  throw std::invalid_argument("softtile: unknown variant '" + name + "'");
}

}  // namespace shadowcts::softtile
