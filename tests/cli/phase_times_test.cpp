// Build and query phases: every algorithm that declares phases reports them in results.json, each
// within the time of the whole call; the others report none; an output that reports other phases
// than its algorithm declares is a Crash. No assertion here is about speed.
#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/phase_clock.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
// Keeps the file's key order: phases are listed in the order the algorithm declares them.
using json = nlohmann::ordered_json;

// Phases are read inside the runner's timed interval with the same steady clock, so they never
// exceed it; this only absorbs the rounding of nanoseconds converted to double milliseconds.
constexpr double rounding_ms = 1e-6;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("shadowcts_phase_times_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

json read_json(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return json::parse(s.str());
}

std::vector<double> runs_of(const json& timing) {
  return timing.at("runs").get<std::vector<double>>();
}

TEST(RunnerPhases, PresentExactlyWhereDeclaredAndWithinTheTotal) {
  RunOptions o;
  // A point light, a directional light, a sun disk and ranged lights: every algorithm runs.
  o.fixtures = {"ground_blockers.2k", "closed_shapes.1k", "foliage.2k", "many_lights.1k"};
  o.algorithms = {{"bruteforce", "exact"},
                  {"embree", ""},
                  {"ptsv", "twopass"},
                  {"ptsv", "hdb2011"},
                  {"psv", "hybrid"},
                  {"metric", "capsules"},
                  {"shadowmap", "1k"},
                  {"stencil", "zfail"},
                  {"softtile", "grid16"},
                  {"lightassign", "tiled"},
                  {"lightassign", "clustered"},
                  {"lightassign", "brute"}};
  o.out_dir = fresh_dir("all").string();
  o.repeats = 3;
  o.threads = 2;
  std::ostringstream log, err;
  run_suite(o, builtin_registry(), log, err);  // verdicts are other tests' business
  const json results = read_json(fs::path(o.out_dir) / "results.json");

  std::set<std::string> with_phases, without_phases;
  for (const json& r : results["results"]) {
    const std::string name = r["name"];
    if (r["verdict"] == "NotSupported") continue;
    ASSERT_NE(r["verdict"], "Crash") << name << ": " << r["reason"];
    const Algorithm* algorithm = builtin_registry().find(r["algorithm"], r["backend"]);
    ASSERT_NE(algorithm, nullptr) << name;
    const std::vector<std::string> declared = algorithm->timed_phases(r["variant"]);
    const json& time = r["time_ms"];
    const std::vector<double> total = runs_of(time);
    ASSERT_EQ(total.size(), 3u) << name;
    if (declared.empty()) {
      EXPECT_FALSE(time.contains("phases")) << name;
      without_phases.insert(r["algorithm"].get<std::string>() + ":" +
                            r["variant"].get<std::string>());
      continue;
    }
    ASSERT_TRUE(time.contains("phases")) << name;
    with_phases.insert(r["algorithm"].get<std::string>());
    std::vector<std::string> reported;
    std::vector<double> sum(total.size(), 0.0);
    for (const auto& [phase, timing] : time["phases"].items()) {
      reported.push_back(phase);
      const std::vector<double> runs = runs_of(timing);
      ASSERT_EQ(runs.size(), total.size()) << name << " " << phase;
      for (std::size_t i = 0; i < runs.size(); ++i) {
        EXPECT_GE(runs[i], 0.0) << name << " " << phase;
        EXPECT_LE(runs[i], total[i] + rounding_ms) << name << " " << phase << " run " << i;
        sum[i] += runs[i];
      }
      // Each phase is within the total run by run, so its median, min and max are too.
      for (const char* statistic : {"median", "min", "max"})
        EXPECT_LE(timing.at(statistic).get<double>(),
                  time.at(statistic).get<double>() + rounding_ms)
            << name << " " << phase << " " << statistic;
      EXPECT_EQ(timing["min"].get<double>(), *std::min_element(runs.begin(), runs.end()));
      EXPECT_EQ(timing["max"].get<double>(), *std::max_element(runs.begin(), runs.end()));
    }
    EXPECT_EQ(reported, declared) << name;
    // The phases are disjoint parts of one call: together they fit in it too.
    for (std::size_t i = 0; i < total.size(); ++i)
      EXPECT_LE(sum[i], total[i] + rounding_ms) << name << " run " << i;
  }
  EXPECT_EQ(with_phases, (std::set<std::string>{"embree", "ptsv", "psv", "metric", "shadowmap",
                                                "stencil", "softtile", "lightassign"}));
  EXPECT_EQ(without_phases, (std::set<std::string>{"bruteforce:exact", "lightassign:brute"}));

  // The machine record names the ISA Highway dispatches to.
  const json& machine = results["machine"];
  ASSERT_TRUE(machine["isa"].is_string());
  EXPECT_FALSE(machine["isa"].get<std::string>().empty());
  ASSERT_FALSE(machine["isa_targets"].empty());
  EXPECT_EQ(machine["isa_targets"][0], machine["isa"]);
}

// Lit everywhere (wrong, but that is the verdict's business), with phases as configured.
class PhaseReporter : public Algorithm {
 public:
  PhaseReporter(std::vector<std::string> declared, std::vector<std::string> reported)
      : declared_(std::move(declared)), reported_(std::move(reported)) {
    info_.id = "phase_reporter";
    info_.backend = "test";
    info_.variants = {"v"};
    info_.summary = "reports the phases it is told to";
    info_.capabilities.point_light = info_.capabilities.directional_light = true;
  }
  const AlgorithmInfo& info() const override { return info_; }
  std::vector<std::string> timed_phases(const std::string&) const override { return declared_; }
  AlgorithmOutput run(const PreparedScene& scene, const std::string&) const override {
    const ViewSamples& samples = scene.view_samples;
    PhaseClock clock(reported_);
    AlgorithmOutput out;
    out.shadowed.assign(samples.samples.size(), 0);
    for (const std::string& phase : reported_) clock.lap(phase);
    out.phase_ms = clock.times();
    return out;
  }

 private:
  AlgorithmInfo info_;
  std::vector<std::string> declared_, reported_;
};

json run_reporter(const std::string& name, std::vector<std::string> declared,
                  std::vector<std::string> reported) {
  Registry registry;
  registry.add(std::make_unique<PhaseReporter>(std::move(declared), std::move(reported)));
  RunOptions o;
  o.fixtures = {"ground_blockers.2k"};
  o.out_dir = fresh_dir(name).string();
  o.repeats = 2;
  std::ostringstream log, err;
  run_suite(o, registry, log, err);
  const json results = read_json(fs::path(o.out_dir) / "results.json");
  EXPECT_EQ(results["results"].size(), 1u);
  return results["results"][0];
}

TEST(RunnerPhases, OtherPhasesThanDeclaredAreACrash) {
  const json fine = run_reporter("fine", {"build", "query"}, {"build", "query"});
  EXPECT_NE(fine["verdict"], "Crash") << fine["reason"];
  EXPECT_EQ(fine["time_ms"]["phases"].size(), 2u);

  const json missing = run_reporter("missing", {"build", "query"}, {"query"});
  EXPECT_EQ(missing["verdict"], "Crash");
  EXPECT_NE(missing["reason"].get<std::string>().find("declares {build, query}"), std::string::npos)
      << missing["reason"];

  const json undeclared = run_reporter("undeclared", {}, {"build"});
  EXPECT_EQ(undeclared["verdict"], "Crash");
  EXPECT_NE(undeclared["reason"].get<std::string>().find("reports phases {build}"),
            std::string::npos)
      << undeclared["reason"];
}

// An emulated backend's time is the emulator's: by default it runs once, without a warm-up, and
// that run is timed; --repeat gives it a warm-up and that many timed repeats; other backends keep
// the case's repeats after their warm-up.
TEST(RunnerTiming, EmulatedBackendsAreTimedOnceUnlessRepeatIsGiven) {
  const auto timed_runs = [](const std::string& name, std::optional<std::uint32_t> repeats) {
    RunOptions o;
    o.fixtures = {"closed_shapes.1k"};
    o.algorithms = {{"psv", "stackless"}};
    o.backends = {"cuda-emu", "reference"};
    o.out_dir = fresh_dir(name).string();
    o.repeats = repeats;
    std::ostringstream log, err;
    run_suite(o, builtin_registry(), log, err);
    std::map<std::string, std::size_t> runs;
    const json results = read_json(fs::path(o.out_dir) / "results.json");
    for (const json& r : results["results"]) {
      EXPECT_EQ(r["verdict"], "Pass") << r["name"] << ": " << r["reason"];
      runs[r["backend"].get<std::string>()] = runs_of(r["time_ms"]).size();
    }
    return runs;
  };
  const std::map<std::string, std::size_t> by_default = timed_runs("default", std::nullopt);
  EXPECT_EQ(by_default.at("cuda-emu"), 1u);
  EXPECT_EQ(by_default.at("reference"), 2u);  // Case::Parameters::repeats
  const std::map<std::string, std::size_t> asked = timed_runs("asked", 3);
  EXPECT_EQ(asked.at("cuda-emu"), 3u);
  EXPECT_EQ(asked.at("reference"), 3u);
  EXPECT_TRUE(builtin_registry().find("psv", "cuda-emu")->info().emulated);
  EXPECT_FALSE(builtin_registry().find("psv", "reference")->info().emulated);
}

// Counts its runs; declares itself emulated.
class CountingEmulated : public PhaseReporter {
 public:
  explicit CountingEmulated(std::atomic<int>& calls) : PhaseReporter({}, {}), calls_(calls) {
    info_.emulated = true;
  }
  const AlgorithmInfo& info() const override { return info_; }
  AlgorithmOutput run(const PreparedScene& scene, const std::string& variant) const override {
    ++calls_;
    return PhaseReporter::run(scene, variant);
  }

 private:
  AlgorithmInfo info_ = PhaseReporter::info();
  std::atomic<int>& calls_;
};

// No GPU to warm and no GPU time to measure: one call by default; --repeat N gives the warm-up
// and N timed repeats (which must reproduce it), as for every other backend.
TEST(RunnerTiming, EmulatedBackendsRunOnceWithoutAWarmUpUnlessRepeatIsGiven) {
  for (const std::optional<std::uint32_t> repeats :
       {std::optional<std::uint32_t>(), std::optional<std::uint32_t>(2)}) {
    std::atomic<int> calls{0};
    Registry registry;
    registry.add(std::make_unique<CountingEmulated>(calls));
    RunOptions o;
    o.fixtures = {"ground_blockers.2k"};
    o.out_dir = fresh_dir(repeats ? "emulated_repeat" : "emulated_once").string();
    o.repeats = repeats;
    std::ostringstream log, err;
    run_suite(o, registry, log, err);
    const json results = read_json(fs::path(o.out_dir) / "results.json");
    ASSERT_EQ(results["results"].size(), 1u);
    EXPECT_EQ(calls.load(), repeats ? 3 : 1);
    EXPECT_EQ(runs_of(results["results"][0]["time_ms"]).size(), repeats ? 2u : 1u);
  }
}

TEST(PhaseClock, LapsAddUpPerPhaseInDeclaredOrder) {
  PhaseClock clock;  // build, query
  clock.lap(query_phase);
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  clock.lap(build_phase);
  clock.lap(query_phase);
  clock.restart();
  clock.lap("extra");
  const PhaseTimes& times = clock.times();
  ASSERT_EQ(times.size(), 3u);
  EXPECT_EQ(times[0].first, "build");
  EXPECT_EQ(times[1].first, "query");
  EXPECT_EQ(times[2].first, "extra");
  EXPECT_GE(times[0].second, 1.0);  // the sleep went to build: a lower bound, not a speed
  for (const auto& [name, ms] : times) EXPECT_GE(ms, 0.0) << name;

  const PhaseClock unused;
  ASSERT_EQ(unused.times().size(), 2u);
  EXPECT_EQ(unused.times()[0].second, 0.0);
  EXPECT_EQ(unused.times()[1].second, 0.0);
}

}  // namespace
}  // namespace shadowcts
