// Issue 23: `shadowcts certify` of ports loaded through the C ABI. The example port in plain C
// passes (certified in two shards, merged, verified); the broken example gives exactly Fail,
// Crash, Timeout and Fail while the run completes; bad libraries exit 2 naming the library and
// the field and write nothing; verify rejects edited, incomplete and duplicated certificates.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "runner/certify.h"
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

void write_certificate(const fs::path& dir, const ordered_json& c) {
  std::ofstream(dir / "certificate.json", std::ios::trunc) << c.dump(2) << "\n";
}

// The content hash recomputed, as someone who edits a certificate on purpose would.
void reseal(ordered_json& c) {
  c.erase("certificate_sha256");
  c["certificate_sha256"] = certificate_content_sha256(c);
}

// Copies the certification folder (only its certificate matters to verify) to a new folder.
fs::path copy_of(const fs::path& dir, const std::string& name) {
  const fs::path to = fresh_dir(name);
  fs::copy_file(dir / "certificate.json", to / "certificate.json");
  return to;
}

TEST(Certify, ExamplePortPassesInShardsThatMergeAndVerify) {
  const fs::path dir = fresh_dir("certify_example");
  // Two small cases, one per light kind the example declares (point and directional).
  const std::string common = std::string("certify --backend '") + EXAMPLE_BRUTEFORCE_C +
                             "' --fixture ground_blockers.100 --fixture closed_shapes.100 "
                             "--timeout 120 --threads 1";
  ASSERT_EQ(run_tool(common + " --shard 0/2 --out shard0", dir), 0)
      << read_file(dir / "stdout.txt") << read_file(dir / "stderr.txt");
  ASSERT_EQ(run_tool(common + " --shard 1/2 --out shard1", dir), 0)
      << read_file(dir / "stdout.txt") << read_file(dir / "stderr.txt");
  for (const char* shard : {"shard0", "shard1"}) {
    const ordered_json c = read_certificate(dir / shard);
    ASSERT_EQ(c["results"].size(), 1u);
    EXPECT_EQ(c["results"][0]["verdict"], "Pass") << c["results"][0].dump();
    EXPECT_EQ(c["results"][0]["runs"].size(), 2u);
    EXPECT_EQ(c["cases"].size(), 2u);  // the whole case list, in every shard
    for (const char* file : {"results.json", "junit.xml", "report.html"})
      EXPECT_TRUE(fs::exists(dir / shard / file)) << shard << "/" << file;
  }
  // A shard alone is incomplete.
  EXPECT_EQ(run_tool("certify verify shard0", dir), 1);
  EXPECT_NE(read_file(dir / "stdout.txt").find("certify merge"), std::string::npos)
      << read_file(dir / "stdout.txt");

  ASSERT_EQ(run_tool("certify merge merged shard1 shard0", dir), 0)
      << read_file(dir / "stderr.txt");
  ASSERT_EQ(run_tool("certify verify merged", dir), 0) << read_file(dir / "stdout.txt");
  EXPECT_NE(read_file(dir / "stdout.txt").find("ACCEPTED"), std::string::npos);
  const ordered_json merged = read_certificate(dir / "merged");
  ASSERT_EQ(merged["results"].size(), 2u);
  EXPECT_EQ(merged["results"][0]["case"], "ground_blockers.100");  // case-list order
  EXPECT_EQ(merged["results"][1]["case"], "closed_shapes.100");
  const ordered_json results = ordered_json::parse(read_file(dir / "merged" / "results.json"));
  EXPECT_EQ(results["results"].size(), 2u);
  // Every image the merged page shows is there (the runs' paths, made relative to the folder).
  const std::string page = read_file(dir / "merged" / "report.html");
  std::size_t images = 0;
  for (std::size_t at = page.find("src=\""); at != std::string::npos;
       at = page.find("src=\"", at + 1), ++images) {
    const std::size_t end = page.find('"', at + 5);
    const std::string src = page.substr(at + 5, end - at - 5);
    EXPECT_TRUE(fs::exists(dir / "merged" / src)) << src;
  }
  EXPECT_GE(images, 4u);

  // Merging a shard twice (and leaving one out) is refused, and writes nothing.
  EXPECT_EQ(run_tool("certify merge twice shard0 shard0", dir), 2);
  EXPECT_FALSE(fs::exists(dir / "twice"));

  {
    SCOPED_TRACE("an edited verdict");
    const fs::path edited = copy_of(dir / "merged", "certify_edited");
    ordered_json c = read_certificate(edited);
    c["results"][0]["time_ms"] = 1.0;
    write_certificate(edited, c);
    EXPECT_EQ(run_tool("certify verify '" + edited.string() + "'", dir), 1);
    EXPECT_NE(read_file(dir / "stdout.txt").find("edited"), std::string::npos)
        << read_file(dir / "stdout.txt");
  }
  {
    SCOPED_TRACE("a rerun's output hash changed, content hash recomputed");
    const fs::path edited = copy_of(dir / "merged", "certify_forged");
    ordered_json c = read_certificate(edited);
    c["results"][1]["runs"][1]["output_sha256"] = std::string(64, '0');
    reseal(c);
    write_certificate(edited, c);
    EXPECT_EQ(run_tool("certify verify '" + edited.string() + "'", dir), 1);
    EXPECT_NE(read_file(dir / "stdout.txt").find("two runs of the same output hash"),
              std::string::npos)
        << read_file(dir / "stdout.txt");
  }
  {
    SCOPED_TRACE("a case missing");
    const fs::path edited = copy_of(dir / "merged", "certify_incomplete");
    ordered_json c = read_certificate(edited);
    c["results"].erase(c["results"].begin() + 1);
    reseal(c);
    write_certificate(edited, c);
    EXPECT_EQ(run_tool("certify verify '" + edited.string() + "'", dir), 1);
    EXPECT_NE(read_file(dir / "stdout.txt").find("closed_shapes.100 variant watertight is missing"),
              std::string::npos)
        << read_file(dir / "stdout.txt");
  }
  {
    SCOPED_TRACE("a case twice");
    const fs::path edited = copy_of(dir / "merged", "certify_duplicated");
    ordered_json c = read_certificate(edited);
    c["results"].push_back(c["results"][0]);
    reseal(c);
    write_certificate(edited, c);
    EXPECT_EQ(run_tool("certify verify '" + edited.string() + "'", dir), 1);
    EXPECT_NE(read_file(dir / "stdout.txt").find("appears more than once"), std::string::npos)
        << read_file(dir / "stdout.txt");
  }
  {
    SCOPED_TRACE("a case of the list dropped from the list and the results");
    const fs::path edited = copy_of(dir / "merged", "certify_shortened");
    ordered_json c = read_certificate(edited);
    c["cases"].erase(c["cases"].begin() + 1);
    c["results"].erase(c["results"].begin() + 1);
    reseal(c);
    write_certificate(edited, c);
    EXPECT_EQ(run_tool("certify verify '" + edited.string() + "'", dir), 1);
    EXPECT_NE(read_file(dir / "stdout.txt").find("case_list_sha256 does not match"),
              std::string::npos)
        << read_file(dir / "stdout.txt");
  }
}

TEST(Certify, BrokenPortGivesFailCrashTimeoutFailCrashAndTheRunCompletes) {
  const fs::path dir = fresh_dir("certify_broken");
  // example_broken.c: a leak at shared edges (ground_blockers), a segfault (gate_house), a hang
  // (closed_shapes), other answers in every second process (foliage) and exit(3) inside the
  // call (shared_edges).
  // TMPDIR: where the broken example keeps its marker file between processes.
  const int code = testing::run_shell(
      "TMPDIR=\"$PWD\" exec '" SHADOWCTS_TOOL "' certify --backend '" EXAMPLE_BROKEN
      "' --fixture ground_blockers.100 --fixture gate_house.1000 --fixture closed_shapes.100 "
      "--fixture foliage.100 --fixture shared_edges.500 --timeout 6 --threads 1 --out out\n",
      dir);
  const std::string log = read_file(dir / "stdout.txt") + read_file(dir / "stderr.txt");
  ASSERT_EQ(code, 1) << log;
  const ordered_json c = read_certificate(dir / "out");
  ASSERT_EQ(c["results"].size(), 5u) << log;
  std::vector<std::string> verdicts;
  for (const ordered_json& r : c["results"]) verdicts.push_back(r["verdict"]);
  EXPECT_EQ(verdicts, (std::vector<std::string>{"Fail", "Crash", "Timeout", "Fail", "Crash"}))
      << log;
  EXPECT_NE(c["results"][0]["reason"].get<std::string>().find("leaks"), std::string::npos);
  EXPECT_NE(c["results"][1]["reason"].get<std::string>().find("signal 11"), std::string::npos);
  EXPECT_NE(c["results"][3]["reason"].get<std::string>().find(
                "nondeterministic: the rerun in a separate process gave other outputs"),
            std::string::npos)
      << c["results"][3].dump();
  EXPECT_EQ(c["results"][3]["runs"].size(), 2u);
  // An exit status that no shadowcts error explains is the library's, with what it printed.
  EXPECT_NE(c["results"][4]["reason"].get<std::string>().find(
                "the worker exited with status 3 without an error from shadowcts: the library "
                "ended the process (exit() in a plugin call?); worker.log ends with "
                "'example_broken: fatal: cannot continue'"),
            std::string::npos)
      << c["results"][4].dump();
  // The usual outputs carry the same verdicts, the timeout as Timeout.
  const ordered_json results = ordered_json::parse(read_file(dir / "out" / "results.json"));
  ASSERT_EQ(results["results"].size(), 5u);
  EXPECT_EQ(results["results"][1]["verdict"], "Crash");
  EXPECT_EQ(results["results"][2]["verdict"], "Timeout");
  const std::string junit = read_file(dir / "out" / "junit.xml");
  EXPECT_NE(junit.find("type=\"Crash\""), std::string::npos);
  EXPECT_NE(junit.find("type=\"Timeout\""), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "out" / "report.html"));
  EXPECT_EQ(run_tool("certify verify out", dir), 1);
}

// A certification interrupted while a worker hangs in the library (workers run in process groups
// of their own, so a terminal's Ctrl-C reaches only the certifying process) kills the worker and
// removes its unfinished folder, which the worker's run lies in: nothing is left behind.
TEST(Certify, AnInterruptedCertificationTakesItsHungWorkerAndUnfinishedFolderWithIt) {
  const fs::path dir = fresh_dir("certify_interrupted");
  const int code = testing::run_shell(
      "'" SHADOWCTS_TOOL "' certify --backend '" EXAMPLE_BROKEN
      "' --fixture closed_shapes.100 --timeout 600 --threads 1 --out out > tool_stdout.txt "
      "2> tool_stderr.txt &\n"
      "pid=$!\n"
      "worker=\n"
      "for i in $(seq 1 600); do\n"
      "  for p in /proc/[0-9]*; do\n"
      // This certification's own worker (its run lies in out.partial-<pid>), not one of a test
      // running beside it.
      "    if tr '\\0' ' ' < $p/cmdline 2>/dev/null | grep -q -- \"[c]ertify --worker "
      ".*/out.partial-$pid/\"; then worker=${p#/proc/}; fi\n"
      "  done\n"
      "  if [ -n \"$worker\" ]; then break; fi\n"
      "  sleep 0.05\n"
      "done\n"
      "sleep 0.5\n"
      "kill -TERM $pid\n"
      "wait $pid\n"
      "echo $? > status.txt\n"
      "echo \"$worker\" > worker.txt\n",
      dir);
  const std::string log = read_file(dir / "tool_stdout.txt") + read_file(dir / "tool_stderr.txt");
  ASSERT_EQ(code, 0) << log;
  ASSERT_EQ(read_file(dir / "status.txt"), "143\n") << log;
  std::string worker = read_file(dir / "worker.txt");
  while (!worker.empty() && worker.back() == '\n') worker.pop_back();
  ASSERT_FALSE(worker.empty()) << "no worker was seen running\n" << log;
  // Killed, it is at most a zombie left to the process that adopted it.
  std::string state;
  for (int i = 0; i < 500; ++i) {
    std::ifstream stat("/proc/" + worker + "/stat");
    std::string fields;
    std::getline(stat, fields);
    const auto close = fields.rfind(')');
    state = close == std::string::npos ? "" : fields.substr(close + 2, 1);
    if (state.empty() || state == "Z") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(state.empty() || state == "Z") << "worker " << worker << " still runs: " << state;
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().rfind("out", 0), std::string::npos) << entry.path();
  EXPECT_NE(log.find("interrupted (SIGTERM); removed the unfinished"), std::string::npos) << log;
}

TEST(Certify, NothingJudgedCertifiesNothing) {
  // The example declares hard shadows only; many_lights has no shadow light: NotSupported, as
  // declared, and nothing else.
  const fs::path dir = fresh_dir("certify_nothing");
  EXPECT_EQ(run_tool(std::string("certify --backend '") + EXAMPLE_BRUTEFORCE_C +
                         "' --fixture many_lights.100 --timeout 60 --threads 1 --out out",
                     dir),
            1);
  const ordered_json c = read_certificate(dir / "out");
  ASSERT_EQ(c["results"].size(), 1u);
  EXPECT_EQ(c["results"][0]["verdict"], "NotSupported");
  EXPECT_TRUE(c["results"][0]["declared_not_supported"].get<bool>());
  EXPECT_EQ(run_tool("certify verify out", dir), 1);
  EXPECT_NE(read_file(dir / "stdout.txt").find("certifies nothing"), std::string::npos);
}

struct BadLibrary {
  const char* name;
  std::string library;
  const char* field;  // the message names it
};

// One test for all of them: each case costs a few process starts, not a whole certification.
TEST(Certify, EveryBadLibraryExitsTwoNamingLibraryAndFieldAndWritesNothing) {
  const BadLibrary bad_libraries[] = {
      {"missing_file", "/nonexistent/libport.so", "library file"},
      {"no_entry_point", BAD_PLUGIN_NO_ENTRY_POINT, "shadowcts_backend_negotiate"},
      {"abi_version", BAD_PLUGIN_ABI_VERSION, "abi_version"},
      {"unknown_algorithm", BAD_PLUGIN_UNKNOWN_ALGORITHM, "variants[0].algorithm"},
      {"zero_size", BAD_PLUGIN_ZERO_SIZE, "variants[0].max_triangles"},
      {"null_function", BAD_PLUGIN_NULL_FUNCTION, "variants[0].run"},
      {"no_variants", BAD_PLUGIN_NO_VARIANTS, "variant_count"},
      {"empty_name", BAD_PLUGIN_EMPTY_NAME, "name: is empty"},
      {"crash_in_negotiate", BAD_PLUGIN_CRASH_IN_NEGOTIATE,
       "shadowcts_backend_negotiate: the library crashed"}};
  for (const BadLibrary& bad : bad_libraries) {
    SCOPED_TRACE(bad.name);
    const fs::path dir = fresh_dir(std::string("certify_bad_") + bad.name);
    EXPECT_EQ(run_tool("certify --backend '" + bad.library +
                           "' --fixture ground_blockers.100 --out out --timeout 5",
                       dir),
              2);
    const std::string message = read_file(dir / "stderr.txt");
    EXPECT_NE(message.find(bad.library), std::string::npos) << message;
    EXPECT_NE(message.find(bad.field), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir / "out"));
    for (const fs::directory_entry& entry : fs::directory_iterator(dir))
      EXPECT_NE(entry.path().filename().string().rfind("out.", 0), 0u) << entry.path();
  }
}

}  // namespace
}  // namespace shadowcts
