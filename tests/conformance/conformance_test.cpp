// Every registered algorithm x variant x backend on every default fixture is a CTest case, named
// like the runner's records (dots become underscores for GoogleTest), e.g.
// Conformance/hard_bruteforce_exact_reference_gate_house_20k.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"
#include "shadowcts/view_samples.h"
#include "tests/test_name.h"
#if SHADOWCTS_HAVE_CUDA
#include "gpu/device.h"
#endif

namespace shadowcts {
namespace {

namespace fs = std::filesystem;

struct ConformanceCase {
  std::string fixture, algorithm, variant, backend;
};

// Readable parameter values in test logs.
void PrintTo(const ConformanceCase& c, std::ostream* os) {
  *os << c.algorithm << ":" << c.variant << " [" << c.backend << "] on " << c.fixture;
}

std::vector<ConformanceCase> all_cases() {
  std::vector<ConformanceCase> cases;
  for (const std::string& fixture : default_fixtures())
    for (const auto& a : builtin_registry().algorithms())
      for (const std::string& variant : a->info().variants)
        cases.push_back({fixture, a->info().id, variant, a->info().backend});
  return cases;
}

std::string case_name(const testing::TestParamInfo<ConformanceCase>& info) {
  return test_support::test_name(info.param.algorithm + "_" + info.param.variant + "_" +
                                 info.param.backend + "_" + info.param.fixture);
}

class Conformance : public testing::TestWithParam<ConformanceCase> {};

TEST_P(Conformance, PassesOrIsNotSupported) {
  const ConformanceCase& c = GetParam();
  const fs::path out = fs::temp_directory_path() / ("shadowcts_conformance_" + case_name({c, 0}));
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {c.fixture};
  options.algorithms = {{c.algorithm, c.variant}};
  options.backends = {c.backend};
  options.out_dir = out.string();
  options.repeats = 1;
  options.images = false;  // the verdicts are the test; images are the report's (Runner tests)
  // Every algorithm of a fixture is judged against the same truth: the first case of a fixture
  // computes it, the others read it (the soft oracle alone costs ~17 s per foliage.10k case).
  options.truth_cache_dir = SHADOWCTS_TRUTH_CACHE_DIR;
  std::ostringstream log, err;
  const int code = run_suite(options, builtin_registry(), log, err);
  std::ifstream in(out / "results.json");
  const auto results = nlohmann::json::parse(in);
  ASSERT_EQ(results["results"].size(), 1u) << log.str();
  const auto& record = results["results"][0];
  const std::string verdict = record["verdict"];
  if (verdict == "NotSupported") {
    EXPECT_EQ(code, exit_pass);
    // Shown as skipped, with the reason, so CI logs say what was not certified.
    GTEST_SKIP() << "NotSupported: " << record["reason"].get<std::string>();
  }
  // Approximate algorithms (shadow maps) report their robust mismatches as QualityWarning: their
  // error figures, not a failure.
  const Algorithm* algorithm = builtin_registry().find(c.algorithm, c.backend);
  ASSERT_NE(algorithm, nullptr);
  if (algorithm->info().capabilities.approximate && verdict == "QualityWarning") {
    EXPECT_EQ(code, exit_pass) << record["reason"];
    fs::remove_all(out);
    return;
  }
  EXPECT_EQ(verdict, "Pass") << record["reason"] << "\n" << log.str();
  EXPECT_EQ(code, exit_pass);
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Conformance, Conformance, testing::ValuesIn(all_cases()), case_name);

// The cases above skip what an algorithm declares NotSupported, so a port that declares every
// case unsupported would pass them all. Each algorithm x backend must therefore run enough of
// them: every variant at least half of the default fixtures that carry its output's light
// (a shadow light for hard shadows, a sun disk for soft shadows, ranged lights for light lists)
// and lie within its declared size limit, and at least one. Decided as the runner plans
// (unsupported_reason on the case as that output sees it). A device backend with no device here
// says "no CUDA device" for every case and is held to the minimum only where a device is present.
bool carries_light_for(const Case& c, OutputKind kind) {
  switch (kind) {
    case OutputKind::hard_shadow:
      return c.light.has_value();
    case OutputKind::soft_shadow:
      return c.light && c.light->kind == ShadowLightKind::sun_disk;
    case OutputKind::light_lists:
      return !c.ranged_lights.empty();
  }
  return false;
}

struct CoverageInput {
  Case c, hard_view;
  ViewSamples samples;
};

const std::vector<CoverageInput>& coverage_inputs() {
  static const std::vector<CoverageInput> inputs = [] {
    std::vector<CoverageInput> out;
    for (const std::string& fixture : default_fixtures()) {
      CoverageInput in;
      in.c = make_fixture(fixture);
      in.samples = generate_view_samples(in.c);
      if (in.c.light) in.hard_view = hard_shadow_view(in.c);
      out.push_back(std::move(in));
    }
    return out;
  }();
  return inputs;
}

// What falls short of the minimum, one line per algorithm:variant [backend]; `no_device` says
// why this process has no CUDA device (nullopt: it has one).
std::vector<std::string> coverage_shortfalls(const Registry& registry,
                                             const std::optional<std::string>& no_device) {
  std::vector<std::string> shortfalls;
  for (const auto& a : registry.algorithms()) {
    const AlgorithmInfo& info = a->info();
    for (const std::string& variant : info.variants) {
      const std::string name = info.id + ":" + variant + " [" + info.backend + "]";
      std::size_t eligible = 0, supported = 0, without_device = 0, above_limit = 0;
      for (const CoverageInput& in : coverage_inputs()) {
        if (!carries_light_for(in.c, info.capabilities.output)) continue;
        // A declared size limit (docs/specification.md, "Size limits") leaves out what lies
        // above it; it must still admit some default fixture (the minimum is at least 1).
        const std::uint64_t pairs = std::uint64_t(in.samples.count(SampleClass::regular)) *
                                    std::uint64_t(in.c.triangles.size());
        if (info.capabilities.max_sample_triangle_pairs != 0 &&
            pairs > info.capabilities.max_sample_triangle_pairs) {
          ++above_limit;
          continue;
        }
        ++eligible;
        const Case& view =
            info.capabilities.output == OutputKind::hard_shadow ? in.hard_view : in.c;
        const std::optional<std::string> why = a->unsupported_reason(view, in.samples, variant);
        if (!why) {
          ++supported;
        } else if (why->rfind("no CUDA device", 0) == 0) {
          ++without_device;
          if (!no_device)
            shortfalls.push_back(name + " on " + in.c.name + " says '" + *why +
                                 "' although this process has a device");
        }
      }
      std::cout << "[ COVERAGE ] " << name << ": " << supported << " of " << eligible
                << " default fixtures with its light within its size limit"
                << (above_limit ? " (" + std::to_string(above_limit) + " above it)" : std::string())
                << (without_device ? " (" + std::to_string(without_device) + " need a device)"
                                   : std::string())
                << "\n";
      if (without_device == eligible && eligible > 0 && no_device) continue;
      if (supported < std::max<std::size_t>(1, (eligible + 1) / 2))
        shortfalls.push_back(name + " runs " + std::to_string(supported) + " of the " +
                             std::to_string(eligible) +
                             " default fixtures with its light within its size limit");
    }
  }
  return shortfalls;
}

TEST(ConformanceCoverage, EveryAlgorithmAndBackendRunsEnoughDefaultCases) {
#if SHADOWCTS_HAVE_CUDA
  const std::optional<std::string> no_device = cuda_unavailable_reason();
#else
  const std::optional<std::string> no_device = "this build has no CUDA backend";
#endif
  for (const std::string& shortfall : coverage_shortfalls(builtin_registry(), no_device))
    ADD_FAILURE() << shortfall;
}

// A port that declares every case unsupported, and one whose size limit admits no default
// fixture, fall short; one that says it needs a device is excused only without a device.
class DeclaresNothing : public Algorithm {
 public:
  DeclaresNothing(std::string reason, std::uint64_t limit) : reason_(std::move(reason)) {
    info_.id = "declares_nothing";
    info_.backend = "test";
    info_.variants = {"only"};
    info_.capabilities.point_light = info_.capabilities.directional_light = true;
    info_.capabilities.max_sample_triangle_pairs = limit;
  }
  const AlgorithmInfo& info() const override { return info_; }
  std::optional<std::string> unsupported_reason(const Case& c, const ViewSamples& samples,
                                                const std::string& variant) const override {
    if (auto why = Algorithm::unsupported_reason(c, samples, variant)) return why;
    if (reason_.empty()) return std::nullopt;
    return reason_;
  }
  AlgorithmOutput run(const PreparedScene&, const std::string&) const override { return {}; }

 private:
  AlgorithmInfo info_;
  std::string reason_;
};

TEST(ConformanceCoverage, APortThatDeclaresEverythingUnsupportedFallsShort) {
  const auto shortfalls = [](std::string reason, std::uint64_t limit,
                             std::optional<std::string> no_device) {
    Registry registry;
    registry.add(std::make_unique<DeclaresNothing>(std::move(reason), limit));
    return coverage_shortfalls(registry, no_device).size();
  };
  EXPECT_EQ(shortfalls("", 0, std::nullopt), 0u) << "a port that runs everything";
  EXPECT_EQ(shortfalls("not implemented", 0, std::nullopt), 1u);
  EXPECT_EQ(shortfalls("", 1, std::nullopt), 1u) << "a size limit that admits nothing";
  EXPECT_EQ(shortfalls("no CUDA device: test", 0, std::string("no driver")), 0u);
  EXPECT_GE(shortfalls("no CUDA device: test", 0, std::nullopt), 1u);
}

}  // namespace
}  // namespace shadowcts
