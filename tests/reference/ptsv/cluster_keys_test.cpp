// Cluster keys: the layout's bits, keys of hand-placed samples, the implicit cells around them,
// and the refusal (never a wrap-around) when a case needs more bits than the key has.
#include "reference/ptsv/cluster_keys.h"

#include <cmath>

#include <gtest/gtest.h>

#include "reference/ptsv/view_frame.h"

namespace shadowcts::ptsv {
namespace {

Camera paper_camera() {
  Camera cam;
  cam.position = {0.0f, 0.0f, 0.0f};
  cam.target = {0.0f, 0.0f, -1.0f};
  cam.up = {0.0f, 1.0f, 0.0f};
  cam.vertical_fov_degrees = 60.0f;
  cam.near_plane = 0.5f;
  cam.far_plane = 100.0f;
  cam.width = 1024;
  cam.height = 1024;
  return cam;
}

TEST(ClusterKeyLayout, PaperResolutionNeedsSevenBitsPerScreenAxis) {
  Camera cam = paper_camera();
  cam.near_plane = 1.0f;
  cam.far_plane = 90.0f;
  const KeyLayoutResult r = make_cluster_key_layout(cam, 1024, 1024);
  ASSERT_TRUE(r.problem.empty()) << r.problem;
  EXPECT_EQ(r.layout.tiles_x, 128u);
  EXPECT_EQ(r.layout.x_bits, 7);
  EXPECT_EQ(r.layout.y_bits, 7);
  // 1 + 2 tan(30 deg) / 128; slices up to the one holding far = 90 near.
  const double ratio = 1.0 + 2.0 * std::tan(3.14159265358979323846 / 6.0) / 128.0;
  EXPECT_NEAR(r.layout.slice_ratio, ratio, 1e-15);
  const auto slices = std::uint32_t(std::floor(std::log(90.0) / std::log(ratio))) + 1;
  EXPECT_EQ(r.layout.depth_slices, slices);
  EXPECT_EQ(r.layout.depth_bits, 9);  // the paper's nine depth bits: 23-bit keys
  EXPECT_EQ(r.layout.key_bits(), 23);
  EXPECT_EQ(r.layout.mask_levels(), 5);  // five levels of masks, MAXLEVELS = 6 in Algorithm 1
}

TEST(ClusterKeyLayout, RefusesCasesThatNeedMoreThan32Bits) {
  Camera cam = paper_camera();
  cam.near_plane = 1e-6f;
  cam.far_plane = 1e6f;
  const KeyLayoutResult r = make_cluster_key_layout(cam, 16384, 16384);
  EXPECT_GT(r.layout.key_bits(), key_bits_available);
  EXPECT_NE(r.problem.find("bits"), std::string::npos) << r.problem;
}

TEST(ClusterKeyLayout, InterleavesXYDepthFromTheBottomWithExtraDepthBitsOnTop) {
  ClusterKeyLayout layout;
  layout.x_bits = 2;
  layout.y_bits = 2;
  layout.depth_bits = 4;
  // bit 0: x0, 1: y0, 2: z0, 3: x1, 4: y1, 5: z1, 6: z2, 7: z3
  EXPECT_EQ(layout.interleave({1, 0, 0}), 0b1u);
  EXPECT_EQ(layout.interleave({0, 1, 0}), 0b10u);
  EXPECT_EQ(layout.interleave({0, 0, 1}), 0b100u);
  EXPECT_EQ(layout.interleave({2, 0, 0}), 0b1000u);
  EXPECT_EQ(layout.interleave({0, 2, 0}), 0b10000u);
  EXPECT_EQ(layout.interleave({0, 0, 2}), 0b100000u);
  EXPECT_EQ(layout.interleave({0, 0, 12}), 0b11000000u);
  for (std::uint32_t x = 0; x < 4; ++x)
    for (std::uint32_t y = 0; y < 4; ++y)
      for (std::uint32_t z = 0; z < 16; ++z) {
        const ClusterCoordinate c = layout.deinterleave(layout.interleave({x, y, z}));
        EXPECT_EQ(c.x, x);
        EXPECT_EQ(c.y, y);
        EXPECT_EQ(c.slice, z);
      }
}

// One sample per pixel of a 64x32 image; samples placed by hand on the rays of chosen pixels.
struct PlacedSamples {
  Camera cam = paper_camera();
  ViewSamples samples;
  ViewFrame frame;
  PlacedSamples() {
    cam.width = 64;
    cam.height = 32;
    samples.width = 64;
    samples.height = 32;
    samples.samples.resize(64 * 32);
    for (std::uint32_t y = 0; y < 32; ++y)
      for (std::uint32_t x = 0; x < 64; ++x) {
        samples.samples[y * 64 + x].pixel_x = x;
        samples.samples[y * 64 + x].pixel_y = y;
      }
    frame = make_view_frame(cam, 64, 32);
  }
  // A regular sample at pixel (x, y)'s centre ray, at view depth `depth`.
  void place(std::uint32_t x, std::uint32_t y, double depth) {
    const double sx = (screen_x_of_column(frame, x) + screen_x_of_column(frame, x + 1)) / 2;
    const double sy = (screen_y_of_row(frame, y) + screen_y_of_row(frame, y + 1)) / 2;
    ViewSample& s = samples.samples[y * 64 + x];
    s.position =
        glm::vec3(frame.origin + depth * (frame.forward + sx * frame.right + sy * frame.up));
    s.sample_class = SampleClass::regular;
    s.receiver = 0;
  }
};

TEST(ClusterKeys, KeysOfHandPlacedSamples) {
  PlacedSamples p;
  const KeyLayoutResult r = make_cluster_key_layout(p.cam, 64, 32);
  ASSERT_TRUE(r.problem.empty());
  const ClusterKeyLayout& layout = r.layout;
  EXPECT_EQ(layout.tiles_x, 8u);
  EXPECT_EQ(layout.tiles_y, 4u);
  // Slice k starts at near * ratio^k: put samples in the middle of slices 0, 5 and 40.
  auto middle_of_slice = [&](std::uint32_t k) {
    return std::sqrt(std::max(layout.slice_start(k), layout.near) * layout.slice_start(k + 1));
  };
  p.place(0, 0, 0.75 * layout.near);  // in front of the near plane: slice 0
  p.place(63, 31, middle_of_slice(5));
  p.place(17, 9, middle_of_slice(20));
  p.place(8, 8, middle_of_slice(3));
  const ClusterKeys keys = assign_cluster_keys(layout, p.frame, p.samples, true);
  ASSERT_TRUE(keys.problem.empty()) << keys.problem;
  EXPECT_EQ(keys.key[0], layout.interleave({0, 0, 0}));
  EXPECT_EQ(keys.key[31 * 64 + 63], layout.interleave({7, 3, 5}));
  EXPECT_EQ(keys.key[9 * 64 + 17], layout.interleave({2, 1, 20}));
  EXPECT_EQ(keys.key[8 * 64 + 8], layout.interleave({1, 1, 3}));
  EXPECT_EQ(keys.key[1], no_key);  // not regular
  // By hand: tile (2, 1), slice 20 with 3 x bits, 2 y bits and 5 depth bits. From bit 0 up:
  // x0 y0 z0 x1 y1 z1 x2 z2 z3 z4 = 0 1 0 1 0 0 0 1 0 1.
  EXPECT_EQ(layout.x_bits, 3);
  EXPECT_EQ(layout.y_bits, 2);
  EXPECT_EQ(layout.depth_bits, 5);
  EXPECT_EQ(keys.key[9 * 64 + 17], 0b1010001010u);
}

TEST(ClusterKeys, ImplicitCellsContainTheirSamples) {
  PlacedSamples p;
  const ClusterKeyLayout layout = make_cluster_key_layout(p.cam, 64, 32).layout;
  for (std::uint32_t y = 0; y < 32; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) p.place(x, y, 0.5 + 0.37 * (x * 32 + y) / 20.0);
  const ClusterKeys keys = assign_cluster_keys(layout, p.frame, p.samples, true);
  ASSERT_TRUE(keys.problem.empty()) << keys.problem;
  for (std::size_t i = 0; i < keys.key.size(); ++i)
    for (int level = 0; level <= layout.mask_levels(); ++level) {
      const int shift = fanout_bits * (layout.mask_levels() - level);
      const FrustumCell cell =
          implicit_node_cell(layout, level, shift >= 32 ? 0 : keys.key[i] >> shift);
      const ViewPoint v = to_view(p.frame, glm::dvec3(p.samples.samples[i].position));
      EXPECT_TRUE(inside_pixel_wedge(p.frame, v, cell.x0, cell.x1, cell.y0, cell.y1));
      EXPECT_GE(v.depth, cell.depth0);
      EXPECT_LE(v.depth, cell.depth1);
    }
}

TEST(ClusterKeys, ReportsSamplesTheLayoutCannotHold) {
  PlacedSamples p;
  const ClusterKeyLayout layout = make_cluster_key_layout(p.cam, 64, 32).layout;
  p.place(3, 3, 1.0);
  EXPECT_TRUE(assign_cluster_keys(layout, p.frame, p.samples, true).problem.empty());
  // Beyond the last representable slice: refused, not wrapped into slice 0.
  p.place(5, 5, layout.slice_start((1u << layout.depth_bits)) * 1.5);
  const std::string beyond = assign_cluster_keys(layout, p.frame, p.samples, true).problem;
  EXPECT_NE(beyond.find("depth bits"), std::string::npos) << beyond;
  p.samples.samples[5 * 64 + 5].sample_class = SampleClass::sky;
  // A sample outside its tile's frustum: implicit bounds refuse it, explicit ones do not care.
  p.place(20, 20, 2.0);
  p.samples.samples[20 * 64 + 20].pixel_x = 40;
  EXPECT_FALSE(assign_cluster_keys(layout, p.frame, p.samples, true).problem.empty());
  EXPECT_TRUE(assign_cluster_keys(layout, p.frame, p.samples, false).problem.empty());
}

}  // namespace
}  // namespace shadowcts::ptsv
