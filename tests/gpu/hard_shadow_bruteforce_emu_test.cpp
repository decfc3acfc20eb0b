// The brute-force kernel of the `cuda` backend run by the emulator (`cuda-emu`): the kernel's raw
// answers match the host evaluation of the same shared tests under every schedule with race
// checking on, and the backend matches the exact oracle on every robust sample, beside a
// T-junction and with the light on a caster included.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gpu/bruteforce/hard_shadow_bruteforce_backend.h"
#include "gpu/bruteforce/hard_shadow_bruteforce_emu.h"
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/emulator/emulator.h"
#include "hand_built_case.h"
#include "shadowcts/geometry/edge_proximity.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_box.h"
#include "shadowcts/geometry/segment_triangle.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/registry.h"
#include "shadowcts/runner.h"

namespace shadowcts {
namespace {

using shadowcts::testing::HandBuiltCase;

std::uint64_t counter(const AlgorithmOutput& output, const std::string& name) {
  for (const auto& [counter_name, value] : output.counters) {
    if (counter_name == name) return value;
  }
  ADD_FAILURE() << "no counter " << name;
  return 0;
}

// The kernel's contract on the host: casters whose box misses the segment's are skipped; only
// casters that the receiver half-space rule lets shadow the sample take part; shadowed at the first
// such hit away from the triangle's edges and the light's end of the segment, else unsure when
// such a caster passes near an edge or reaches that end;
// pair_tests counts casters visited, the receiver included.
BruteforceShadowResult evaluate_on_host(const BruteforceShadowInput& input) {
  BruteforceShadowResult result;
  result.shadowed.assign(input.sample_positions.size(), bruteforce_sample_lit);
  for (std::size_t i = 0; i < input.sample_positions.size(); ++i) {
    const glm::vec3 p = input.sample_positions[i];
    const RaySpace ray =
        make_ray_space(input.directional_light ? ray_to_directional_light(p, input.light)
                                               : segment_to_point_light(p, input.light));
    const BruteforceReceiver& r = input.sample_receiver_triangles[i];
    const geometry::ReceiverHalfSpace half_space =
        geometry::receiver_half_space(glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2),
                                      input.directional_light, glm::dvec3(input.light));
    const FloatBox segment = segment_box(p, input.light, input.directional_light);
    bool left_unsure = false;
    for (const BruteforceCaster& caster : input.casters) {
      ++result.pair_tests;
      if (caster.triangle == input.sample_receivers[i] ||
          !boxes_overlap(triangle_box(caster.v0, caster.v1, caster.v2), segment))
        continue;
      const bool hit = ray_hits_triangle(ray, caster.v0, caster.v1, caster.v2);
      const bool unsure =
          ray_within_rounding_of_triangle_edge(ray, caster.v0, caster.v1, caster.v2) ||
          triangle_reaches_light_end(ray, caster.v0, caster.v1, caster.v2);
      if (!hit && !unsure) continue;
      if (!geometry::caster_counts(half_space, glm::dvec3(p), glm::dvec3(caster.v0),
                                   glm::dvec3(caster.v1), glm::dvec3(caster.v2)))
        continue;
      if (hit && !unsure) {
        result.shadowed[i] = bruteforce_sample_shadowed;
        break;
      }
      left_unsure = left_unsure || unsure;
    }
    if (result.shadowed[i] != bruteforce_sample_shadowed && left_unsure) {
      result.shadowed[i] = bruteforce_sample_unsure;
    }
  }
  return result;
}

HandBuiltCase random_case(bool directional, std::uint64_t seed) {
  return shadowcts::testing::make_random_case(
      seed, 8, 300, 1.5f, 1500,
      directional ? shadowcts::testing::directional_light({0.3f, 1.0f, -0.2f})
                  : shadowcts::testing::point_light({1.0f, 9.0f, 2.0f}));
}

TEST(BruteforceHardShadowCudaEmu, DescribesItselfAsEmulated) {
  const auto algorithm = make_bruteforce_hard_shadow_cuda_emu();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "bruteforce");
  EXPECT_EQ(info.backend, "cuda-emu");
  ASSERT_EQ(info.variants, std::vector<std::string>{"float32"});
  EXPECT_NE(info.summary.find("EMULATED"), std::string::npos) << info.summary;
  const HandBuiltCase h = random_case(false, 1);
  EXPECT_EQ(algorithm->unsupported_reason(h.c, h.samples, "float32"), std::nullopt);
  const AlgorithmOutput output = algorithm->run(h.c, h.samples, "float32");
  EXPECT_GT(counter(output, "emulated_threads"), 0u);
}

TEST(BruteforceHardShadowCudaEmu, KernelMatchesHostEvaluationUnderEverySchedule) {
  for (const bool directional : {false, true}) {
    const HandBuiltCase h = random_case(directional, directional ? 2 : 3);
    std::vector<std::size_t> regular;
    const BruteforceShadowInput input = bruteforce_kernel_input(h.c, h.samples, regular);
    const BruteforceShadowResult host = evaluate_on_host(input);
    std::size_t shadowed = 0;
    for (const std::uint8_t s : host.shadowed) shadowed += s == bruteforce_sample_shadowed;
    ASSERT_GT(shadowed, host.shadowed.size() / 10);  // the scene does cast shadows
    ASSERT_LT(shadowed, host.shadowed.size());
    std::vector<emu::Options> schedules{{emu::Schedule::run_until_block, 0, true}};
    for (const std::uint64_t seed : {1, 2})
      schedules.push_back({emu::Schedule::random, seed, true});
    for (const emu::Options& options : schedules) {
      const emu::ScopedOptions scoped(options);
      const BruteforceShadowResult emulated = run_bruteforce_hard_shadow_kernel_emulated(input);
      EXPECT_EQ(emulated.shadowed, host.shadowed)
          << (directional ? "directional" : "point") << ", seed " << options.seed;
      EXPECT_EQ(emulated.pair_tests, host.pair_tests);
    }
  }
}

void expect_robust_samples_match(const HandBuiltCase& h, const AlgorithmOutput& output) {
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  std::size_t robust = 0;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    if (truth.band[i] == BandClass::robust_lit) {
      ++robust;
      EXPECT_EQ(output.shadowed[i], 0) << "sample " << i;
    } else if (truth.band[i] == BandClass::robust_shadowed) {
      ++robust;
      EXPECT_EQ(output.shadowed[i], 1) << "sample " << i;
    }
  }
  EXPECT_GT(robust, 0u);
}

TEST(BruteforceHardShadowCudaEmu, MatchesTheExactOracleOnRobustSamples) {
  const auto algorithm = make_bruteforce_hard_shadow_cuda_emu();
  for (const bool directional : {false, true}) {
    const HandBuiltCase h = random_case(directional, 4);
    expect_robust_samples_match(h, algorithm->run(h.c, h.samples, "float32"));
  }
}

// fuzz_watertight-531e78eca2acc5e5 (as in the metric tests): a T-junction with a segment exactly
// through the covered edge piece. The float test misses both triangles; the kernel must say
// unsure there and the host decide it shadowed.
TEST(BruteforceHardShadowCudaEmu, NoLeakThroughACrackAtATJunction) {
  const auto [h, sample] = shadowcts::testing::t_junction_crack();
  const HardShadowTruth truth = exact_hard_shadow_oracle(h.c, h.samples);
  ASSERT_EQ(truth.band[sample], BandClass::robust_shadowed);

  std::vector<std::size_t> regular;
  const BruteforceShadowResult raw =
      run_bruteforce_hard_shadow_kernel_emulated(bruteforce_kernel_input(h.c, h.samples, regular));
  EXPECT_EQ(raw.shadowed.at(0), bruteforce_sample_unsure);
  const AlgorithmOutput output =
      make_bruteforce_hard_shadow_cuda_emu()->run(h.c, h.samples, "float32");
  EXPECT_EQ(output.shadowed[sample], 1);
  EXPECT_EQ(counter(output, "exact_fallback_samples"), 1u);
}

// A point light inside a caster triangle: the closed segment of every sample ends on that
// triangle, so every sample it does not receive is shadowed. The float test decides t <= 1 on the
// rounded L - p, far from any edge, and misses some; the triangle reaches the light's end of every
// segment, so the kernel leaves those samples to the exact fallback, and the host's pass for a
// light on a caster has nothing left to change.
TEST(BruteforceHardShadowCudaEmu, LightOnACasterShadowsEverySampleItDoesNotReceive) {
  auto h =
      shadowcts::testing::make_hand_built_case(shadowcts::testing::point_light({1.5f, 4, 1.5f}));
  const std::uint32_t holder = h.add_triangle({1, 4, 1}, {3, 4, 1}, {1, 4, 3});
  // Not dyadic, so L - p rounds.
  for (int i = 0; i < 32; ++i) {
    const float f = static_cast<float>(i);
    h.add_ground_sample({-6.1f + 0.213f * f, 0.0f, -5.3f + 0.171f * f});
  }
  const std::size_t on_holder = h.add_sample({1.5f, 4.0f, 1.5f}, holder);
  const AlgorithmOutput output =
      make_bruteforce_hard_shadow_cuda_emu()->run(h.c, h.samples, "float32");
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    EXPECT_EQ(output.shadowed[i], i == on_holder ? 0 : 1) << "sample " << i;
  }
  EXPECT_GT(counter(output, "exact_fallback_samples"), 0u);
  EXPECT_EQ(counter(output, "light_on_caster_samples"), 0u);
  expect_robust_samples_match(h, output);
}

// stiff.light_1e-6_from_caster: segments cross a quad's plane within ~3e-8 of its edge next to
// the light, where the rounding of L - p makes the float test hit on samples that are robustly
// lit. A float hit beside an edge is decided exactly too (157 false shadows before).
// stiff.light_1ulp_off_caster_face: segments cross a face's plane within ~1e-8 of L, away from its
// edges; an answer about a triangle at the light's end of the segment is decided exactly too (a
// few false shadows before).
TEST(BruteforceHardShadowCudaEmu, PassesTheStiffCasesWithTheLightNextToACaster) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / "shadowcts_cuda_emu_light_next_to_caster";
  fs::remove_all(out);
  RunOptions options;
  options.fixtures = {"stiff.light_1e-6_from_caster", "stiff.light_1ulp_off_caster_face"};
  options.algorithms = {{"bruteforce", "float32"}};
  options.backends = {"cuda-emu"};
  options.out_dir = out.string();
  options.repeats = 1;
  std::ostringstream log, err;
  EXPECT_EQ(run_suite(options, builtin_registry(), log, err), exit_pass) << err.str();
  std::ifstream in(out / "results.json");
  const auto results = nlohmann::json::parse(in);
  ASSERT_EQ(results["results"].size(), 2u) << log.str();
  for (const auto& record : results["results"]) {
    EXPECT_EQ(record["verdict"], "Pass") << record["case"] << ": " << record["reason"];
    EXPECT_EQ(record["backend"], "cuda-emu");
    EXPECT_GT(record["counters"]["exact_fallback_samples"].get<std::uint64_t>(), 0u);
  }
  fs::remove_all(out);
}

}  // namespace
}  // namespace shadowcts
