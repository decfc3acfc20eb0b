// A case with few samples (a small camera) gives statistical verdicts little to go on: a mean
// error of a dozen samples or a shadow map's mismatch rate of eight is mostly chance. Every
// registered algorithm on such cases must not fail where it is faithful (before the verdicts
// weighed their sample counts, softtile and shadow-map records failed on these cameras), and the
// records must still be judged (Pass or QualityWarning, not all left out).
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

struct SmallCase {
  const char* generator;
  int triangles, width, height;
};

// The cameras where the verdicts of faithful algorithms went wrong (2026-12-06).
constexpr SmallCase small_cases[] = {
    {"foliage", 2000, 5, 5},        {"foliage", 10000, 3, 3},   {"foliage", 10000, 7, 7},
    {"foliage", 10000, 9, 9},       {"foliage", 10000, 13, 13}, {"foliage", 10000, 31, 17},
    {"closed_shapes", 2000, 17, 3}, {"foliage", 10000, 100, 2},
};

TEST(SmallCameras, FaithfulAlgorithmsDoNotFailByChance) {
  const fs::path dir = fs::temp_directory_path() / "shadowcts_small_cameras";
  fs::remove_all(dir);
  fs::create_directories(dir);
  RunOptions options;
  for (const SmallCase& c : small_cases) {
    const std::string name = std::string(c.generator) + "." + std::to_string(c.triangles) + "." +
                             std::to_string(c.width) + "x" + std::to_string(c.height);
    const fs::path manifest = dir / (name + ".json");
    std::ofstream(manifest) << nlohmann::json{
        {"name", name},
        {"scene", {{"generator", c.generator}, {"triangles", c.triangles}}},
        {"camera", {{"width", c.width}, {"height", c.height}}}};
    options.case_files.push_back(manifest.string());
  }
  options.out_dir = (dir / "out").string();
  options.repeats = 1;
  options.images = false;
  std::ostringstream log, err;
  EXPECT_EQ(run_suite(options, builtin_registry(), log, err), exit_pass) << err.str();
  std::ifstream in(dir / "out" / "results.json");
  const auto results = nlohmann::json::parse(in);
  std::map<std::string, int> judged;  // output kind -> records judged
  for (const auto& r : results["results"]) {
    const std::string verdict = r["verdict"];
    EXPECT_NE(verdict, "Fail") << r["name"] << ": " << r["reason"];
    if (verdict == "Pass" || verdict == "QualityWarning") ++judged[r["output"]];
  }
  EXPECT_GT(judged["soft"], 50) << "the soft records were not judged";
  EXPECT_GT(judged["hard"], 50) << "the hard records were not judged";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace shadowcts
