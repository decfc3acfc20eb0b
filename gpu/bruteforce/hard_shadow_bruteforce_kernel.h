#pragma once
// Launch interface of the brute-force hard-shadow kernel. Plain data only, so that the C++20 host
// side (the Algorithm) and the C++17 CUDA translation unit share it.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace shadowcts {

struct BruteforceCaster {
  glm::vec3 v0, v1, v2;
  std::uint32_t triangle;  // index into Case::triangles, to skip a sample's own receiver
};

// The vertices of a sample's receiver triangle, for the receiver half-space rule; all zero (no
// plane: every caster counts) for a sample without a receiver.
struct BruteforceReceiver {
  glm::vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
};

struct BruteforceShadowInput {
  // Regular samples only, in the order the results come back.
  std::vector<glm::vec3> sample_positions;
  std::vector<std::uint32_t> sample_receivers;
  std::vector<BruteforceReceiver> sample_receiver_triangles;
  // Triangles of caster meshes, in Case::triangles order.
  std::vector<BruteforceCaster> casters;
  bool directional_light = false;
  glm::vec3 light{0.0f};  // point light position, or unit direction towards a directional light
};

// Per-sample answers of the kernel. Only casters that the receiver half-space rule lets shadow
// the sample take part: a hit away from every edge whose crossing of the caster's plane lies
// strictly on the light's side of the receiver's plane (decided exactly) shadows it.
constexpr std::uint8_t bruteforce_sample_lit = 0;
constexpr std::uint8_t bruteforce_sample_shadowed = 1;
// No such hit, but the segment passes within the rounding of the edge of a caster the rule does
// not exclude: the host decides the sample exactly.
constexpr std::uint8_t bruteforce_sample_unsure = 2;

struct BruteforceShadowResult {
  std::vector<std::uint8_t> shadowed;  // per input sample, one of bruteforce_sample_*
  // Sample/caster pairs visited (the receiver included, as in the reference backend): each sample
  // visits casters in order and stops at its first occluder that the rule counts, so the count
  // does not depend on the launch configuration.
  std::uint64_t pair_tests = 0;
};

// Runs on the current CUDA device; throws std::runtime_error if a CUDA call fails.
BruteforceShadowResult run_bruteforce_hard_shadow_kernel(BruteforceShadowInput input);

// The same kernel source run by the CUDA-subset emulator on the host (gpu/emulator); throws
// shadowcts::emu::EmulatorError where a GPU would hang or race.
BruteforceShadowResult run_bruteforce_hard_shadow_kernel_emulated(BruteforceShadowInput input);

}  // namespace shadowcts
