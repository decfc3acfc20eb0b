// Timings run by hand, not in CI (disabled tests):
//   lightassign_test --gtest_also_run_disabled_tests --gtest_filter='*Timing*'
// 1920 x 1080 samples of many_lights with 32 ... 1 M lights: the oracle, every variant with its
// verdict and efficiency, and tiled against clustered assignment time (Paper II, Table 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "lightassign_test_support.h"
#include "shadowcts/fixtures.h"

namespace shadowcts {
namespace {

using testing::lightassign;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <class F>
double median_ms(int repeats, F&& f) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    times.push_back(1e3 * seconds_since(start));
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

void time_full_hd(const std::string& generator, std::uint64_t lights) {
  {
    Case c = make_fixture(generator, 4 * lights);
    c.camera.width = 1920;
    c.camera.height = 1080;
    const ViewSamples samples = generate_view_samples(c);
    auto start = std::chrono::steady_clock::now();
    const LightAssignmentTruth plain = exact_light_assignment_oracle(c, samples, false);
    const double oracle_s = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const LightAssignmentTruth normals = exact_light_assignment_oracle(c, samples, true);
    const double oracle_normals_s = seconds_since(start);
    std::printf(
        "%s: %zu lights, %zu regular samples; oracle %.2f s (normal rule %.2f s), "
        "exact minimum %llu, ambiguous pairs %zu\n",
        c.name.c_str(), c.ranged_lights.size(), samples.count(SampleClass::regular), oracle_s,
        oracle_normals_s, (unsigned long long)plain.exact_minimum(), plain.ambiguous_lights.size());
    for (const std::string& variant : lightassign().info().variants) {
      AlgorithmOutput output;
      const double ms = median_ms(3, [&] { output = lightassign().run(c, samples, variant); });
      const LightAssignmentComparison cmp = compare_light_lists(
          output.light_lists, c, samples, light_lists_use_normal_rule(variant) ? normals : plain);
      std::printf(
          "  %-14s %9.1f ms  %s  misses %llu unsound %llu  lighting %llu (%.2fx min %llu)"
          "  clusters %llu  bvh nodes %llu\n",
          variant.c_str(), ms, std::string(verdict_name(cmp.verdict)).c_str(),
          (unsigned long long)cmp.completeness_misses, (unsigned long long)cmp.unsound_listings,
          (unsigned long long)cmp.lighting_computations, cmp.lighting_ratio,
          (unsigned long long)cmp.exact_minimum,
          (unsigned long long)testing::counter(output, "unique_clusters"),
          (unsigned long long)testing::counter(output, "bvh_nodes_tested"));
      EXPECT_EQ(cmp.verdict, Verdict::pass) << variant << ": " << cmp.reason;
    }
  }
}

TEST(LightAssignTiming, DISABLED_FullHdFrom32To1MLights) {
  for (const std::uint64_t lights : {32ull, 1024ull, 32768ull, 1048576ull})
    time_full_hd("many_lights", lights);
}

TEST(LightAssignTiming, DISABLED_FullHdDepthGaps) {
  for (const std::uint64_t lights : {1024ull, 32768ull}) time_full_hd("depth_gaps", lights);
}

}  // namespace
}  // namespace shadowcts
