// The page renders in a real browser: headless chromium takes a screenshot and dumps the DOM of
// the report of a real run. Chromium is part of the test setup (ci/setup.sh); without it the test
// fails rather than skips.
#include <sys/wait.h>

#include <cstdlib>
#include <regex>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "html_report.h"
#include "report_test_support.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using namespace test;

std::string find_chromium() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    for (const char* name : {"chromium", "chromium-browser"}) {
      const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      if (!candidate.parent_path().empty() && fs::exists(candidate)) return candidate.string();
    }
    start = end + 1;
  }
  return "";
}

// Runs chromium headless on the page with a fresh profile; `what` is --screenshot=... or
// --dump-dom; stdout goes to stdout_file. Returns the exit status.
int run_chromium(const std::string& chromium, const fs::path& work, const std::string& what,
                 const fs::path& page, const fs::path& stdout_file) {
  static int runs = 0;  // a fresh profile per run, so no state carries over
  const fs::path profile = work / ("profile" + std::to_string(++runs));
  const std::string command =
      "timeout 180 " + chromium +
      " --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
      " --disable-background-networking --disable-component-update --disable-sync"
      " --user-data-dir='" +
      profile.string() + "' " + what + " --window-size=1280,4000 'file://" +
      fs::absolute(page).string() + "' > '" + stdout_file.string() + "' 2> '" +
      (work / "chromium.stderr").string() + "'";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::size_t count_near(const Rgb8Image& image, int r, int g, int b, int tolerance) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < image.rgb.size(); i += 3)
    n += std::abs(image.rgb[i] - r) <= tolerance && std::abs(image.rgb[i + 1] - g) <= tolerance &&
         std::abs(image.rgb[i + 2] - b) <= tolerance;
  return n;
}

TEST(BrowserRender, ChromiumShowsEveryCaseWithItsPlotAndImages) {
  const std::string chromium = find_chromium();
  if (chromium.empty())
    FAIL() << "chromium is not installed, and this test needs a real browser: run ci/setup.sh "
              "(it installs Debian's chromium)";

  const fs::path dir = fresh_dir("browser");
  run_small_suite(dir);
  const fs::path page = dir / "report.html";
  write_html_report({dir}, page);
  const auto results = nlohmann::json::parse(read_text(dir / "results.json"));

  // The DOM as the browser built it.
  ASSERT_EQ(run_chromium(chromium, dir, "--dump-dom", page, dir / "dom.html"), 0)
      << read_text(dir / "chromium.stderr");
  const std::string dom = read_text(dir / "dom.html");
  std::set<std::string> sections_with_plot;
  const std::regex section(R"re(<section class="case" id="case-[0-9]+" data-case="([^"]*)">)re");
  std::vector<std::pair<std::size_t, std::string>> starts;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), section);
       it != std::sregex_iterator(); ++it)
    starts.emplace_back(std::size_t(it->position()), html_unescape((*it)[1]));
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const std::size_t end = i + 1 < starts.size() ? starts[i + 1].first : dom.size();
    const std::string body = dom.substr(starts[i].first, end - starts[i].first);
    if (body.find("<svg class=\"plot error-vs-time\"") != std::string::npos)
      sections_with_plot.insert(starts[i].second);
  }
  ASSERT_FALSE(results["cases"].empty());
  for (const auto& c : results["cases"])
    EXPECT_TRUE(sections_with_plot.count(c["name"].get<std::string>()))
        << "case " << c["name"] << " has no error-against-time plot in the DOM";
  const std::vector<std::string> sources = image_sources(dom);
  EXPECT_GE(sources.size(), 3u);
  for (const std::string& src : sources) {
    const fs::path file = dir / url_decode(src);
    EXPECT_TRUE(fs::exists(file)) << src;
    EXPECT_GT(read_rgb8(file).width, 0) << src;
  }

  // The screenshot: not blank, and showing the plots and the images.
  const fs::path shot = dir / "screenshot.png";
  ASSERT_EQ(run_chromium(chromium, dir, "--screenshot='" + shot.string() + "'", page,
                         dir / "chromium.stdout"),
            0)
      << read_text(dir / "chromium.stderr");
  const Rgb8Image image = read_rgb8(shot);
  ASSERT_GT(image.width * image.height, 0);
  std::set<int> colours;
  for (std::size_t i = 0; i + 2 < image.rgb.size() && colours.size() < 64; i += 3)
    colours.insert(image.rgb[i] << 16 | image.rgb[i + 1] << 8 | image.rgb[i + 2]);
  EXPECT_GE(colours.size(), 64u) << "the screenshot is (nearly) a single colour";
  // The first plot series' colour (#0072B2): the plots were drawn.
  EXPECT_GT(count_near(image, 0x00, 0x72, 0xB2, 3), 20u);
  // The sky colour of the masks and mismatch maps, far more than the legend swatches hold: the
  // images loaded.
  EXPECT_GT(count_near(image, 110, 150, 200, 3), 5000u);
}

}  // namespace
}  // namespace shadowcts
