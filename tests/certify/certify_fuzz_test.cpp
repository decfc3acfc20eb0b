// Issue 23, the fuzz profile of `shadowcts certify`: the watertight, degenerate and differential
// generators drive a port for a fixed seed and count. The example port passes a small profile and
// verify accepts its certificate but rejects an edited seed, count or case list; the broken example
// leaks at the shared edges of grid-aligned casters (decided from the geometry it receives), so
// watertight cases Fail, each with a shrunk reproducer that still fails when replayed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "runner/certify.h"
#include "runner/conformance_violation.h"
#include "runner/plugin_backend.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/gbuffer_exr.h"
#include "tests/cli/tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using testing::fresh_dir;
using testing::read_file;
using testing::run_tool;

ordered_json read_certificate(const fs::path& dir) {
  return ordered_json::parse(read_file(dir / "certificate.json"));
}

// A copy of the certificate with `edit` applied and the content hash recomputed, as someone who
// edits a certificate on purpose would; returns verify's exit code, its output in `said`.
template <typename Edit>
int verify_edited(const fs::path& dir, const std::string& name, Edit edit, std::string& said) {
  const fs::path to = fresh_dir(name);
  ordered_json c = read_certificate(dir);
  edit(c);
  c.erase("certificate_sha256");
  c["certificate_sha256"] = certificate_content_sha256(c);
  std::ofstream(to / "certificate.json") << c.dump(2) << "\n";
  const int code = run_tool("certify verify '" + to.string() + "'", to);
  said = read_file(to / "stdout.txt");
  return code;
}

constexpr unsigned fuzz_count = 8;  // per generator

TEST(CertifyFuzz, ExamplePortPassesAndVerifyChecksSeedCountAndCaseList) {
  const fs::path dir = fresh_dir("certify_fuzz_example");
  const int code = run_tool(std::string("certify --backend '") + EXAMPLE_BRUTEFORCE_C +
                                "' --profile fuzz --fuzz-seed 7 --fuzz-count " +
                                std::to_string(fuzz_count) + " --timeout 120 --threads 1 --out out",
                            dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 0) << log;
  const ordered_json c = read_certificate(dir / "out");
  EXPECT_EQ(c["profile"], "fuzz");
  EXPECT_EQ(c["fuzz"]["seed"], 7);
  EXPECT_EQ(c["fuzz"]["count"], fuzz_count);
  ASSERT_EQ(c["cases"].size(), 3 * fuzz_count);
  EXPECT_EQ(c["cases"][0]["name"], "fuzz.watertight.7.0");
  EXPECT_EQ(c["cases"][fuzz_count]["name"], "fuzz.degenerate.7.0");
  EXPECT_EQ(c["cases"][3 * fuzz_count - 1]["name"],
            "fuzz.differential.7." + std::to_string(fuzz_count - 1));
  std::size_t passed = 0;
  for (const ordered_json& r : c["results"]) {
    if (r["verdict"] == "Pass") {
      ++passed;
      continue;
    }
    // A case whose samples the exact oracle calls all ambiguous (or all back-facing) judges
    // nothing, whatever the port answers; allowed on fuzz cases.
    EXPECT_EQ(r["verdict"], "NotSupported") << r.dump();
    EXPECT_EQ(r["reason"].get<std::string>().rfind("no robust sample to judge", 0), 0u) << r.dump();
  }
  EXPECT_GE(passed, 2 * fuzz_count);
  EXPECT_TRUE(c["reproducers"].empty());
  // The workers ran the generator's own samples, not a camera's.
  const ordered_json results = ordered_json::parse(read_file(dir / "out" / "results.json"));
  EXPECT_EQ(results["cases"][0]["samples"]["from"], "the fuzz generator");

  ASSERT_EQ(run_tool("certify verify out", dir), 0) << read_file(dir / "stdout.txt");
  std::string said;
  EXPECT_EQ(
      verify_edited(
          dir / "out", "certify_fuzz_seed", [](ordered_json& e) { e["fuzz"]["seed"] = 8; }, said),
      1);
  EXPECT_NE(said.find("for fuzz seed 8 and count 8"), std::string::npos) << said;
  EXPECT_EQ(
      verify_edited(
          dir / "out", "certify_fuzz_count", [](ordered_json& e) { e["fuzz"]["count"] = 3; }, said),
      1);
  EXPECT_NE(said.find("not the fuzz profile's 9 cases in order for fuzz seed 7 and count 3"),
            std::string::npos)
      << said;
  // A case replaced by another of the same generator, with its own inputs hash: still not the
  // profile's list.
  EXPECT_EQ(verify_edited(
                dir / "out", "certify_fuzz_list",
                [](ordered_json& e) {
                  e["cases"][1]["name"] = "fuzz.watertight.7.99";
                  e["cases"][1]["input_sha256"] = fixture_input_sha256("fuzz.watertight.7.99");
                  e["results"][1]["case"] = "fuzz.watertight.7.99";
                },
                said),
            1);
  EXPECT_NE(said.find("is not the fuzz profile's"), std::string::npos) << said;
  // An input hash that does not belong to its case (a generator whose cases changed).
  EXPECT_EQ(
      verify_edited(
          dir / "out", "certify_fuzz_input",
          [](ordered_json& e) { e["cases"][2]["input_sha256"] = std::string(64, '0'); }, said),
      1);
  EXPECT_NE(said.find("case fuzz.watertight.7.2: its inputs hash differently"), std::string::npos)
      << said;
}

TEST(CertifyFuzz, BrokenPortFailsWatertightCasesWithReproducersThatReplay) {
  const fs::path dir = fresh_dir("certify_fuzz_broken");
  // TMPDIR: the broken example's marker files (a fault of foliage.* only) stay in the folder.
  const int code =
      testing::run_shell("TMPDIR=\"$PWD\" exec '" SHADOWCTS_TOOL
                         "' certify --backend '" EXAMPLE_BROKEN "' --profile fuzz --fuzz-count " +
                             std::to_string(fuzz_count) + " --timeout 120 --threads 1 --out out\n",
                         dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 1) << log;
  const ordered_json c = read_certificate(dir / "out");
  ASSERT_EQ(c["results"].size(), 3 * fuzz_count) << log;
  std::size_t fails = 0;
  for (const ordered_json& r : c["results"]) {
    const std::string name = r["case"];
    if (r["verdict"] == "Fail") {
      ++fails;
      // Only the watertight generator's casters lie on the grid the fault looks for.
      EXPECT_EQ(name.rfind("fuzz.watertight.", 0), 0u) << r.dump();
      EXPECT_NE(r["reason"].get<std::string>().find("leak"), std::string::npos) << r.dump();
    } else {
      EXPECT_EQ(r["verdict"], "Pass") << r.dump();
    }
  }
  EXPECT_GE(fails, 1u) << log;
  ASSERT_EQ(c["reproducers"].size(), fails) << c["reproducers"].dump();
  EXPECT_EQ(run_tool("certify verify out", dir), 1);

  PluginBackend broken(EXAMPLE_BROKEN);
  const auto port = broken.algorithm(0);
  for (const ordered_json& r : c["reproducers"]) {
    SCOPED_TRACE(r.dump());
    EXPECT_EQ(r["verdict"], "Fail");
    EXPECT_TRUE(r["shrunk"].get<bool>());
    EXPECT_EQ(r["samples"], 1);
    EXPECT_LT(r["triangles"].get<std::size_t>(), r["original_triangles"].get<std::size_t>());
    const fs::path manifest = dir / "out" / r["manifest"].get<std::string>();
    EXPECT_NE(
        log.find("reproducer: " + (fs::path("out") / r["manifest"].get<std::string>()).string()),
        std::string::npos);
    // Replayed the way `shadowcts run --case` loads it, through the broken port: the same leak.
    Case replayed = load_case_manifest(manifest.string());
    ViewSamples samples = read_gbuffer_exr(replayed.gbuffer_path);
    classify_samples(replayed, samples, replayed.gbuffer_path);
    const std::optional<Violation> violation =
        find_violation(*port, "faulty", replayed, samples, exact_truths(replayed, samples));
    ASSERT_TRUE(violation.has_value());
    EXPECT_NE(violation->what.find("leak"), std::string::npos) << violation->what;
  }
}

}  // namespace
}  // namespace shadowcts
