#pragma once
// Cluster keys of Paper II (Section 3.1, 4.1): screen tile (i, j), exponential depth slice k
// (eq. 1-2) and optionally a quantized normal direction (3x3 cells per cube face, Figure 4),
// packed into one 32-bit key. Each field takes the fewest bits that hold its range for the view;
// a view whose fields need more than 32 bits in all is rejected, never truncated.
#include <cstdint>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "reference/lightassign/view_frustum.h"

namespace shadowcts {

struct ClusterCoordinates {
  std::uint32_t i = 0, j = 0, k = 0;  // tile column, tile row (from the top), depth slice
  std::uint32_t normal = 0;           // cube face * divisions^2 + row * divisions + column
};

class ClusterGrid {
 public:
  // tile_size: pixels per tile side (Paper I's 32). normal_divisions: 0 for no normal
  // clustering, else X for X x X cells per cube face. deepest: the largest view depth to cover
  // (at least the far plane).
  ClusterGrid(const Camera& camera, std::uint32_t tile_size, std::uint32_t normal_divisions,
              double deepest);

  std::uint32_t tiles_x() const { return tiles_x_; }
  std::uint32_t tiles_y() const { return tiles_y_; }
  std::uint64_t slices() const { return slices_; }
  std::uint32_t tile_size() const { return tile_size_; }
  std::uint32_t normal_divisions() const { return normal_divisions_; }

  // Eq. 1: near_k = near (1 + 2 tan(theta) / S_y)^k, S_y the number of tile rows.
  double slice_near(std::uint64_t k) const;
  double slice_base() const { return base_; }
  // Eq. 2 with the floor: slice k holds depths [near_k, near_{k+1}) (eq. 2's ceiling labels the
  // same slice by its far plane). Depths before the near plane go to slice 0, beyond the last
  // slice to the last.
  std::uint32_t slice_of(double depth) const;

  // Bits per field and in all; the key fits when bits() <= 32.
  int bits_i() const { return bits_i_; }
  int bits_j() const { return bits_j_; }
  int bits_k() const { return bits_k_; }
  int bits_normal() const { return bits_normal_; }
  int bits() const { return bits_i_ + bits_j_ + bits_k_ + bits_normal_; }
  // Why the key cannot be packed into 32 bits, or nullopt.
  std::optional<std::string> overflow_reason() const;

  // Key layout, least significant first: normal, k, j, i (sorting a tile's keys orders its
  // samples by depth, then normal direction, as in Figure 5).
  std::uint32_t pack(const ClusterCoordinates& c) const;
  ClusterCoordinates unpack(std::uint32_t key) const;

  // The sub-frustum of the cluster (tile rectangle x slice depth range).
  SubFrustum sub_frustum(const ClusterCoordinates& c) const;

 private:
  std::uint32_t tile_size_, normal_divisions_;
  std::uint32_t width_, height_, tiles_x_, tiles_y_;
  double near_, base_, log_base_;
  std::uint64_t slices_;
  int bits_i_, bits_j_, bits_k_, bits_normal_;
};

// Cube-face quantization of a direction (Paper II, Figure 4): face 0..5 = +x, -x, +y, -y, +z,
// -z by the largest |component| (first one on ties), then X x X cells over the face.
std::uint32_t quantize_normal(const glm::vec3& n, std::uint32_t divisions);

}  // namespace shadowcts
