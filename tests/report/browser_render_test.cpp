// The page renders in a real browser: headless chromium takes a screenshot and dumps the DOM of
// the report of a real run. Chromium is part of the test setup (ci/setup.sh); without it the test
// fails rather than skips.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <map>
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

// The matrix cells of a DOM dump: data-record -> (class, data-verdict, link target).
struct MatrixCell {
  std::string css_class, verdict, href;
};
std::map<std::string, MatrixCell> matrix_cells(const std::string& dom) {
  std::map<std::string, MatrixCell> cells;
  const std::regex cell(
      R"re(<td class="(cell [^"]*)" data-record="([^"]*)" data-verdict="([^"]*)" title="[^"]*"><a href="#([^"]*)">)re");
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), cell); it != std::sregex_iterator();
       ++it)
    cells[html_unescape((*it)[2])] = MatrixCell{(*it)[1], html_unescape((*it)[3]), (*it)[4]};
  return cells;
}

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// The verdict matrix's cell colours (runner/report/html_report.cpp, .m-Pass and .m-Fail).
constexpr int pass_cell[] = {0x7b, 0xc7, 0x7f}, fail_cell[] = {0xe8, 0x67, 0x5a};

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
  // The verdict matrix comes first: a row per algorithm:variant [backend], a cell per case, each
  // with its record's verdict and a link to the record's row in the summary.
  const std::size_t matrix = dom.find("<table id=\"verdict-matrix\">");
  ASSERT_NE(matrix, std::string::npos);
  ASSERT_FALSE(starts.empty());
  EXPECT_LT(matrix, starts.front().first);
  const std::size_t overview = dom.find("<svg class=\"plot overview\"");
  ASSERT_NE(overview, std::string::npos) << "no overview plot";
  EXPECT_LT(matrix, overview);
  EXPECT_LT(overview, starts.front().first);
  const std::map<std::string, MatrixCell> cells = matrix_cells(dom);
  std::set<std::string> labels;
  for (const auto& r : results["results"]) {
    labels.insert(r["algorithm"].get<std::string>() + ":" + r["variant"].get<std::string>() + " [" +
                  r["backend"].get<std::string>() + "]");
    const auto cell = cells.find(r["name"].get<std::string>());
    ASSERT_NE(cell, cells.end()) << r["name"];
    EXPECT_EQ(cell->second.verdict, r["verdict"].get<std::string>());
    EXPECT_EQ(cell->second.css_class, "cell m-" + r["verdict"].get<std::string>());
    EXPECT_EQ(count_of(dom, " id=\"" + cell->second.href + "\""), 1u) << cell->second.href;
  }
  EXPECT_EQ(cells.size(), results["results"].size());
  const std::string matrix_html = dom.substr(matrix, dom.find("</table>", matrix) - matrix);
  EXPECT_EQ(count_of(matrix_html, "<tr data-label="), labels.size());
  EXPECT_EQ(count_of(matrix_html, "<td class=\"cell"), labels.size() * results["cases"].size());

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
  // The matrix cells are painted: every one is a Pass here, each at least 64 x 30 pixels.
  EXPECT_GT(count_near(image, pass_cell[0], pass_cell[1], pass_cell[2], 2), 1000 * cells.size());
  EXPECT_EQ(count_near(image, fail_cell[0], fail_cell[1], fail_cell[2], 2), 0u);
}

TEST(BrowserRender, MatrixColoursFailuresAndFoldsWhatIsNeverSupported) {
  const std::string chromium = find_chromium();
  if (chromium.empty()) FAIL() << "chromium is not installed: run ci/setup.sh";
  const fs::path run = fresh_dir("browser_matrix_run"), dir = fresh_dir("browser_matrix");
  run_small_suite(run);
  // A copy of the run with bruteforce failing and embree NotSupported everywhere.
  auto results = nlohmann::ordered_json::parse(read_text(run / "results.json"));
  std::string failing;
  for (auto& r : results["results"])
    if (r["algorithm"] == "bruteforce") {
      r["verdict"] = "Fail";
      r["error"]["leaks"] = 7;
      failing = r["name"];
    } else {
      r["verdict"] = "NotSupported";
      r["reason"] = "planted: no such device";
    }
  ASSERT_FALSE(failing.empty());
  std::ofstream(dir / "results.json") << results.dump(2);
  const fs::path page = dir / "report.html";
  write_html_report({dir}, page);

  ASSERT_EQ(run_chromium(chromium, dir, "--dump-dom", page, dir / "dom.html"), 0)
      << read_text(dir / "chromium.stderr");
  const std::string dom = read_text(dir / "dom.html");
  const std::map<std::string, MatrixCell> cells = matrix_cells(dom);
  ASSERT_EQ(cells.size(), 1u);
  EXPECT_EQ(cells.begin()->first, failing);
  EXPECT_EQ(cells.begin()->second.css_class, "cell m-Fail");
  EXPECT_NE(dom.find("7 leaks"), std::string::npos);
  // embree is one folded line with its reason, not a row of grey cells.
  const std::regex folded(
      R"re(<li data-algorithm="embree">.*planted: no such device <span class="count">\(1 record\)</span></li>)re");
  EXPECT_TRUE(std::regex_search(dom, folded));

  const fs::path shot = dir / "screenshot.png";
  ASSERT_EQ(run_chromium(chromium, dir, "--screenshot='" + shot.string() + "'", page,
                         dir / "chromium.stdout"),
            0)
      << read_text(dir / "chromium.stderr");
  const Rgb8Image image = read_rgb8(shot);
  EXPECT_GT(count_near(image, fail_cell[0], fail_cell[1], fail_cell[2], 2), 1000u);
  EXPECT_EQ(count_near(image, pass_cell[0], pass_cell[1], pass_cell[2], 2), 0u);
}

}  // namespace
}  // namespace shadowcts
