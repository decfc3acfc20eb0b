// End-to-end: the runner through the registry, and the tool's exit codes and outputs.
#include "shadowcts/runner.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/errors.h"
#include "shadowcts/registry.h"
#include "tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using testing::read_file;
using testing::run_tool;

fs::path fresh_dir(const std::string& name) {
  return testing::fresh_dir("runner_test_" + name);
}

RunOptions small_run(const fs::path& out, std::uint32_t threads) {
  RunOptions o;
  o.fixtures = {"ground_blockers.2k", "shared_edges.1k"};
  o.out_dir = out.string();
  o.repeats = 1;
  o.threads = threads;
  // Exact algorithms and one approximate baseline: enough to exercise every output path fast.
  o.algorithms = {{"bruteforce", ""}, {"embree", ""}, {"ptsv", "twopass"}, {"shadowmap", "1k"}};
  return o;
}

TEST(Runner, WritesResultsJunitAndImagesAndPasses) {
  const fs::path out = fresh_dir("outputs");
  std::ostringstream log, err;
  const int code = run_suite(small_run(out, 2), builtin_registry(), log, err);
  EXPECT_EQ(code, exit_pass) << log.str();
  const auto results = nlohmann::json::parse(read_file(out / "results.json"));
  EXPECT_EQ(results["schema"], "shadowcts.results/2");
  ASSERT_EQ(results["cases"].size(), 2u);
  bool ran_bruteforce = false;
  for (const auto& r : results["results"]) {
    if (r["verdict"] == "NotSupported") continue;
    if (r["algorithm"] == "shadowmap") {
      // Approximate by design: its mismatches, within its declared ceiling, are figures.
      EXPECT_TRUE(r["verdict"] == "Pass" || r["verdict"] == "QualityWarning") << r.dump();
    } else {
      EXPECT_EQ(r["verdict"], "Pass") << r.dump();
      EXPECT_EQ(r["error"]["leaks"], 0);
    }
    ran_bruteforce |= r["algorithm"] == "bruteforce";
    for (const auto& image : r["images"]) EXPECT_TRUE(fs::exists(out / image.get<std::string>()));
  }
  EXPECT_TRUE(ran_bruteforce);
  for (const auto& c : results["cases"])
    EXPECT_TRUE(fs::exists(out / c["oracles"]["hard"]["mask_image"].get<std::string>()));
  const std::string junit = read_file(out / "junit.xml");
  EXPECT_NE(junit.find("<testsuites"), std::string::npos);
  EXPECT_NE(junit.find("hard.bruteforce.exact.reference.ground_blockers.2k"), std::string::npos);
  // The plan is printed: oracle and what is left out.
  EXPECT_NE(log.str().find("oracle:"), std::string::npos);
  EXPECT_NE(log.str().find("left out:"), std::string::npos);
  // No partial files left behind.
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
}

// Without a terminal, long steps print plain progress lines (once a minute by default; here
// every 10 ms, so the G-buffer pass and the oracle of a 100k-triangle case show some) with the
// phase's done / total.
TEST(Runner, PrintsPlainProgressLinesWhenStderrIsNoTerminal) {
  const fs::path out = fresh_dir("progress_lines");
  RunOptions o;
  o.fixtures = {"gate_house.100k"};
  o.out_dir = out.string();
  o.repeats = 1;
  o.threads = 1;
  o.algorithms = {{"embree", ""}};
  o.progress_lines = true;
  o.progress_line_seconds = 0.01;
  std::ostringstream log, err;
  ASSERT_EQ(run_suite(o, builtin_registry(), log, err), exit_pass) << log.str() << err.str();
  const std::string lines = err.str();
  EXPECT_NE(lines.find("progress: [1/1] gate_house.100k: "), std::string::npos) << lines;
  EXPECT_NE(lines.find(" / "), std::string::npos) << lines;  // a phase that counts its work
  // ... and says what it counts (phase_progress::begin's unit): "1200 / 65536 view samples (".
  EXPECT_TRUE(std::regex_search(lines, std::regex("[0-9]+ / [0-9]+ [a-z][a-z ]* \\("))) << lines;
  EXPECT_EQ(lines.find("\r"), std::string::npos);  // no terminal control characters
}

// softtile:grid16 [simd] alone on dir/case.json, into dir/out, without images.
RunOptions softtile_run(const fs::path& dir) {
  RunOptions o;
  o.case_files = {(dir / "case.json").string()};
  o.out_dir = (dir / "out").string();
  o.algorithms = {{"softtile", "grid16"}};
  o.backends = {"simd"};
  o.repeats = 1;
  o.images = false;
  return o;
}

// The soft-shadow oracles count their samples too (a 1080p exact oracle runs for many minutes).
TEST(Runner, SoftShadowOraclesReportTheirSamplesInProgressLines) {
  for (const OracleChoice oracle : {OracleChoice::exact, OracleChoice::embree}) {
    const fs::path dir = fresh_dir(oracle == OracleChoice::exact ? "soft_exact" : "soft_sampled");
    std::ofstream(dir / "case.json") << R"({"scene": {"generator": "foliage", "triangles": 10000},
                                             "camera": {"width": 96, "height": 64}})";
    RunOptions o = softtile_run(dir);
    o.threads = 1;
    o.oracle = oracle;
    o.progress_lines = true;
    o.progress_line_seconds = 0.01;
    std::ostringstream log, err;
    ASSERT_EQ(run_suite(o, builtin_registry(), log, err), exit_pass) << log.str() << err.str();
    EXPECT_TRUE(
        std::regex_search(err.str(), std::regex("soft oracle — [0-9]+ / 6144 view samples \\(")))
        << err.str();
  }
}

// The automatic soft-shadow oracle follows the exact oracle's estimated work, not the sample
// count: 1,200 samples under a 60-degree sun (about 840,000 projected blades to unite, minutes of
// exact Boolean operations) get the sampled oracle and the reason; under a 2-degree sun the exact
// one.
TEST(Runner, WideSunGetsTheSampledSoftOracleWithTheReasonNarrowSunTheExactOne) {
  for (const int degrees : {60, 2}) {
    const fs::path dir = fresh_dir("sun_" + std::to_string(degrees));
    std::ofstream(dir / "case.json") << R"({"scene": {"generator": "foliage", "triangles": 10000},
               "camera": {"width": 40, "height": 30},
               "light": {"type": "sun", "direction": [0.2, 1, 0.1], "angular_radius_degrees": )"
                                     << degrees << "}}";
    const RunOptions o = softtile_run(dir);
    std::ostringstream log, err;
    ASSERT_EQ(run_suite(o, builtin_registry(), log, err), exit_pass) << log.str() << err.str();
    const auto results = nlohmann::json::parse(read_file(dir / "out" / "results.json"));
    const auto& soft = results["cases"][0]["oracles"]["soft"];
    std::string why;
    for (const auto& line : results["cases"][0]["left_out"])
      if (line.get<std::string>().starts_with("exact soft-shadow oracle")) why = line;
    if (degrees == 60) {
      EXPECT_FALSE(soft["exact"].get<bool>()) << soft.dump();
      EXPECT_NE(why.find("projected casters to unite"), std::string::npos) << why;
      EXPECT_NE(why.find("above its limit of 300 s"), std::string::npos) << why;
    } else {
      EXPECT_TRUE(soft["exact"].get<bool>()) << soft.dump();
      EXPECT_EQ(why, "");
    }
  }
}

// Judged by the fast oracle, the embree peer would be judged by Embree itself: the exact oracle
// re-decides a deterministic subset of its robust samples, and the plan says so.
TEST(Runner, FastOracleHasTheEmbreePeerSpotCheckedByTheExactOracle) {
  const fs::path out = fresh_dir("embree_spot_check");
  RunOptions o = small_run(out, 2);
  o.fixtures = {"shared_edges.1k"};
  o.algorithms = {{"embree", ""}, {"bruteforce", ""}};
  o.oracle = OracleChoice::embree;
  o.images = false;
  std::ostringstream log, err;
  ASSERT_EQ(run_suite(o, builtin_registry(), log, err), exit_pass) << log.str() << err.str();
  const auto results = nlohmann::json::parse(read_file(out / "results.json"));
  EXPECT_NE(log.str().find("spot-checks up to 4096"), std::string::npos) << log.str();
  int peers = 0;
  for (const auto& r : results["results"]) {
    if (r["algorithm"] != "embree") {
      EXPECT_FALSE(r["error"].contains("exact_spot_check")) << r.dump();
      continue;
    }
    ++peers;
    EXPECT_EQ(r["verdict"], "Pass") << r.dump();
    const auto& check = r["error"]["exact_spot_check"];
    EXPECT_GT(check["checked"].get<int>(), 500) << r.dump();
    EXPECT_LE(check["checked"].get<int>(), 4096);
    EXPECT_EQ(check["robust_mismatches"], 0);
  }
  EXPECT_EQ(peers, 1);
}

TEST(Runner, OutputsAreIdenticalForOneAndTwoThreads) {
  const fs::path one = fresh_dir("threads1"), two = fresh_dir("threads2");
  std::ostringstream log, err;
  ASSERT_EQ(run_suite(small_run(one, 1), builtin_registry(), log, err), exit_pass);
  ASSERT_EQ(run_suite(small_run(two, 2), builtin_registry(), log, err), exit_pass);
  std::size_t images = 0;
  for (const auto& entry : fs::recursive_directory_iterator(one / "images")) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), one);
    EXPECT_EQ(read_file(entry.path()), read_file(two / relative)) << relative;
    ++images;
  }
  EXPECT_GT(images, 0u);
  // results.json differs only in timings and the thread count.
  auto strip = [](nlohmann::json j) {
    j.erase("threads");
    for (auto& r : j["results"]) r.erase("time_ms");
    for (auto& c : j["cases"])
      for (auto& [kind, oracle] : c["oracles"].items()) oracle.erase("time_ms");
    return j.dump();
  };
  EXPECT_EQ(strip(nlohmann::json::parse(read_file(one / "results.json"))),
            strip(nlohmann::json::parse(read_file(two / "results.json"))));
}

TEST(Runner, ThreeShardsTogetherEqualTheUnshardedRun) {
  auto records_of = [](const fs::path& dir) {
    std::map<std::string, nlohmann::json> by_name;
    const auto results = nlohmann::json::parse(read_file(dir / "results.json"));
    for (auto r : results["results"]) {
      r.erase("time_ms");
      by_name[r["name"]] = r;
    }
    return by_name;
  };
  RunOptions whole = small_run(fresh_dir("unsharded"), 2);
  whole.fixtures = {"ground_blockers.2k", "shared_edges.1k", "closed_shapes.1k", "model.spider"};
  whole.algorithms = {{"embree", ""}};
  std::ostringstream log, err;
  ASSERT_EQ(run_suite(whole, builtin_registry(), log, err), exit_pass);
  std::map<std::string, nlohmann::json> merged;
  std::size_t cases_seen = 0;
  for (std::uint32_t shard = 0; shard < 3; ++shard) {
    RunOptions part = whole;
    part.out_dir = fresh_dir("shard" + std::to_string(shard)).string();
    part.shard_index = shard;
    part.shard_count = 3;
    ASSERT_EQ(run_suite(part, builtin_registry(), log, err), exit_pass);
    cases_seen +=
        nlohmann::json::parse(read_file(fs::path(part.out_dir) / "results.json"))["cases"].size();
    for (auto& [name, record] : records_of(part.out_dir)) {
      EXPECT_FALSE(merged.count(name)) << name << " ran in two shards";
      merged[name] = record;
    }
  }
  EXPECT_EQ(cases_seen, whole.fixtures.size());
  EXPECT_EQ(merged, records_of(whole.out_dir));
}

// `run --no-images`: the same records and verdicts, no image file, no image path, and the plan
// says what was left out.
TEST(Tool, NoImagesKeepsEveryVerdictAndWritesNoImage) {
  auto records_of = [](const fs::path& dir) {
    std::map<std::string, nlohmann::json> by_name;
    for (auto r : nlohmann::json::parse(read_file(dir / "results.json"))["results"]) {
      r.erase("time_ms");
      r.erase("images");
      by_name[r["name"]] = r;
    }
    return by_name;
  };
  RunOptions with_images = small_run(fresh_dir("with_images"), 2);
  with_images.fixtures = {"shared_edges.1k"};
  std::ostringstream log, err;
  ASSERT_EQ(run_suite(with_images, builtin_registry(), log, err), exit_pass);

  const fs::path dir = fresh_dir("no_images");
  const fs::path out = dir / "out";
  ASSERT_EQ(run_tool("run --no-images --repeat 1 --fixture shared_edges.1k --algorithm bruteforce "
                     "--algorithm embree --algorithm ptsv:twopass --algorithm shadowmap:1k --out " +
                         out.string(),
                     dir),
            exit_pass)
      << read_file(dir / "stderr.txt");
  EXPECT_EQ(records_of(out), records_of(with_images.out_dir));
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_FALSE(entry.is_regular_file() &&
                 (entry.path().extension() == ".png" || entry.path().extension() == ".exr"))
        << entry.path();
  const auto results = nlohmann::json::parse(read_file(out / "results.json"));
  for (const auto& r : results["results"])
    EXPECT_TRUE(!r.contains("images") || r["images"].empty()) << r["name"];
  const auto& oracle = results["cases"][0]["oracles"]["hard"];
  EXPECT_FALSE(oracle.contains("mask_image")) << oracle.dump();
  EXPECT_NE(read_file(dir / "stdout.txt").find("left out: images (PNG/EXR): --no-images"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(out / "report.html"));
}

TEST(Runner, UnknownAlgorithmIsAUsageErrorBeforeAnythingIsWritten) {
  const fs::path out = fresh_dir("usage") / "never";
  RunOptions o = small_run(out, 1);
  o.algorithms = {{"no_such_algorithm", ""}};
  std::ostringstream log, err;
  EXPECT_THROW(run_suite(o, builtin_registry(), log, err), UsageError);
  EXPECT_FALSE(fs::exists(out));
}

TEST(Tool, BadInputExitsWithTwoAndNamesTheFile) {
  const fs::path dir = fresh_dir("bad_input");
  const fs::path manifest = dir / "broken.json";
  std::ofstream(manifest) << R"({"name": "broken", "scene": {"generator": "ground_blockers",
      "triangles": 1000}, "light": {"type": "directional", "direction": [0, 0, 0]}})";
  EXPECT_EQ(run_tool("run --case " + manifest.string() + " --out " + (dir / "out").string(), dir),
            exit_bad_input);
  const std::string message = read_file(dir / "stderr.txt");
  EXPECT_NE(message.find("broken.json"), std::string::npos) << message;
  EXPECT_NE(message.find("light"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir / "out" / "results.json"));

  std::ofstream(dir / "truncated.json") << R"({"name": "x", "scene": )";
  EXPECT_EQ(run_tool("run --case " + (dir / "truncated.json").string(), dir), exit_bad_input);
  EXPECT_NE(read_file(dir / "stderr.txt").find("truncated.json"), std::string::npos);

  EXPECT_EQ(run_tool("run --fixture no_such_fixture.1k", dir), exit_bad_input);
  EXPECT_EQ(run_tool("run --eps-rel 2", dir), exit_bad_input);
  EXPECT_EQ(run_tool("frobnicate", dir), exit_bad_input);
}

TEST(Tool, ListsFixturesAndAlgorithmsAsJson) {
  const fs::path dir = fresh_dir("list");
  ASSERT_EQ(run_tool("list --json", dir), exit_pass);
  const auto listing = nlohmann::json::parse(read_file(dir / "stdout.txt"));
  EXPECT_FALSE(listing["fixtures"].empty());
  EXPECT_FALSE(listing["default_fixtures"].empty());
  // Every stiff case and fuzz generator it lists runs by name.
  EXPECT_GT(listing["stiff_fixtures"].size(), 30u);
  EXPECT_EQ(listing["fuzz_generators"],
            nlohmann::json::array({"watertight", "degenerate", "differential"}));
  const std::string stiff = listing["stiff_fixtures"][0];
  EXPECT_EQ(
      run_tool("run --repeat 1 --no-images --algorithm bruteforce --out out --fixture " + stiff +
                   " --fixture fuzz." + std::string(listing["fuzz_generators"][2]) + ".1.0",
               dir),
      exit_pass)
      << read_file(dir / "stderr.txt");
  bool bruteforce = false, embree = false;
  for (const auto& a : listing["algorithms"]) {
    bruteforce |= a["id"] == "bruteforce" && a["backend"] == "reference";
    embree |= a["id"] == "embree";
  }
  EXPECT_TRUE(bruteforce);
  EXPECT_TRUE(embree);
}

TEST(Tool, GbufferRoundTripsThroughACaseManifest) {
  const fs::path dir = fresh_dir("gbuffer");
  ASSERT_EQ(run_tool("gbuffer --fixture ground_blockers.2k --out " + (dir / "g.exr").string(), dir),
            exit_pass);
  ASSERT_TRUE(fs::exists(dir / "g.exr"));
  // The same case once with Embree primary rays, once from the G-buffer just written.
  std::ofstream(dir / "rays.json")
      << R"({"name": "rays", "scene": {"generator": "ground_blockers", "triangles": 2000}})";
  std::ofstream(dir / "from_gbuffer.json")
      << R"({"name": "from_gbuffer", "scene": {"generator": "ground_blockers", "triangles": 2000},
            "gbuffer": "g.exr"})";
  ASSERT_EQ(run_tool("run --repeat 1 --algorithm embree --case " + (dir / "rays.json").string() +
                         " --case " + (dir / "from_gbuffer.json").string() + " --out " +
                         (dir / "out").string(),
                     dir),
            exit_pass);
  const auto results = nlohmann::json::parse(read_file(dir / "out" / "results.json"));
  const auto& rays = results["cases"][0];
  const auto& gbuffer = results["cases"][1];
  EXPECT_EQ(rays["samples"]["from"], "embree primary rays");
  EXPECT_NE(gbuffer["samples"]["from"].get<std::string>().find("g.exr"), std::string::npos);
  for (const char* key : {"regular", "sky", "back_facing"})
    EXPECT_EQ(rays["samples"][key], gbuffer["samples"][key]) << key;
  EXPECT_EQ(rays["oracles"]["hard"]["robust_shadowed"],
            gbuffer["oracles"]["hard"]["robust_shadowed"]);
  EXPECT_EQ(rays["oracles"]["hard"]["ambiguous"], gbuffer["oracles"]["hard"]["ambiguous"]);
  bool says_why = false;
  for (const auto& why : gbuffer["left_out"])
    says_why |= why.get<std::string>().find("G-buffer") != std::string::npos;
  EXPECT_TRUE(says_why);
}

}  // namespace
}  // namespace shadowcts
