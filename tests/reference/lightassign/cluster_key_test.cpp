// Cluster keys and exponential slices against hand-computed values (Paper II, eq. 1-2), key bit
// accounting and overflow, cube-face normal quantization.
#include "reference/lightassign/cluster_key.h"

#include <gtest/gtest.h>

#include <cmath>

namespace shadowcts {
namespace {

Camera camera_256() {
  Camera cam;
  cam.width = cam.height = 256;
  cam.vertical_fov_degrees = 60.0f;
  cam.near_plane = 0.1f;
  cam.far_plane = 100.0f;
  return cam;
}

TEST(ClusterKey, ExponentialSlicesMatchHandComputedValues) {
  // S_y = 256 / 32 = 8 tile rows; base = 1 + 2 tan(30 deg) / 8 = 1.1443375672974065;
  // K = floor(ln(100 / 0.1) / ln(base)) + 1 = floor(51.23) + 1 = 52 slices.
  const ClusterGrid grid(camera_256(), 32, 0, 0.0);
  EXPECT_EQ(grid.tiles_x(), 8u);
  EXPECT_EQ(grid.tiles_y(), 8u);
  EXPECT_NEAR(grid.slice_base(), 1.1443375672974065, 1e-12);
  EXPECT_EQ(grid.slices(), 52u);
  // Eq. 1: near_17 = 0.1 base^17 = 0.98951104, near_18 = 1.13233466.
  EXPECT_NEAR(grid.slice_near(17), 0.989511041423837, 1e-7);
  EXPECT_NEAR(grid.slice_near(18), 1.1323346579568767, 1e-7);
  EXPECT_EQ(grid.slice_near(0), double(0.1f));  // the float near plane
  // Eq. 2 (floor): depth 1 lies in [near_17, near_18); 10 in slice 34; the far plane in the last.
  EXPECT_EQ(grid.slice_of(1.0), 17u);
  EXPECT_EQ(grid.slice_of(10.0), 34u);
  EXPECT_EQ(grid.slice_of(99.9), 51u);
  EXPECT_EQ(grid.slice_of(100.0), 51u);
  EXPECT_EQ(grid.slice_of(0.1144), 0u);
  EXPECT_EQ(grid.slice_of(0.05), 0u);  // before the near plane: slice 0
  EXPECT_EQ(grid.slice_of(1e9), 51u);  // beyond the last slice: the last
  for (std::uint32_t k = 0; k < 51; ++k) {
    EXPECT_EQ(grid.slice_of(grid.slice_near(k) * (1.0 + 1e-12)), k) << k;
    EXPECT_EQ(grid.slice_of(grid.slice_near(k + 1) * (1.0 - 1e-12)), k) << k;
  }
}

TEST(ClusterKey, BitsPackingAndUnpacking) {
  const ClusterGrid plain(camera_256(), 32, 0, 0.0);
  EXPECT_EQ(plain.bits_i(), 3);
  EXPECT_EQ(plain.bits_j(), 3);
  EXPECT_EQ(plain.bits_k(), 6);  // 52 slices
  EXPECT_EQ(plain.bits_normal(), 0);
  EXPECT_EQ(plain.bits(), 12);
  const ClusterGrid normals(camera_256(), 32, 3, 0.0);
  EXPECT_EQ(normals.bits_normal(), 6);  // 3 x 3 x 6 = 54 cells
  EXPECT_EQ(normals.bits(), 18);
  // Layout, least significant first: normal, k, j, i.
  const ClusterCoordinates c{5, 6, 17, 53};
  EXPECT_EQ(normals.pack(c), (((5u << 3 | 6u) << 6 | 17u) << 6) | 53u);
  const ClusterCoordinates back = normals.unpack(normals.pack(c));
  EXPECT_EQ(back.i, 5u);
  EXPECT_EQ(back.j, 6u);
  EXPECT_EQ(back.k, 17u);
  EXPECT_EQ(back.normal, 53u);
  // A deeper sample than the far plane adds slices.
  EXPECT_GT(ClusterGrid(camera_256(), 32, 0, 1000.0).slices(), 52u);
}

TEST(ClusterKey, NearFarRatioOf1e7NeverOverflowsSilently) {
  Camera cam = camera_256();
  cam.near_plane = 1e-5f;
  cam.far_plane = 100.0f;
  // 256^2: base 1.1443, 120 slices (7 bits): fits.
  const ClusterGrid fits(cam, 32, 3, 0.0);
  EXPECT_EQ(fits.slices(), 120u);
  EXPECT_EQ(fits.overflow_reason(), std::nullopt);
  // 16384^2 at a 1-degree field of view: 512 x 512 tiles (9 + 9 bits) and base
  // 1 + 2 tan(0.5 deg) / 512, so about 472k slices (19 bits): 37 bits, rejected with the reason.
  cam.width = cam.height = 16384;
  cam.vertical_fov_degrees = 1.0f;
  const ClusterGrid overflows(cam, 32, 0, 0.0);
  EXPECT_EQ(overflows.bits_i(), 9);
  EXPECT_EQ(overflows.bits_k(), 19);
  ASSERT_TRUE(overflows.overflow_reason().has_value());
  EXPECT_NE(overflows.overflow_reason()->find("37 bits"), std::string::npos)
      << *overflows.overflow_reason();
}

TEST(ClusterKey, CubeFaceNormalQuantization) {
  // Face order +x, -x, +y, -y, +z, -z; 3 x 3 cells, row along the second other axis.
  EXPECT_EQ(quantize_normal({1, 0, 0}, 3), 0u * 9 + 1 * 3 + 1);
  EXPECT_EQ(quantize_normal({-1, 0, 0}, 3), 1u * 9 + 4);
  EXPECT_EQ(quantize_normal({0, 1, 0}, 3), 2u * 9 + 4);
  EXPECT_EQ(quantize_normal({0, -1, 0}, 3), 3u * 9 + 4);
  EXPECT_EQ(quantize_normal({0, 0, 1}, 3), 4u * 9 + 4);
  EXPECT_EQ(quantize_normal({0, 0, -1}, 3), 5u * 9 + 4);
  // +y face: u along x, v along z. (0.9, 1, -0.9): u cell 2, v cell 0.
  EXPECT_EQ(quantize_normal({0.9f, 1.0f, -0.9f}, 3), 2u * 9 + 0 * 3 + 2);
  EXPECT_EQ(quantize_normal({-0.9f, 1.0f, 0.9f}, 3), 2u * 9 + 2 * 3 + 0);
  // Ties go to the first axis.
  EXPECT_EQ(quantize_normal({1, 1, 0}, 3) / 9, 0u);
}

}  // namespace
}  // namespace shadowcts
