// One realistic bug in the tiled kernels' source (a mutated copy of tiled_assignment.cuh written
// by the build, see CMakeLists.txt), run by the emulator with race checking: the emulator must
// report it in the tile reduction. SHADOWCTS_MUTANT_KIND is the ErrorKind it must report. The
// unmutated kernels run clean under race checking (lightassign_emu_test's random schedule).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>

#include "gpu/lightassign/lightassign_kernels.cuh"  // includes the mutated tiled_assignment.cuh

namespace shadowcts {
namespace {

// A 64 x 64 view of the plane z = 0 from (0, 0, 5): four tiles of 1024 samples, 200 lights.
LightAssignKernelInput ground() {
  LightAssignKernelInput in;
  in.frame.origin = {0.0, 0.0, 5.0};
  in.frame.forward = {0.0, 0.0, -1.0};
  in.frame.right = {1.0, 0.0, 0.0};
  in.frame.up = {0.0, 1.0, 0.0};
  in.frame.tan_half_fov = std::tan(0.5);
  in.frame.width = in.frame.height = 64;
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) {
      in.sample_pixel.push_back(y * 64 + x);
      in.sample_position.push_back(
          {(float(x) - 31.5f) / 32.0f * 2.7f, (31.5f - float(y)) / 32.0f * 2.7f, 0.0f});
      in.sample_normal.push_back({0.0f, 0.0f, 1.0f});
    }
  std::mt19937 random(5);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int l = 0; l < 200; ++l)
    in.lights.push_back({{3.0f * unit(random), 3.0f * unit(random), 0.5f + unit(random)},
                         0.3f + 0.2f * unit(random)});
  in.tiled = true;
  return in;
}

TEST(LightAssignKernelMutant, IsReportedByTheEmulator) {
  const emu::ScopedOptions options({emu::Schedule::run_until_block, 0, true});
  try {
    emulated::lightassign::run(ground());
    FAIL() << "the mutant ran without a report";
  } catch (const emu::EmulatorError& error) {
    EXPECT_EQ(error.kind, emu::ErrorKind::SHADOWCTS_MUTANT_KIND) << error.what();
    EXPECT_EQ(error.kernel, "tile_volumes") << error.what();
    std::cout << error.what() << "\n";
  }
}

}  // namespace
}  // namespace shadowcts
