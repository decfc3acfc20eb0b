// The CUDA brute-force algorithm. Without a usable device it must say so through
// unsupported_reason and never abort; with one, it must agree bit for bit with the host evaluation
// of the same shared segment/triangle test, counters included.
#include "gpu/bruteforce/hard_shadow_bruteforce_cuda.h"

#include <cuda_runtime_api.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "gpu/bruteforce/hard_shadow_bruteforce_backend.h"
#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.h"
#include "gpu/device.h"
#include "shadowcts/geometry/receiver_half_space.h"
#include "shadowcts/geometry/segment_triangle.h"

namespace shadowcts {
namespace {

// Asked directly, not through the code under test.
bool device_present() {
  int count = 0;
  const bool present = cudaGetDeviceCount(&count) == cudaSuccess && count > 0;
  cudaGetLastError();
  return present;
}

void add_quad(Case& c, std::uint32_t mesh, glm::vec3 corner, glm::vec3 u, glm::vec3 v) {
  c.triangles.push_back({corner, corner + u, corner + u + v, mesh});
  c.triangles.push_back({corner, corner + u + v, corner + v, mesh});
}

// Ground (triangles 0, 1) lit by a point light, a caster square over the left half and a
// non-caster square over the right half; samples on the ground, plus a sky and a back-facing one.
Case small_case() {
  Case c;
  c.name = "gpu.small";
  c.source = "hard_shadow_bruteforce_cuda_test";
  c.meshes = {{"ground", false, true}, {"blocker", false, true}, {"glass", false, false}};
  add_quad(c, 0, {-4.0f, -4.0f, 0.0f}, {8.0f, 0.0f, 0.0f}, {0.0f, 8.0f, 0.0f});
  add_quad(c, 1, {-3.0f, -3.0f, 1.0f}, {2.5f, 0.0f, 0.0f}, {0.0f, 6.0f, 0.0f});
  add_quad(c, 2, {0.5f, -3.0f, 1.0f}, {2.5f, 0.0f, 0.0f}, {0.0f, 6.0f, 0.0f});
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {0.0f, 0.0f, 10.0f};
  c.light = light;
  return c;
}

ViewSamples ground_samples(std::uint32_t width, std::uint32_t height) {
  ViewSamples samples;
  samples.width = width;
  samples.height = height;
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      ViewSample s;
      s.position = {-3.75f + 7.5f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width),
                    -3.75f + 7.5f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height),
                    0.0f};
      s.normal = {0.0f, 0.0f, 1.0f};
      s.receiver = s.position.x - s.position.y >= 0.0f ? 0 : 1;  // the ground's diagonal
      s.pixel_x = x;
      s.pixel_y = y;
      s.sample_class = SampleClass::regular;
      samples.samples.push_back(s);
    }
  }
  samples.samples[0].sample_class = SampleClass::sky;
  samples.samples[0].receiver = no_receiver;
  samples.samples[1].sample_class = SampleClass::back_facing;
  return samples;
}

// A random triangle soup over the ground, some of it in non-caster meshes.
Case random_case(bool directional, std::uint64_t seed) {
  Case c = small_case();
  c.name = "gpu.random";
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 3000; ++i) {
    const glm::vec3 centre(4.0f * unit(random), 4.0f * unit(random), 2.0f + unit(random));
    const std::uint32_t mesh = i % 5 == 0 ? 2 : 1;
    c.triangles.push_back({centre + 0.3f * glm::vec3(unit(random), unit(random), unit(random)),
                           centre + 0.3f * glm::vec3(unit(random), unit(random), unit(random)),
                           centre + 0.3f * glm::vec3(unit(random), unit(random), unit(random)),
                           mesh});
  }
  // A zero-area caster right over the middle of the ground: it must shadow nothing.
  c.triangles.push_back({{-2.0f, -2.0f, 0.5f}, {2.0f, 2.0f, 0.5f}, {0.0f, 0.0f, 0.5f}, 1});
  if (directional) {
    ShadowLight light;
    light.kind = ShadowLightKind::directional;
    light.direction = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));
    c.light = light;
  }
  return c;
}

struct HostEvaluation {
  std::vector<std::uint8_t> shadowed;
  std::uint64_t pair_tests = 0;
};

// The algorithm's contract, evaluated on the host with the same shared tests (the float
// segment/triangle test and the receiver half-space rule).
HostEvaluation evaluate_on_host(const Case& c, const ViewSamples& samples) {
  HostEvaluation result;
  result.shadowed.assign(samples.samples.size(), 0);
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& sample = samples.samples[i];
    if (sample.sample_class != SampleClass::regular) continue;
    const RaySpace ray =
        make_ray_space(c.light->kind == ShadowLightKind::point
                           ? segment_to_point_light(sample.position, c.light->position)
                           : ray_to_directional_light(sample.position, c.light->direction));
    const bool directional = c.light->kind != ShadowLightKind::point;
    geometry::ReceiverHalfSpace half_space;  // no plane without a receiver
    if (sample.receiver != no_receiver) {
      const Triangle& r = c.triangles[sample.receiver];
      half_space = geometry::receiver_half_space(
          glm::dvec3(r.v0), glm::dvec3(r.v1), glm::dvec3(r.v2), directional,
          glm::dvec3(directional ? c.light->direction : c.light->position));
    }
    for (std::size_t t = 0; t < c.triangles.size(); ++t) {
      const Triangle& triangle = c.triangles[t];
      if (!c.meshes[triangle.mesh].caster) continue;
      ++result.pair_tests;  // the receiver counts as a visited pair
      if (t == sample.receiver) continue;
      if (ray_hits_triangle(ray, triangle.v0, triangle.v1, triangle.v2) &&
          geometry::caster_counts(half_space, glm::dvec3(sample.position), glm::dvec3(triangle.v0),
                                  glm::dvec3(triangle.v1), glm::dvec3(triangle.v2))) {
        result.shadowed[i] = 1;
        break;
      }
    }
  }
  return result;
}

std::uint64_t counter(const AlgorithmOutput& output, const std::string& name) {
  for (const auto& [counter_name, value] : output.counters) {
    if (counter_name == name) return value;
  }
  ADD_FAILURE() << "no counter " << name;
  return 0;
}

TEST(BruteforceHardShadowCuda, DescribesItself) {
  const auto algorithm = make_bruteforce_hard_shadow_cuda();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "bruteforce");
  EXPECT_EQ(info.backend, "cuda");
  ASSERT_EQ(info.variants, std::vector<std::string>{"float32"});
  EXPECT_EQ(info.capabilities.output, OutputKind::hard_shadow);
  EXPECT_TRUE(info.capabilities.point_light);
  EXPECT_TRUE(info.capabilities.directional_light);
  EXPECT_FALSE(info.capabilities.needs_closed_meshes);
  EXPECT_GT(info.capabilities.max_sample_triangle_pairs, 0u);
}

TEST(BruteforceHardShadowCuda, WithoutDeviceReportsNoCudaDevice) {
  if (device_present()) GTEST_SKIP() << "a CUDA device is present: " << cuda_device_summary();
  const auto algorithm = make_bruteforce_hard_shadow_cuda();
  const Case c = small_case();
  const ViewSamples samples = ground_samples(8, 8);
  const std::optional<std::string> reason = algorithm->unsupported_reason(c, samples, "float32");
  ASSERT_TRUE(reason.has_value());
  EXPECT_EQ(reason->rfind("no CUDA device: ", 0), 0u) << *reason;
  EXPECT_GT(reason->size(), std::string("no CUDA device: ").size()) << "names the CUDA error";
  EXPECT_EQ(cuda_device_summary().rfind("no CUDA device (", 0), 0u) << cuda_device_summary();
  // Capability problems still come first.
  EXPECT_EQ(algorithm->unsupported_reason(c, samples, "float64"), "unknown variant 'float64'");
  // Run anyway: an exception, not an abort.
  EXPECT_THROW(algorithm->run(c, samples, "float32"), std::runtime_error);
}

TEST(BruteforceHardShadowCuda, WithDeviceShadowsTheSmallCase) {
  if (!device_present()) GTEST_SKIP() << cuda_device_summary();
  const auto algorithm = make_bruteforce_hard_shadow_cuda();
  const Case c = small_case();
  const ViewSamples samples = ground_samples(16, 16);
  ASSERT_EQ(algorithm->unsupported_reason(c, samples, "float32"), std::nullopt);
  const AlgorithmOutput output = algorithm->run(c, samples, "float32");
  ASSERT_EQ(output.shadowed.size(), samples.samples.size());
  EXPECT_EQ(output.shadowed[0], 0);  // sky
  EXPECT_EQ(output.shadowed[1], 0);  // back-facing
  for (std::size_t i = 2; i < samples.samples.size(); ++i) {
    const glm::vec3 p = samples.samples[i].position;
    // The light is at height 10 over the origin and the blocker at height 1 covers x in
    // [-3, -0.5]: its shadow on the ground covers x in [-3.33, -0.56] (y likewise scaled).
    const bool under_blocker = p.x > -3.3f && p.x < -0.6f && p.y > -3.3f && p.y < 3.3f;
    const bool clear = p.x > -0.5f || p.x < -3.4f || p.y > 3.4f || p.y < -3.4f;
    if (under_blocker) {
      EXPECT_EQ(output.shadowed[i], 1) << p.x << " " << p.y;
    }
    if (clear) {
      EXPECT_EQ(output.shadowed[i], 0) << p.x << " " << p.y;  // glass casts nothing
    }
  }
  const HostEvaluation host = evaluate_on_host(c, samples);
  // Samples beside an edge are decided exactly on the host; elsewhere the answers are the
  // float test's, bit for bit.
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < host.shadowed.size(); ++i) {
    mismatches += output.shadowed.at(i) != host.shadowed[i] ? 1 : 0;
  }
  EXPECT_LE(mismatches, counter(output, "exact_fallback_samples"));
}

TEST(BruteforceHardShadowCuda, WithDeviceMatchesHostEvaluationBitForBit) {
  if (!device_present()) GTEST_SKIP() << cuda_device_summary();
  const auto algorithm = make_bruteforce_hard_shadow_cuda();
  for (const bool directional : {false, true}) {
    const Case c = random_case(directional, directional ? 5 : 6);
    const ViewSamples samples = ground_samples(61, 67);  // not a multiple of the block size
    const AlgorithmOutput output = algorithm->run(c, samples, "float32");
    const HostEvaluation host = evaluate_on_host(c, samples);
    // Samples beside an edge are decided again exactly on the host (exact_fallback_samples):
    // there the float answer may differ by design.
    std::size_t mismatches = 0, shadowed = 0;
    for (std::size_t i = 0; i < host.shadowed.size(); ++i) {
      mismatches += output.shadowed.at(i) != host.shadowed[i] ? 1 : 0;
      shadowed += host.shadowed[i];
    }
    EXPECT_LE(mismatches, counter(output, "exact_fallback_samples"))
        << (directional ? "directional" : "point");
    EXPECT_GT(shadowed, host.shadowed.size() / 10);  // the scene does cast shadows
    EXPECT_LT(shadowed, host.shadowed.size());
    // A float hit beside an edge does not end the kernel's search: it may visit more pairs.
    EXPECT_GE(counter(output, "pair_tests"), host.pair_tests);
  }
}

// The same kernel source on the device and under the emulator: the raw per-sample answers
// (unsure ones included) and the pair count agree bit for bit.
TEST(BruteforceHardShadowCuda, WithDeviceMatchesTheEmulatorBitForBit) {
  if (!device_present()) GTEST_SKIP() << cuda_device_summary();
  for (const bool directional : {false, true}) {
    const Case c = random_case(directional, directional ? 7 : 8);
    const ViewSamples samples = ground_samples(61, 67);
    std::vector<std::size_t> regular;
    const BruteforceShadowInput input = bruteforce_kernel_input(c, samples, regular);
    const BruteforceShadowResult device = run_bruteforce_hard_shadow_kernel(input);
    const BruteforceShadowResult emulated = run_bruteforce_hard_shadow_kernel_emulated(input);
    EXPECT_EQ(device.shadowed, emulated.shadowed) << (directional ? "directional" : "point");
    EXPECT_EQ(device.pair_tests, emulated.pair_tests);
  }
}

}  // namespace
}  // namespace shadowcts
