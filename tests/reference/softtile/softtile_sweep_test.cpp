// Every softtile variant against the exact soft-shadow oracle on the soft fixtures: within its
// declared budget, and larger grids give lower error. Prints the error-against-time table. The
// exact oracle runs on every SHADOWCTS_SOFT_SWEEP_STRIDE-th regular sample (default 9) to keep CI
// time modest; the algorithm runs on the whole image (its tiles need their neighbours).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>

#include <gtest/gtest.h>

#include "oracles/soft_shadow/soft_shadow_comparison.h"
#include "reference/softtile/softtile_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

std::size_t sweep_stride() {
  const char* text = std::getenv("SHADOWCTS_SOFT_SWEEP_STRIDE");
  return text ? std::max<std::size_t>(1, std::strtoul(text, nullptr, 10)) : 9;
}

class SofttileSweep : public ::testing::TestWithParam<const char*> {};

TEST_P(SofttileSweep, EveryVariantWithinItsBudget) {
  const Case c = make_fixture(GetParam());
  const ViewSamples samples = generate_view_samples(c);
  const ViewSamples compared = testing::every_nth_regular(samples, sweep_stride());
  const auto oracle_start = std::chrono::steady_clock::now();
  const SoftShadowTruth truth = exact_soft_shadow_oracle(c, compared);
  const double oracle_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - oracle_start).count();
  const auto algorithm = make_softtile();
  std::printf("%s: exact oracle %.3f ms/sample on %zu samples\n", GetParam(),
              1e3 * oracle_seconds / double(compared.count(SampleClass::regular)),
              compared.count(SampleClass::regular));
  std::printf(
      "| variant | mean abs e | RMS | p99 | max | bias | leaks | lit occl. | median ms | verdict "
      "|\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  std::map<std::string, double> mean_error;
  for (const std::string& variant : algorithm->info().variants) {
    std::vector<double> times;
    AlgorithmOutput output;
    // Three timed repeats (the median) for the sweep table; one in CI.
    const int repeats = std::getenv("SHADOWCTS_SOFT_SWEEP_STRIDE") ? 3 : 1;
    for (int repeat = 0; repeat < repeats; ++repeat) {
      const auto start = std::chrono::steady_clock::now();
      output = algorithm->run(c, samples, variant);
      times.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    const SoftShadowComparison r =
        compare_soft_shadows(output.visible_fraction, truth, softtile_error_budget(variant));
    mean_error[variant] = r.mean_abs_error;
    std::printf("| %s | %.5f | %.5f | %.4f | %.4f | %+.5f | %llu | %llu | %.1f | %s |\n",
                variant.c_str(), r.mean_abs_error, r.rms_error, r.p99_abs_error, r.max_abs_error,
                r.mean_signed_error, static_cast<unsigned long long>(r.umbra_leaks),
                static_cast<unsigned long long>(r.lit_occlusions), 1e3 * times[times.size() / 2],
                std::string(verdict_name(r.verdict)).c_str());
    EXPECT_EQ(r.verdict, Verdict::pass) << variant << ": " << r.reason;
    if (variant == "grid16")
      for (const auto& [name, value] : output.counters)
        std::printf("  %s = %llu\n", name.c_str(), static_cast<unsigned long long>(value));
  }
  // Finer grids, lower error.
  EXPECT_GT(mean_error["rows3"], mean_error["rows7"]);
  EXPECT_GT(mean_error["rows7"], mean_error["rows15"]);
  EXPECT_GT(mean_error["rows15"], mean_error["rows31"]);
  EXPECT_GT(mean_error["rows3"], mean_error["grid16"]);
}

INSTANTIATE_TEST_SUITE_P(SoftFixtures, SofttileSweep, ::testing::Values("foliage.10k"),
                         [](const auto& param) { return test_support::test_name(param.param); });

}  // namespace
}  // namespace shadowcts
