#pragma once
// Launch interface of the lightassign kernels (tiled and clustered light assignment, Olsson's
// Papers I and II). Plain data only, so that the C++20 host side (the Algorithm) and the C++17
// CUDA translation unit share it. What the kernels cannot compute as the reference does (glibc's
// log and pow behind the depth slices) comes from the host through LightAssignGridHooks, built from
// the reference's ClusterGrid.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace shadowcts {

// ViewFrustum's camera frame and pixel mapping, in its doubles.
struct LightAssignFrame {
  glm::dvec3 origin{0.0}, right{1.0, 0.0, 0.0}, up{0.0, 1.0, 0.0}, forward{0.0, 0.0, -1.0};
  double tan_half_fov = 1.0, aspect = 1.0;
  std::uint32_t width = 1, height = 1;
};

// The cluster grid's numbers the kernels need (ClusterGrid's, for the deepest sample).
struct LightAssignGrid {
  std::uint32_t tiles_x = 1, tiles_y = 1;
  std::uint64_t slices = 1;
  int bits_j = 0, bits_k = 0, bits_normal = 0, bits = 0;
  double near_plane = 1.0, log_base = 1.0;
};

struct LightAssignGridHooks {
  // The grid for the deepest sample depth; throws when its key does not fit 32 bits.
  std::function<LightAssignGrid(double deepest)> grid;
  // ClusterGrid::slice_of, for the depths whose slice the device's logarithm leaves in doubt.
  std::function<std::uint32_t(double depth)> slice_of;
  // ClusterGrid::slice_near(k).
  std::function<double(std::uint64_t k)> slice_near;
};

struct LightAssignSphere {
  glm::vec3 centre{0.0f};
  float range = 0.0f;
};

struct LightAssignBox {
  glm::vec3 min{0.0f}, max{0.0f};
};

struct LightAssignKernelInput {
  LightAssignFrame frame;
  // Regular samples in ascending view-sample index (= pixel_y * width + pixel_x).
  std::vector<std::uint32_t> sample_pixel;
  std::vector<glm::vec3> sample_position, sample_normal;
  std::vector<LightAssignSphere> lights;  // Case::ranged_lights' bounding spheres, in order
  std::uint32_t tile_size = 32;
  bool tiled = false;  // else clustered with the settings below
  std::uint32_t normal_divisions = 0;
  bool explicit_bounds = false, explicit_normal_cones = false;
  LightAssignGridHooks hooks;
};

// The lists and the intermediate results the reference defines (UniqueClusters, the light BVH's
// order), for the diff against the reference.
struct LightAssignKernelResult {
  std::vector<std::uint32_t> sample_key;  // per regular sample: its cluster key (tiled: 0)
  std::vector<std::uint32_t> cluster_keys, cluster_tiles;  // per list
  std::vector<std::uint32_t> member_offsets;               // per list + 1
  std::vector<std::uint32_t> members;                      // regular-sample indices by list
  std::vector<std::uint32_t> list_of_regular;              // per regular sample
  std::vector<LightAssignBox> bounds;                      // per list
  std::vector<std::uint32_t> offsets, lights;              // CSR lists
  std::vector<std::uint32_t> light_order;                  // clustered: the BVH's Morton order
  std::uint64_t nodes_tested = 0, light_tests = 0, backface_culled = 0, bounds_grown = 0;
  std::uint64_t key_bits = 0;
  std::uint64_t emulated_threads = 0;  // threads launched (the emulated backend's counter)
  double build_ms = 0.0, query_ms = 0.0;
};

// Runs on the current CUDA device; throws std::runtime_error if a CUDA call fails.
LightAssignKernelResult run_lightassign_kernels(LightAssignKernelInput input);

// The same kernel source run by the CUDA-subset emulator on the host (gpu/emulator); throws
// shadowcts::emu::EmulatorError where a GPU would hang or race.
LightAssignKernelResult run_lightassign_kernels_emulated(LightAssignKernelInput input);

}  // namespace shadowcts
