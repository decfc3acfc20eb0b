// The page's colour legends name every colour the hard-shadow images use: read real images of a
// run and look each pixel up in the legend.
#include "colour_legends.h"

#include <set>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "report_test_support.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using namespace test;

using Colour = std::tuple<int, int, int>;

std::set<Colour> colours_of(const std::vector<LegendEntry>& legend) {
  std::set<Colour> out;
  for (const LegendEntry& e : legend) out.insert({e.r, e.g, e.b});
  return out;
}

// The image's colours that the legend does not have.
std::set<Colour> unexplained(const fs::path& image_file, const std::set<Colour>& legend) {
  const Rgb8Image image = read_rgb8(image_file);
  std::set<Colour> out;
  for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const Colour c{image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
    if (!legend.count(c)) out.insert(c);
  }
  return out;
}

TEST(ColourLegends, NameEveryColourOfARunsImages) {
  const fs::path dir = fresh_dir("legends");
  run_small_suite(dir);
  const auto results = nlohmann::json::parse(read_text(dir / "results.json"));
  const std::set<Colour> mask = colours_of(shadow_mask_legend());
  const std::set<Colour> mismatch = colours_of(mismatch_map_legend());
  std::size_t masks = 0, maps = 0;
  for (const auto& c : results["cases"]) {
    const fs::path oracle = dir / c["oracles"]["hard"]["mask_image"].get<std::string>();
    EXPECT_TRUE(unexplained(oracle, mask).empty()) << oracle;
    ++masks;
  }
  for (const auto& r : results["results"]) {
    if (r["verdict"] == "NotSupported") continue;
    for (const auto& image : r["images"]) {
      const std::string path = image.get<std::string>();
      const bool is_map = path.find(".mismatch.") != std::string::npos;
      EXPECT_TRUE(unexplained(dir / path, is_map ? mismatch : mask).empty()) << path;
      ++(is_map ? maps : masks);
    }
  }
  EXPECT_GE(masks, 3u);
  EXPECT_GE(maps, 2u);
}

TEST(ColourLegends, LegendHtmlShowsEachColour) {
  const std::string html = legend_html("mismatch map", mismatch_map_legend());
  EXPECT_NE(html.find("background:#ff0000"), std::string::npos);
  EXPECT_NE(html.find("leak"), std::string::npos);
  EXPECT_NE(html.find("background:#0046ff"), std::string::npos);
  EXPECT_NE(html.find("background:#ffdc00"), std::string::npos);
}

}  // namespace
}  // namespace shadowcts
