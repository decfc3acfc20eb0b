// results.json validates against the documented schema (docs/results-schema.json), and the
// schema check is strict enough to catch what breaks it.
#include <gtest/gtest.h>

#include "json_schema_subset.h"
#include "report_test_support.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace test;

json documented_schema() {
  return json::parse(read_text(SHADOWCTS_RESULTS_SCHEMA));
}

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += line + "\n";
  return out;
}

TEST(ResultsSchema, ARealRunValidates) {
  const fs::path dir = fresh_dir("schema_real");
  run_small_suite(dir);
  const json results = json::parse(read_text(dir / "results.json"));
  ASSERT_FALSE(results["results"].empty());
  const std::vector<std::string> violations = schema_violations(documented_schema(), results);
  EXPECT_TRUE(violations.empty()) << joined(violations);
}

TEST(ResultsSchema, HandWrittenRecordsOfEveryVerdictValidate) {
  json doc = {{"schema", "shadowcts.results/2"}, {"threads", 2}};
  doc["cases"] = json::array({json(hand_case("a"))});
  json pass = hand_hard_record("a", "x", 1, 0), fail = hand_hard_record("a", "y", 1, 2);
  json unsupported = {{"name", "hard.z.v.cuda.a"}, {"case", "a"},          {"output", "hard"},
                      {"algorithm", "z"},          {"variant", "v"},       {"backend", "cuda"},
                      {"verdict", "NotSupported"}, {"reason", "no device"}};
  json crash = pass;
  crash["name"] = "hard.w.exact.reference.a";
  crash["verdict"] = "Crash";
  crash["error"] = nullptr;
  crash["time_ms"]["runs"] = json::array();
  json soft = pass;
  soft["name"] = "soft.s.v.reference.a";
  soft["output"] = "soft";
  soft["error"] = {{"mean_abs_error", 0.01}};
  json phased = pass;
  phased["name"] = "hard.p.exact.reference.a";
  phased["time_ms"]["phases"] = {
      {"build", {{"median", 0.25}, {"min", 0.2}, {"max", 0.3}, {"runs", {0.3, 0.25, 0.2}}}},
      {"query", {{"median", 0.5}, {"runs", {0.5, 0.5, 0.5}}}}};
  doc["machine"] = {
      {"cpu", "hand"}, {"hardware_threads", 2}, {"isa", "AVX2"}, {"isa_targets", {"AVX2", "SSE4"}}};
  doc["results"] = {pass, fail, unsupported, crash, soft, phased};
  const std::vector<std::string> violations = schema_violations(documented_schema(), doc);
  EXPECT_TRUE(violations.empty()) << joined(violations);
}

TEST(ResultsSchema, CatchesWhatBreaksIt) {
  json doc = {{"schema", "shadowcts.results/2"}, {"threads", 2}};
  doc["machine"] = {
      {"cpu", "hand"}, {"hardware_threads", 2}, {"isa", "SSE4"}, {"isa_targets", {"SSE4"}}};
  doc["cases"] = json::array({json(hand_case("a"))});
  doc["results"] = json::array({json(hand_hard_record("a", "x", 1, 0))});
  doc["results"][0]["time_ms"]["phases"] = {
      {"build", {{"median", 0.25}, {"runs", {0.3, 0.25, 0.2}}}},
      {"query", {{"median", 0.5}, {"runs", {0.5, 0.5, 0.5}}}}};
  const json schema = documented_schema();
  ASSERT_TRUE(schema_violations(schema, doc).empty()) << joined(schema_violations(schema, doc));

  struct Breakage {
    const char* what;
    void (*apply)(json&);
  };
  const Breakage breakages[] = {
      {"older schema", [](json& d) { d["schema"] = "shadowcts.results/1"; }},
      {"machine without isa", [](json& d) { d["machine"].erase("isa"); }},
      {"empty isa", [](json& d) { d["machine"]["isa"] = ""; }},
      {"no isa targets", [](json& d) { d["machine"]["isa_targets"] = json::array(); }},
      {"no threads", [](json& d) { d.erase("threads"); }},
      {"unknown light", [](json& d) { d["cases"][0]["light"] = "laser"; }},
      {"three resolution numbers", [](json& d) { d["cases"][0]["resolution"].push_back(1); }},
      {"negative triangles", [](json& d) { d["cases"][0]["triangles"] = -1; }},
      // (without one is valid: run --no-images)
      {"empty oracle mask path",
       [](json& d) { d["cases"][0]["oracles"]["hard"]["mask_image"] = ""; }},
      {"unknown verdict", [](json& d) { d["results"][0]["verdict"] = "Maybe"; }},
      {"ran but no time", [](json& d) { d["results"][0].erase("time_ms"); }},
      {"negative median", [](json& d) { d["results"][0]["time_ms"]["median"] = -1; }},
      {"negative min", [](json& d) { d["results"][0]["time_ms"]["min"] = -1; }},
      {"phases not an object",
       [](json& d) {
         d["results"][0]["time_ms"]["phases"] = json::array({1, 2});
       }},
      {"phase without runs",
       [](json& d) { d["results"][0]["time_ms"]["phases"]["build"].erase("runs"); }},
      {"negative phase median",
       [](json& d) { d["results"][0]["time_ms"]["phases"]["query"]["median"] = -0.5; }},
      {"phase run not a number",
       [](json& d) { d["results"][0]["time_ms"]["phases"]["query"]["runs"].push_back("x"); }},
      {"fractional counter", [](json& d) { d["results"][0]["counters"]["pair_tests"] = 1.5; }},
      {"hard error without leaks", [](json& d) { d["results"][0]["error"].erase("leaks"); }},
      {"rate above 1", [](json& d) { d["results"][0]["error"]["robust_mismatch_rate"] = 2; }},
      {"empty curve", [](json& d) { d["results"][0]["error"]["mismatch_curve"] = json::array(); }},
      {"image not a string", [](json& d) { d["results"][0]["images"].push_back(3); }},
  };
  for (const Breakage& b : breakages) {
    json broken = doc;
    b.apply(broken);
    EXPECT_FALSE(schema_violations(schema, broken).empty()) << b.what;
  }
}

TEST(ResultsSchema, TheCheckerRefusesKeywordsItDoesNotKnow) {
  const json schema = {{"type", "object"}, {"patternProperties", json::object()}};
  EXPECT_THROW(schema_violations(schema, json::object()), std::invalid_argument);
  const json dangling = {{"$ref", "#/$defs/missing"}};
  EXPECT_THROW(schema_violations(dangling, json::object()), std::invalid_argument);
}

}  // namespace
}  // namespace shadowcts
