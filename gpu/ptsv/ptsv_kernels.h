#pragma once
// Launch interface of the CUDA ptsv (Sintorn 2014 per-triangle shadow volumes over the view-sample
// cluster hierarchy). Plain data only, so that the C++20 host side (ptsv_algorithm.cpp) and the
// C++17 CUDA translation unit share it. The host sets up what the reference sets up once per case
// (the shadow volumes, the receivers' half-spaces and reject reaches, the depth-slice table); the
// device computes the cluster keys, builds the hierarchy and traverses it.
#include <cstdint>
#include <vector>

#include "reference/ptsv/counters.h"
#include "shadowcts/geometry/receiver_half_space.h"

namespace shadowcts::gpu_ptsv {

inline constexpr std::uint32_t no_key = 0xFFFFFFFFu;  // ptsv::no_key
inline constexpr std::uint32_t no_sample = 0xFFFFFFFFu;

// ptsv::Plane: value = ((n.x (x - a.x) + n.y (y - a.y)) + n.z (z - a.z)) + shift.
struct Plane {
  double normal[3];
  double anchor[3];
  double shift;
};

// ptsv::ShadowVolume, flattened: planes 0-2 the edges, 3 the triangle, 4.. the extra culling
// planes; the exact definition (canonical vertices and outside signs) for samples within the
// rounding of a plane; the caster's own vertices for the receiver half-space rule.
struct Volume {
  Plane plane[7];
  double condition[4];
  float exact_vertices[9];
  std::int32_t edge_outside[3];
  std::int32_t triangle_outside;
  float exact_light[3];  // the point light, or the direction towards the light
  std::int32_t directional;
  std::int32_t extra_count;
  std::uint32_t triangle;
  float caster[9];
};

struct Sample {
  float position[3];
  std::uint32_t receiver;    // triangle index or no_receiver
  std::uint32_t half_space;  // index into KernelInput::half_spaces
  std::uint32_t pixel_x, pixel_y;
  std::uint32_t regular;  // 1: a regular sample (the others get no key and are never tested)
  double reach;           // ptsv::ReceiverRule::reject_reach
};

// ptsv::ClusterKeyLayout and the part of ptsv::ViewFrame the keys and implicit cells need.
struct Layout {
  std::uint32_t tiles_x, tiles_y;
  std::int32_t x_bits, y_bits, depth_bits;
  std::int32_t leaf_level;  // mask_levels()
  std::uint32_t width, height;
  double origin[3], right[3], up[3], forward[3];
  double tan_half_fov, aspect;
};

struct KernelInput {
  std::vector<Sample> samples;  // every view sample, in ViewSamples order
  std::vector<geometry::ReceiverHalfSpace> half_spaces;
  std::vector<Volume> volumes;  // in triangle order (the reference's volume order)
  // slice_start[k] = ClusterKeyLayout::slice_start(k) for k = 0 .. 2^depth_bits, computed by the
  // host's std::pow so the device's slices are the reference's bit for bit.
  std::vector<double> slice_start;
  Layout layout{};
  bool implicit_cells = false;  // else explicit boxes
  bool extra_planes = false;
  std::int32_t job_level = -1;  // two-pass: the level whose visits are the jobs; -1: one pass
  // ptsv::NodeTolerances: the accept bias, and the rounding as a function of the node bound (the
  // scene bound; implicit cells: also the largest corner of a level-1 cell, found on the device).
  double scene_bound = 0.0, accept_bias = 0.0;
  double (*rounding_for_node_bound)(double) = nullptr;
};

// One level of the hierarchy as built on the device (the reference's HierarchyLevel).
struct Level {
  std::vector<std::uint32_t> index, child_mask;  // child_mask before the traversal
  std::vector<double> lo, hi;                    // explicit bounds, 3 per node (x, y, z)
  std::vector<double> reach;
};

struct KernelResult {
  // The first view sample the key layout cannot hold (no_sample: none); nothing else is filled in
  // then (the host asks the reference for the message).
  std::uint32_t first_bad_sample = no_sample;
  std::vector<std::uint32_t> key;      // per view sample, no_key for the others
  std::vector<Level> levels;           // 0 .. leaf_level
  std::vector<std::uint8_t> shadowed;  // per view sample
  ptsv::TraversalCounters counters;
  std::uint64_t threads = 0;  // CUDA threads launched by the kernels
};

// Runs on the current CUDA device; throws std::runtime_error if a CUDA call fails.
KernelResult run_ptsv_kernels(KernelInput input);

// The same kernel sources run by the CUDA-subset emulator on the host (gpu/emulator).
KernelResult run_ptsv_kernels_emulated(KernelInput input);

}  // namespace shadowcts::gpu_ptsv
