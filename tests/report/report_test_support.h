#pragma once
// Shared by the report tests: result directories (written by hand or by a real run) and reading
// the page back.
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowcts::test {

// An empty folder under the temporary directory, named after the test.
std::filesystem::path fresh_dir(const std::string& name);

std::string read_text(const std::filesystem::path& file);

// A hand-written case entry and hard-shadow record in the results.json format.
nlohmann::ordered_json hand_case(const std::string& name);
nlohmann::ordered_json hand_hard_record(const std::string& case_name, const std::string& algorithm,
                                        double median_ms, std::uint64_t leaks);
// (Lists as vectors: a braced single json would not become an array.)
void write_results(const std::filesystem::path& dir,
                   const std::vector<nlohmann::ordered_json>& cases,
                   const std::vector<nlohmann::ordered_json>& results,
                   const std::string& schema = "shadowcts.results/2");

// Runs the suite (ground_blockers.2k, bruteforce and embree, two timed repeats) into dir.
void run_small_suite(const std::filesystem::path& dir);

// Undoes html_escape (and numeric character references).
std::string html_unescape(const std::string& text);

// The page's marked numbers: (data-record, data-dir, data-field) -> data-value, unescaped.
using MarkedValues = std::map<std::tuple<std::string, std::string, std::string>, std::string>;
MarkedValues marked_values(const std::string& page);

// Every src="..." of an <img>, unescaped (still URL-encoded).
std::vector<std::string> image_sources(const std::string& page);

// An image file's pixels as 8-bit RGB (alpha dropped), read with OpenImageIO.
struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};
Rgb8Image read_rgb8(const std::filesystem::path& file);

// Undoes percent-encoding.
std::string url_decode(const std::string& text);

}  // namespace shadowcts::test
