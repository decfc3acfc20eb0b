// The device build and the emulated build of each kernel on the same cases, sample by sample
// (ci/device.sh runs this where a GPU is lent). Every robust sample must get the same answer;
// every difference is listed with its class in the ambiguity band, and a table gives the sizes
// and times. Without a device it is skipped with the reason.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/device.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/registry.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {
namespace {

const char* band_name(BandClass b) {
  switch (b) {
    case BandClass::robust_lit:
      return "robust lit";
    case BandClass::robust_shadowed:
      return "robust shadowed";
    case BandClass::ambiguous:
      return "ambiguous";
    case BandClass::not_compared:
      break;
  }
  return "not compared";
}

double run_ms(const Algorithm& a, const PreparedScene& scene, AlgorithmOutput& out) {
  const auto start = std::chrono::steady_clock::now();
  out = a.run(scene, a.info().variants.front());
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

TEST(DeviceEmulatorComparison, RobustSamplesAgreeOnEveryDefaultFixture) {
  if (const auto reason = cuda_unavailable_reason()) GTEST_SKIP() << *reason;
  const Registry& registry = builtin_registry();
  int compared = 0;
  std::printf("%-26s %10s %8s %8s %12s %12s\n", "case", "regular", "differ", "robust", "device ms",
              "emulated ms");
  for (const std::string& fixture : default_fixtures()) {
    for (const auto& device : registry.algorithms()) {
      if (device->info().backend != "cuda") continue;
      if (device->info().capabilities.output != OutputKind::hard_shadow) continue;
      const Algorithm* emulated = registry.find(device->info().id, "cuda-emu");
      ASSERT_NE(emulated, nullptr) << device->info().id << " has no emulated backend";
      const Case c = hard_shadow_view(make_fixture(fixture));
      const ViewSamples samples = generate_view_samples(c);
      const std::string& variant = device->info().variants.front();
      if (device->unsupported_reason(c, samples, variant) ||
          emulated->unsupported_reason(c, samples, variant))
        continue;
      const PreparedScene scene = prepare_scene(c, samples);
      AlgorithmOutput on_device, under_emulator;
      const double device_ms = run_ms(*device, scene, on_device);
      const double emulated_ms = run_ms(*emulated, scene, under_emulator);
      ASSERT_EQ(on_device.shadowed.size(), under_emulator.shadowed.size());
      std::vector<std::size_t> differ;
      for (std::size_t i = 0; i < samples.samples.size(); ++i)
        if (on_device.shadowed[i] != under_emulator.shadowed[i]) differ.push_back(i);
      std::size_t robust = 0;
      if (!differ.empty()) {
        const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
        for (std::size_t i : differ) {
          const ViewSample& s = samples.samples[i];
          robust += truth.band[i] != BandClass::ambiguous;
          std::printf("  %s %s pixel (%u, %u): device %d, emulated %d, exact %d, %s\n",
                      c.name.c_str(), device->info().id.c_str(), s.pixel_x, s.pixel_y,
                      on_device.shadowed[i], under_emulator.shadowed[i], truth.shadowed[i],
                      band_name(truth.band[i]));
        }
      }
      std::printf("%-26s %10zu %8zu %8zu %12.1f %12.1f\n",
                  (c.name + " " + device->info().id).c_str(), scene.samples.size(), differ.size(),
                  robust, device_ms, emulated_ms);
      EXPECT_EQ(robust, 0u) << c.name << ": robust samples differ between device and emulator";
      ++compared;
    }
  }
  EXPECT_GT(compared, 0) << "no case ran on both backends";
}

bool same_box(const Aabb& a, const Aabb& b) {
  return std::memcmp(&a.min, &b.min, sizeof a.min) == 0 &&
         std::memcmp(&a.max, &b.max, sizeof a.max) == 0;
}

// Light-list kernels (lightassign): every variant's lists, boxes (bit for bit), list_of_sample
// and counters identical on the device and under the emulator.
TEST(DeviceEmulatorComparison, LightListsAreIdenticalOnEveryDefaultFixture) {
  if (const auto reason = cuda_unavailable_reason()) GTEST_SKIP() << *reason;
  const Registry& registry = builtin_registry();
  int compared = 0;
  for (const std::string& fixture : default_fixtures()) {
    const Case c = make_fixture(fixture);
    const ViewSamples samples = generate_view_samples(c);
    for (const auto& device : registry.algorithms()) {
      if (device->info().backend != "cuda") continue;
      if (device->info().capabilities.output != OutputKind::light_lists) continue;
      const Algorithm* emulated = registry.find(device->info().id, "cuda-emu");
      ASSERT_NE(emulated, nullptr) << device->info().id << " has no emulated backend";
      const PreparedScene scene = prepare_scene(c, samples);
      for (const std::string& variant : device->info().variants) {
        if (device->unsupported_reason(c, samples, variant)) continue;
        SCOPED_TRACE(c.name + " " + device->info().id + ":" + variant);
        const auto start = std::chrono::steady_clock::now();
        const AlgorithmOutput on_device = device->run(scene, variant);
        const auto middle = std::chrono::steady_clock::now();
        const AlgorithmOutput under_emulator = emulated->run(scene, variant);
        const auto end = std::chrono::steady_clock::now();
        const LightLists &a = on_device.light_lists, &b = under_emulator.light_lists;
        EXPECT_EQ(a.list_of_sample, b.list_of_sample);
        EXPECT_EQ(a.offsets, b.offsets);
        EXPECT_EQ(a.lights, b.lights);
        ASSERT_EQ(a.bounds.size(), b.bounds.size());
        for (std::size_t k = 0; k < a.bounds.size(); ++k)
          ASSERT_TRUE(same_box(a.bounds[k], b.bounds[k])) << "list " << k;
        // The emulated record carries emulated_threads after the same counters.
        ASSERT_EQ(a.offsets.size(), b.offsets.size());
        ASSERT_EQ(on_device.counters.size() + 1, under_emulator.counters.size());
        for (std::size_t i = 0; i < on_device.counters.size(); ++i)
          EXPECT_EQ(on_device.counters[i], under_emulator.counters[i]);
        std::printf("%-40s %8zu lists %12.1f ms device %12.1f ms emulated\n",
                    (c.name + " " + device->info().id + ":" + variant).c_str(),
                    a.offsets.size() - 1,
                    std::chrono::duration<double, std::milli>(middle - start).count(),
                    std::chrono::duration<double, std::milli>(end - middle).count());
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 0) << "no light-list case ran on both backends";
}

// Soft-shadow kernels repeat the reference's float operations one rounding at a time: the device
// and the emulator give the same visible fractions bit for bit, and the same counters.
TEST(DeviceEmulatorComparison, SoftKernelsAgreeBitForBitOnEveryDefaultFixture) {
  if (const auto reason = cuda_unavailable_reason()) GTEST_SKIP() << *reason;
  const Registry& registry = builtin_registry();
  int compared = 0;
  for (const std::string& fixture : default_fixtures()) {
    const Case c = make_fixture(fixture);
    const ViewSamples samples = generate_view_samples(c);
    for (const auto& device : registry.algorithms()) {
      if (device->info().backend != "cuda" ||
          device->info().capabilities.output != OutputKind::soft_shadow)
        continue;
      const Algorithm* emulated = registry.find(device->info().id, "cuda-emu");
      ASSERT_NE(emulated, nullptr) << device->info().id << " has no emulated backend";
      for (const std::string& variant : device->info().variants) {
        if (device->unsupported_reason(c, samples, variant) ||
            emulated->unsupported_reason(c, samples, variant))
          continue;
        const PreparedScene scene = prepare_scene(c, samples);
        const AlgorithmOutput on_device = device->run(scene, variant);
        const AlgorithmOutput under_emulator = emulated->run(scene, variant);
        ASSERT_EQ(on_device.visible_fraction.size(), under_emulator.visible_fraction.size());
        std::size_t differ = 0;
        for (std::size_t i = 0; i < on_device.visible_fraction.size(); ++i)
          differ += on_device.visible_fraction[i] != under_emulator.visible_fraction[i];
        EXPECT_EQ(differ, 0u) << c.name << " " << device->info().id << ":" << variant;
        for (std::size_t k = 0; k < on_device.counters.size(); ++k)
          EXPECT_EQ(on_device.counters[k], under_emulator.counters.at(k))
              << c.name << " " << device->info().id << ":" << variant;
        ++compared;
      }
    }
  }
  std::printf("soft kernels: %d case/variant pairs compared\n", compared);
}

}  // namespace
}  // namespace shadowcts
