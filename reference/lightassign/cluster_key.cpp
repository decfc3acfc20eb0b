#include "reference/lightassign/cluster_key.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "shadowcts/geometry/camera_frame.h"

namespace shadowcts {
namespace {

// Bits that hold the values 0 .. count - 1.
int bits_for(std::uint64_t count) {
  return count <= 1 ? 0 : int(std::bit_width(count - 1));
}

}  // namespace

ClusterGrid::ClusterGrid(const Camera& camera, std::uint32_t tile_size,
                         std::uint32_t normal_divisions, double deepest)
    : tile_size_(tile_size),
      normal_divisions_(normal_divisions),
      width_(camera.width),
      height_(camera.height) {
  tiles_x_ = (width_ + tile_size_ - 1) / tile_size_;
  tiles_y_ = (height_ + tile_size_ - 1) / tile_size_;
  near_ = double(camera.near_plane);
  const double tan_theta = camera_frame(camera).tan_half_fov;
  base_ = 1.0 + 2.0 * tan_theta / double(tiles_y_);
  log_base_ = std::log(base_);
  const double far = std::max(double(camera.far_plane), deepest);
  // The last slice must reach `far`: K = floor(log(far / near) / log(base)) + 1, as a double so
  // that absurd ratios are reported rather than wrapped.
  const double slices = std::floor(std::log(far / near_) / log_base_) + 1.0;
  slices_ = slices < 1.0 ? 1 : slices > 0x1p62 ? std::uint64_t(1) << 62 : std::uint64_t(slices);
  bits_i_ = bits_for(tiles_x_);
  bits_j_ = bits_for(tiles_y_);
  bits_k_ = bits_for(slices_);
  bits_normal_ =
      normal_divisions_ == 0 ? 0 : bits_for(6ull * normal_divisions_ * normal_divisions_);
}

std::optional<std::string> ClusterGrid::overflow_reason() const {
  if (bits() <= 32) return std::nullopt;
  return "cluster key needs " + std::to_string(bits()) + " bits (i " + std::to_string(bits_i_) +
         ", j " + std::to_string(bits_j_) + ", k " + std::to_string(bits_k_) + " for " +
         std::to_string(slices_) + " depth slices, normal " + std::to_string(bits_normal_) +
         "), more than the 32-bit key";
}

double ClusterGrid::slice_near(std::uint64_t k) const {
  return near_ * std::pow(base_, double(k));
}

std::uint32_t ClusterGrid::slice_of(double depth) const {
  if (!(depth > near_)) return 0;
  const double k = std::floor(std::log(depth / near_) / log_base_);
  return std::uint32_t(std::min(k, double(slices_ - 1)));
}

std::uint32_t ClusterGrid::pack(const ClusterCoordinates& c) const {
  std::uint64_t key = c.i;
  key = (key << bits_j_) | c.j;
  key = (key << bits_k_) | c.k;
  key = (key << bits_normal_) | c.normal;
  return std::uint32_t(key);
}

ClusterCoordinates ClusterGrid::unpack(std::uint32_t key) const {
  auto take = [&](int bits) {
    const std::uint32_t value = bits == 0 ? 0 : key & ((std::uint32_t(1) << bits) - 1);
    key = bits >= 32 ? 0 : key >> bits;
    return value;
  };
  ClusterCoordinates c;
  c.normal = take(bits_normal_);
  c.k = take(bits_k_);
  c.j = take(bits_j_);
  c.i = take(bits_i_);
  return c;
}

SubFrustum ClusterGrid::sub_frustum(const ClusterCoordinates& c) const {
  SubFrustum f;
  f.x0 = double(c.i) * tile_size_;
  f.x1 = std::min(double(c.i + 1) * tile_size_, double(width_));
  f.y0 = double(c.j) * tile_size_;
  f.y1 = std::min(double(c.j + 1) * tile_size_, double(height_));
  f.near_depth = slice_near(c.k);
  f.far_depth = slice_near(c.k + 1);
  return f;
}

std::uint32_t quantize_normal(const glm::vec3& n, std::uint32_t divisions) {
  const double a[3] = {std::fabs(double(n.x)), std::fabs(double(n.y)), std::fabs(double(n.z))};
  int axis = 0;
  if (a[1] > a[axis]) axis = 1;
  if (a[2] > a[axis]) axis = 2;
  const std::uint32_t face = std::uint32_t(2 * axis + (n[axis] < 0.0f ? 1 : 0));
  if (!(a[axis] > 0.0)) return 0;
  // Face coordinates in [-1, 1] along the two other axes, in increasing axis order.
  const int u_axis = axis == 0 ? 1 : 0, v_axis = axis == 2 ? 1 : 2;
  auto cell = [&](int other) {
    const double t = (double(n[other]) / a[axis] + 1.0) * 0.5 * divisions;
    return std::uint32_t(std::clamp(std::floor(t), 0.0, double(divisions - 1)));
  };
  return face * divisions * divisions + cell(v_axis) * divisions + cell(u_axis);
}

}  // namespace shadowcts
