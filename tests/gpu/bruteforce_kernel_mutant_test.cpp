// One realistic bug in the brute-force kernel source (a mutated copy of
// hard_shadow_bruteforce_kernel.cuh written by the build, see CMakeLists.txt), run by the
// emulator with race checking: the emulator must report it, naming the mutated line's kernel.
// SHADOWCTS_MUTANT_KIND is the ErrorKind it must report.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "gpu/bruteforce/hard_shadow_bruteforce_kernel.cuh"  // the mutated copy

namespace shadowcts {
namespace {

// A triangle soup over a ground of samples; 1000 samples (a partial last block) and 600 casters
// (three tiles, the last partial).
BruteforceShadowInput soup() {
  BruteforceShadowInput input;
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    input.sample_positions.push_back({4.0f * unit(random), 4.0f * unit(random), 0.0f});
    input.sample_receivers.push_back(0);
    input.sample_receiver_triangles.push_back({{-8, -8, 0}, {8, -8, 0}, {0, 8, 0}});
  }
  input.casters.push_back({{-8, -8, 0}, {8, -8, 0}, {0, 8, 0}, 0});  // the ground: the receiver
  for (std::uint32_t t = 1; t < 600; ++t) {
    const glm::vec3 centre(4.0f * unit(random), 4.0f * unit(random), 2.0f + unit(random));
    auto corner = [&] { return centre + 0.4f * glm::vec3(unit(random), unit(random), 0.0f); };
    input.casters.push_back({corner(), corner(), corner(), t});
  }
  input.light = {0.5f, -0.3f, 10.0f};
  return input;
}

TEST(BruteforceKernelMutant, IsReportedByTheEmulator) {
  const emu::ScopedOptions options({emu::Schedule::run_until_block, 0, true});
  try {
    emulated::bruteforce::run(soup());
    FAIL() << "the mutant ran without a report";
  } catch (const emu::EmulatorError& error) {
    EXPECT_EQ(error.kind, emu::ErrorKind::SHADOWCTS_MUTANT_KIND) << error.what();
    EXPECT_EQ(error.kernel, "bruteforce_hard_shadow") << error.what();
    std::cout << error.what() << "\n";
  }
}

}  // namespace
}  // namespace shadowcts
