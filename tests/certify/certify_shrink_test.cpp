// Issue 23: a fuzz case on which a port crashes or hangs is shrunk with a worker process per
// candidate (runner/certify.cpp, runner/case_shrinking.h). The test plugin (shrink_plugin.c)
// crashes (variant `crashes`) or hangs (variant `hangs`) exactly when a triangle has two
// bit-identical vertices, so the shrunk reproducer keeps one such triangle, the receiver of one
// sample and that sample, and still crashes or hangs when the worker runs it again.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "fixtures/fuzz/fuzz_fixtures.h"
#include "runner/case_shrinking.h"
#include "runner/certify.h"
#include "shadowcts/case_manifest.h"
#include "tests/cli/tool_run.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;
using testing::fresh_dir;
using testing::read_file;

// The plugin's trigger, on the suite's side.
bool repeated_vertex(const Triangle& t) {
  return t.v0 == t.v1 || t.v1 == t.v2 || t.v2 == t.v0;
}

std::size_t triangles_with_repeated_vertex(const Case& c) {
  std::size_t n = 0;
  for (const Triangle& t : c.triangles) n += repeated_vertex(t);
  return n;
}

// 15 triangles (the receiver and 14 degenerate ones, some with a repeated vertex) and 19 samples.
constexpr const char* crash_case = "fuzz.degenerate.1.3";

std::string certify_command(const std::string& fixture, const std::string& extra) {
  return "exec '" SHADOWCTS_TOOL "' certify --backend '" SHRINK_PLUGIN "' --fixture " + fixture +
         " --threads 1 --out out " + extra + "\n";
}

TEST(CertifyShrink, CrashAndHangAreShrunkAWorkerPerCandidateAndStillCrashAndHang) {
  const fs::path dir = fresh_dir("certify_shrink");
  // Neither variant answers on the whole case, so --timeout only bounds the hang's first wait.
  // Each candidate may take 2 s (one that runs to the end takes about 0.2 s); one that hangs
  // costs that much waiting, no CPU.
  const int code =
      testing::run_shell(certify_command(crash_case, "--timeout 4 --shrink-timeout 2"), dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 1) << log;
  const ordered_json c = ordered_json::parse(read_file(dir / "out" / "certificate.json"));
  ASSERT_EQ(c["results"].size(), 2u) << log;
  EXPECT_EQ(c["results"][0]["variant"], "crashes");
  EXPECT_EQ(c["results"][0]["verdict"], "Crash") << log;
  EXPECT_EQ(c["results"][1]["variant"], "hangs");
  EXPECT_EQ(c["results"][1]["verdict"], "Timeout") << log;
  EXPECT_EQ(c["shrink_budget"]["timeout_s"], 2.0);
  EXPECT_EQ(c["shrink_budget"]["runs"], 100);

  const fuzzing::GeneratedCase original = fuzzing::make_fuzz_case(crash_case);
  const std::size_t original_triangles = original.sample_case.c.triangles.size();
  const std::size_t original_samples = original.sample_case.samples.samples.size();
  ASSERT_GE(triangles_with_repeated_vertex(original.sample_case.c), 2u);
  ASSERT_GT(original_samples, 1u);

  ASSERT_EQ(c["reproducers"].size(), 2u) << log;
  const ordered_json results = ordered_json::parse(read_file(dir / "out" / "results.json"));
  ASSERT_EQ(results["results"].size(), 2u);
  const std::string junit = read_file(dir / "out" / "junit.xml");
  for (std::size_t k = 0; k < 2; ++k) {
    const ordered_json& r = c["reproducers"][k];
    SCOPED_TRACE(r.dump());
    EXPECT_EQ(r["verdict"], c["results"][k]["verdict"]);
    EXPECT_TRUE(r["shrunk"].get<bool>());
    EXPECT_FALSE(r["budget_exhausted"].get<bool>());
    EXPECT_EQ(r["original_triangles"], original_triangles);
    EXPECT_EQ(r["original_samples"], original_samples);
    // Every removable triangle but the one that triggers the fault is gone (each was tried
    // alone last), and one sample is enough.
    EXPECT_EQ(r["samples"], 1);
    EXPECT_LE(r["triangles"].get<std::size_t>(), 2u);
    EXPECT_LT(r["worker_runs"].get<std::size_t>(), original_triangles + original_samples);
    const std::string how = r["how"];
    EXPECT_NE(how.find(" worker runs, one per candidate (timeout 2 s)"), std::string::npos);
    EXPECT_NE(
        log.find("reproducer: " + (fs::path("out") / r["manifest"].get<std::string>()).string() +
                 " (" + r["triangles"].dump() + " triangles, 1 samples; " + how + ")"),
        std::string::npos)
        << log;
    // results.json and JUnit name the reproducer and how it was obtained too.
    const std::string named = "reproducer: " + r["manifest"].get<std::string>() + " (" + how + ")";
    EXPECT_NE(results["results"][k]["reproduce"].get<std::string>().find(named), std::string::npos)
        << results["results"][k].dump();
    EXPECT_NE(junit.find(named), std::string::npos) << junit;
    const Case shrunk =
        load_case_manifest((dir / "out" / r["manifest"].get<std::string>()).string());
    EXPECT_EQ(shrunk.triangles.size(), r["triangles"].get<std::size_t>());
    EXPECT_EQ(triangles_with_repeated_vertex(shrunk), 1u);
    EXPECT_TRUE(fs::exists(dir / "out" / "cases" / crash_case / r["variant"].get<std::string>() /
                           "shrink.log"));
  }

  // The reproducers, run again through the worker as the parent runs candidates: the crash
  // still crashes (bash reports 128 + SIGSEGV), the hang is still running after 4 s and is
  // killed (128 + SIGKILL).
  const std::string worker = "'" SHADOWCTS_TOOL "' certify --worker --backend '" SHRINK_PLUGIN
                             "' --no-images --threads 1 ";
  const std::string replay =
      worker + "--case out/" + c["reproducers"][0]["manifest"].get<std::string>() +
      " --variant crashes --out crash --worker-result crash.json > crash.log 2>&1\n"
      "echo $? > crash.status\n"
      "timeout -s KILL 4 " +
      worker + "--case out/" + c["reproducers"][1]["manifest"].get<std::string>() +
      " --variant hangs --out hang --worker-result hang.json > hang.log 2>&1\n"
      "echo $? > hang.status\n";
  ASSERT_EQ(testing::run_shell(replay, dir), 0);
  EXPECT_EQ(read_file(dir / "crash.status"), "139\n") << read_file(dir / "crash.log");
  EXPECT_EQ(read_file(dir / "hang.status"), "137\n") << read_file(dir / "hang.log");
}

TEST(CertifyShrink, ABudgetOfNoWorkerRunsWritesTheWholeCaseUnshrunk) {
  const fs::path dir = fresh_dir("certify_shrink_budget");
  // Neither variant ever answers on this case, so the timeout only bounds the hang's wait.
  const std::string fixture = "fuzz.degenerate.1.2";
  const int code = testing::run_shell(certify_command(fixture, "--timeout 2 --shrink-runs 0"), dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 1) << log;
  const ordered_json c = ordered_json::parse(read_file(dir / "out" / "certificate.json"));
  ASSERT_EQ(c["reproducers"].size(), 2u) << log;
  const fuzzing::GeneratedCase original = fuzzing::make_fuzz_case(fixture);
  for (const ordered_json& r : c["reproducers"]) {
    SCOPED_TRACE(r.dump());
    EXPECT_FALSE(r["shrunk"].get<bool>());
    EXPECT_TRUE(r["budget_exhausted"].get<bool>());
    EXPECT_EQ(r["worker_runs"], 0);
    EXPECT_EQ(r["note"].get<std::string>().rfind("unshrunk: budget exhausted", 0), 0u);
    EXPECT_EQ(r["triangles"], original.sample_case.c.triangles.size());
    EXPECT_EQ(r["samples"], original.sample_case.samples.samples.size());
    const Case whole =
        load_case_manifest((dir / "out" / r["manifest"].get<std::string>()).string());
    EXPECT_EQ(whole.triangles.size(), original.sample_case.c.triangles.size());
  }
  EXPECT_NE(log.find("unshrunk: budget exhausted"), std::string::npos) << log;
}

// shrink_case_in_chunks alone, with the plugin's trigger as the test: fewer tests than items, a
// 1-minimal result, the same result twice, and a stop that keeps the last failing candidate.
TEST(CaseShrinking, ChunksFindTheTriggerInFewerTestsThanItemsAndStopKeepsTheBest) {
  const fuzzing::SampleCase original = fuzzing::make_fuzz_case(crash_case).sample_case;
  const std::size_t items = original.c.triangles.size() + original.samples.samples.size();
  auto trigger = [](const fuzzing::SampleCase& k) {
    return triangles_with_repeated_vertex(k.c) > 0 ? CandidateResult::fails
                                                   : CandidateResult::passes;
  };
  const ChunkShrinking shrunk = shrink_case_in_chunks(original, trigger);
  EXPECT_FALSE(shrunk.stopped);
  EXPECT_LT(shrunk.tests, items);
  EXPECT_EQ(shrunk.best.samples.samples.size(), 1u);
  EXPECT_LE(shrunk.best.c.triangles.size(), 2u);
  EXPECT_EQ(triangles_with_repeated_vertex(shrunk.best.c), 1u);
  const std::uint32_t receiver = shrunk.best.samples.samples[0].receiver;
  ASSERT_LT(receiver, shrunk.best.c.triangles.size());
  EXPECT_EQ(shrunk.best.samples.samples[0].pixel_x, 0u);
  EXPECT_EQ(shrunk.best.samples.width, 1u);
  const ChunkShrinking again = shrink_case_in_chunks(original, trigger);
  EXPECT_EQ(again.tests, shrunk.tests);
  EXPECT_EQ(case_input_sha256(again.best.c, &again.best.samples),
            case_input_sha256(shrunk.best.c, &shrunk.best.samples));

  // The test stops after two answers: the second failing candidate is the result.
  std::size_t calls = 0;
  std::size_t kept_samples = 0;
  const ChunkShrinking stopped = shrink_case_in_chunks(original, [&](const fuzzing::SampleCase& k) {
    if (++calls > 2) return CandidateResult::stop;
    const CandidateResult r = trigger(k);
    if (r == CandidateResult::fails) kept_samples = k.samples.samples.size();
    return r;
  });
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(calls, 3u);
  EXPECT_EQ(stopped.tests, 2u);
  EXPECT_EQ(stopped.best.samples.samples.size(), kept_samples);
  EXPECT_LT(kept_samples, original.samples.samples.size());
  EXPECT_EQ(stopped.best.c.triangles.size(), original.c.triangles.size());
}

}  // namespace
}  // namespace shadowcts
