#pragma once
// Launch interface of the softtile kernels (softtile_tile.cuh). Plain data only, so that the C++20
// host side (the Algorithm) and the C++17 CUDA translation unit share it. Every double and float
// here is the reference's own value (reference/softtile), computed once on the host by the
// reference's expressions; the kernels repeat the reference's per-tile and per-pixel operations.
#include <cstdint>
#include <vector>

namespace shadowcts {

// The reference's DiskBitmask::max_rows.
inline constexpr int softtile_kernel_max_rows = 31;

// A truncated shadow cone (reference ShadowCone) with |tip|, the term of may_shadow's height slack.
struct SofttileCone {
  double tip[3];
  double start_height;
  double tip_length;
};

struct SofttileCluster {
  SofttileCone cone;
  std::uint32_t first, count;  // its triangles in the gathered order; count <= 64
};

// A gathered triangle: its light-space vertices (float, as the shader reads them) and its index
// into Case::triangles (to skip a pixel's own receiver).
struct SofttileTriangle {
  float vertices[9];
  std::uint32_t triangle;
};

// A tile's bound (reference TileBound) and what may_shadow needs of it, in the reference's
// expressions; built on the device from the tile's samples.
struct SofttileBound {
  double a[3], b[3], radius_a, radius_b;
  double length_a, length_b;    // |a|, |b|: terms of the height slack
  double middle[3], enclosing;  // the capsule's enclosing sphere
  double ab[3], dr, lipschitz;  // b - a, rb - ra, |b - a| + |rb - ra|
  std::uint32_t capsule;        // 0: the sphere (a, radius_a)
};

// A pixel's sample: its position (world space, float as the G-buffer holds it), the grid's
// rotation there (cos / sin of the reference's seeded angle, by the host's libm) and receiver.
struct SofttileFragment {
  float world[3];
  float cos_rotation, sin_rotation;
  std::uint32_t receiver;
  std::uint32_t relevant;  // 0: not a regular sample (left at visible fraction 1)
};

// Per tile, the kind of bound the kernel built.
inline constexpr std::uint8_t softtile_tile_empty = 0;  // no relevant pixel
inline constexpr std::uint8_t softtile_tile_sphere = 1;
inline constexpr std::uint8_t softtile_tile_capsule = 2;

// The sun as may_shadow's cone sees it: the direction d towards the light, the cone axis -d, and
// cos / sin of the angular radius (std::cos / std::sin on the host, as distance_to_cone takes
// them).
struct SofttileSun {
  double direction[3], axis[3];
  double cos_radius, sin_radius;
};

// The variant's disk bitmask: scanline centres (the reference's float expression), the lit disk.
struct SofttileRaster {
  float y[softtile_kernel_max_rows];
  std::uint32_t empty[softtile_kernel_max_rows];
  std::uint32_t full_row;
  int rows, columns;
  float half_columns;
  float inverse_scale;     // 1 / tan(a) or 1 / sin(a), in float
  float reach_per_height;  // disk_reach_per_height(inverse_scale)
  std::uint32_t disk_cells;
};

struct SofttileKernelInput {
  std::uint32_t width = 0, height = 0, tiles_x = 0, tiles_y = 0;
  std::vector<SofttileFragment> fragments;  // width * height, row-major (the samples' order)
  double eye[3] = {0.0, 0.0, 0.0};          // the camera position, for the tile bounds
  double light_axes[3][3] = {};             // light space's x, y, z axes (the reference's)
  std::vector<SofttileCluster> clusters;
  std::vector<SofttileCone> triangle_cones;  // per gathered triangle
  std::vector<SofttileTriangle> triangles;   // per gathered triangle
  SofttileSun sun{};
  SofttileRaster raster{};
  // The tile's shared candidate buffer, in triangles (1..softtile_tile_triangle_limit): a longer
  // list is rasterized in several batches. The results do not depend on it.
  std::uint32_t batch_capacity = 0;
  // For the diff tests: also return the per-tile candidate lists (device memory for every gathered
  // triangle in every tile: small frames only) and the per-pixel bitmasks.
  bool record_candidates = false, record_masks = false;
};

struct SofttileKernelResult {
  std::vector<float> visible_fraction;    // per pixel; 1 where no relevant sample
  std::vector<std::uint32_t> tests;       // per pixel: candidates tested (the receiver skipped)
  std::vector<std::uint32_t> rasterized;  // per pixel: triangles rasterized into its mask
  std::vector<std::uint32_t> candidates;  // per tile: length of its candidate list
  std::vector<std::uint8_t> tile_kinds;   // per tile: softtile_tile_empty / _sphere / _capsule
  // record_candidates: tile t's list is candidate_list[candidate_offsets[t] ..
  // candidate_offsets[t + 1]), indices into the gathered triangles in gathered order.
  std::vector<std::uint32_t> candidate_offsets, candidate_list;
  // record_masks: softtile_kernel_max_rows words per pixel (rows past the variant's are 0).
  std::vector<std::uint32_t> masks;
};

// Runs on the current CUDA device; throws std::runtime_error if a CUDA call fails.
SofttileKernelResult run_softtile_kernel(SofttileKernelInput input);

// The same kernel source run by the CUDA-subset emulator on the host (gpu/emulator); throws
// shadowcts::emu::EmulatorError where a GPU would hang or race.
SofttileKernelResult run_softtile_kernel_emulated(SofttileKernelInput input);

}  // namespace shadowcts
