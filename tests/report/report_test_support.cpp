#include "report_test_support.h"

#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts::test {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcts_report_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

ordered_json hand_case(const std::string& name) {
  return ordered_json{
      {"name", name},
      {"source", "generator:hand"},
      {"light", "point"},
      {"triangles", 12},
      {"ranged_lights", 0},
      {"resolution", {4, 2}},
      {"samples", {{"from", "hand"}, {"regular", 8}, {"sky", 0}, {"back_facing", 0}}},
      {"oracles",
       {{"hard",
         {{"method", "hand"},
          {"exact", true},
          {"time_ms", 1.5},
          {"eps_rel", 1.52587890625e-05},
          {"tau", 0.001},
          {"robust_lit", 6},
          {"robust_shadowed", 2},
          {"ambiguous", 0},
          {"ambiguous_fraction", 0.0},
          {"mask_image", "images/" + name + "/oracle.mask.png"}}}}},
      {"left_out", ordered_json::array()}};
}

ordered_json hand_hard_record(const std::string& case_name, const std::string& algorithm,
                              double median_ms, std::uint64_t leaks) {
  ordered_json curve = ordered_json::array();
  for (int k = -24; k <= -10; ++k)
    curve.push_back({{"eps_rel_log2", k}, {"robust_mismatches", k < -20 ? leaks : 0}});
  return ordered_json{
      {"name", "hard." + algorithm + ".exact.reference." + case_name},
      {"case", case_name},
      {"output", "hard"},
      {"algorithm", algorithm},
      {"variant", "exact"},
      {"backend", "reference"},
      {"verdict", leaks ? "Fail" : "Pass"},
      {"reason", leaks ? "leaks" : "right"},
      {"time_ms",
       {{"median", median_ms}, {"runs", {median_ms * 1.25, median_ms, median_ms * 0.75}}}},
      {"counters", {{"pair_tests", 1234567}}},
      {"error",
       {{"compared", 8},
        {"robust", 8},
        {"ambiguous", 0},
        {"leaks", leaks},
        {"false_shadows", 0},
        {"ambiguous_disagreements", 0},
        {"robust_mismatch_rate", double(leaks) / 8},
        {"mismatch_curve", curve}}},
      {"images", {"images/" + case_name + "/" + algorithm + ".exact.reference.mask.png"}}};
}

void write_results(const fs::path& dir, const std::vector<ordered_json>& cases,
                   const std::vector<ordered_json>& results, const std::string& schema) {
  fs::create_directories(dir);
  const ordered_json root{{"schema", schema},
                          {"threads", 1},
                          {"cases", ordered_json(cases)},
                          {"results", ordered_json(results)}};
  std::ofstream(dir / "results.json") << root.dump(2);
}

void run_small_suite(const fs::path& dir) {
  RunOptions options;
  options.fixtures = {"ground_blockers.2k"};
  options.algorithms = {{"bruteforce", "exact"}, {"embree", ""}};
  options.out_dir = dir.string();
  options.repeats = 2;
  options.threads = 2;
  std::ostringstream log, err;
  const int code = run_suite(options, builtin_registry(), log, err);
  if (code != exit_pass) throw std::runtime_error("run_suite failed:\n" + log.str() + err.str());
}

std::string html_unescape(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '&') {
      out += text[i];
      continue;
    }
    const std::size_t end = text.find(';', i);
    if (end == std::string::npos) throw std::runtime_error("bare & in page text: " + text);
    const std::string entity = text.substr(i + 1, end - i - 1);
    if (entity == "amp")
      out += '&';
    else if (entity == "lt")
      out += '<';
    else if (entity == "gt")
      out += '>';
    else if (entity == "quot")
      out += '"';
    else if (entity == "#39")
      out += '\'';
    else
      throw std::runtime_error("unexpected entity &" + entity + ";");
    i = end;
  }
  return out;
}

MarkedValues marked_values(const std::string& page) {
  static const std::regex marked(
      R"re(data-record="([^"]*)" data-dir="([0-9]+)" data-field="([^"]*)" data-value="([^"]*)")re");
  MarkedValues out;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), marked);
       it != std::sregex_iterator(); ++it)
    out[{html_unescape((*it)[1]), (*it)[2], html_unescape((*it)[3])}] = html_unescape((*it)[4]);
  return out;
}

std::vector<std::string> image_sources(const std::string& page) {
  static const std::regex img(R"re(<img[^>]*\ssrc="([^"]*)")re");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), img); it != std::sregex_iterator();
       ++it)
    out.push_back(html_unescape((*it)[1]));
  return out;
}

Rgb8Image read_rgb8(const fs::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) throw std::runtime_error("cannot open image " + file.string());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels < 3) throw std::runtime_error(file.string() + ": fewer than 3 channels");
  Rgb8Image image;
  image.width = spec.width;
  image.height = spec.height;
  image.rgb.resize(std::size_t(spec.width) * spec.height * 3);
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, image.rgb.data()))
    throw std::runtime_error(file.string() + ": " + in->geterror());
  return image;
}

std::string url_decode(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size()) {
      out += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += text[i];
    }
  }
  return out;
}

}  // namespace shadowcts::test
