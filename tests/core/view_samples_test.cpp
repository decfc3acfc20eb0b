#include "shadowcts/view_samples.h"

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <glm/geometric.hpp>

#include "shadowcts/case.h"
#include "shadowcts/geometry/camera_frame.h"

namespace shadowcts {
namespace {

// A ground quad (y = 0, half-width 20) seen from above, a small quad standing on it facing +z, a
// point light.
Case ground_and_wall(ShadowLight light) {
  Case c;
  c.name = "test.ground_wall";
  c.source = "test";
  c.meshes = {{"ground", false, true}, {"wall", false, true}};
  c.triangles = {{{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, 0},
                 {{-20, 0, -20}, {20, 0, 20}, {-20, 0, 20}, 0},
                 {{-1, 0, 0}, {1, 0, 0}, {1, 2, 0}, 1},
                 {{-1, 0, 0}, {1, 2, 0}, {-1, 2, 0}, 1}};
  c.light = light;
  c.camera.position = {0, 6, 8};
  c.camera.target = {0, 0, 0};
  c.camera.width = 96;
  c.camera.height = 64;
  c.camera.vertical_fov_degrees = 70;
  validate(c);
  return c;
}

ShadowLight point_light(glm::vec3 p) {
  ShadowLight l;
  l.kind = ShadowLightKind::point;
  l.position = p;
  return l;
}

// Embree asserts on ray origins beyond about 1.8e18 and misses hits at tiny scales: outside its
// range the case goes into Embree scaled by a power of two (EmbreeScene). Every scale beyond that
// range then gives the same pixels: classes, receivers and normals identical, positions exactly
// scaled (each one is interpolated from the case's own vertices with the same barycentrics).
TEST(ViewSamples, SamePixelsAtScalesOutsideEmbreesRange) {
  const auto scaled = [](int k) {
    Case c = ground_and_wall(point_light({0, 5, 3}));
    const auto scale = [k](glm::vec3& v) {
      v = {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
    };
    for (Triangle& t : c.triangles) {
      scale(t.v0);
      scale(t.v1);
      scale(t.v2);
    }
    scale(c.camera.position);
    scale(c.camera.target);
    c.camera.near_plane = std::ldexp(c.camera.near_plane, k);
    c.camera.far_plane = std::ldexp(c.camera.far_plane, k);
    scale(c.light->position);
    validate(c);
    return c;
  };
  const int base = -40;  // 20 * 2^-40 < 2^-34: already outside the range
  const ViewSamples want = generate_view_samples(scaled(base));
  std::size_t regular = 0;
  for (const ViewSample& v : want.samples) regular += v.sample_class == SampleClass::regular;
  EXPECT_GT(regular, 2000u);
  for (const int k : {-100, -60, 40, 60, 90}) {
    const ViewSamples got = generate_view_samples(scaled(k));
    ASSERT_EQ(got.samples.size(), want.samples.size());
    for (std::size_t i = 0; i < want.samples.size(); ++i) {
      const ViewSample &a = want.samples[i], &b = got.samples[i];
      ASSERT_EQ(b.sample_class, a.sample_class) << "2^" << k << ", sample " << i;
      if (a.sample_class == SampleClass::sky) continue;
      ASSERT_EQ(b.receiver, a.receiver) << "2^" << k << ", sample " << i;
      for (int axis = 0; axis < 3; ++axis) {
        ASSERT_EQ(b.position[axis], std::ldexp(a.position[axis], k - base))
            << "2^" << k << ", sample " << i;
        ASSERT_EQ(b.normal[axis], a.normal[axis]) << "2^" << k << ", sample " << i;
      }
    }
  }
  // Inside Embree's range the case goes in unchanged, and the same pixels see the same surfaces.
  const ViewSamples unit = generate_view_samples(scaled(0));
  std::size_t same = 0;
  for (std::size_t i = 0; i < want.samples.size(); ++i)
    same += unit.samples[i].sample_class == want.samples[i].sample_class &&
            unit.samples[i].receiver == want.samples[i].receiver;
  EXPECT_GE(same, want.samples.size() - 8);
}

// The primary rays start at the eye and meet only the triangles: a point light far beyond them
// (it sets the case's scale S) must not change which surface a pixel sees. Before, S put the scene
// into Embree scaled by 2^-69, the triangles became denormal-sized and every pixel was sky.
TEST(ViewSamples, AFarPointLightDoesNotChangeWhatThePixelsSee) {
  const ViewSamples want = generate_view_samples(ground_and_wall(point_light({0, 5, 3})));
  for (const float distance : {1e12f, 1e20f, 1e29f}) {
    const Case c = ground_and_wall(point_light({0, distance, 0}));
    ASSERT_GT(c.scale(), 0x1p39);
    const ViewSamples got = generate_view_samples(c);
    ASSERT_EQ(got.samples.size(), want.samples.size());
    std::size_t surface = 0;
    for (std::size_t i = 0; i < want.samples.size(); ++i) {
      const ViewSample &a = want.samples[i], &b = got.samples[i];
      ASSERT_EQ(b.sample_class == SampleClass::sky, a.sample_class == SampleClass::sky)
          << distance << ", sample " << i;
      if (a.sample_class == SampleClass::sky) continue;
      ++surface;
      ASSERT_EQ(b.receiver, a.receiver) << distance << ", sample " << i;
      for (int axis = 0; axis < 3; ++axis)
        ASSERT_EQ(b.position[axis], a.position[axis]) << distance << ", sample " << i;
    }
    EXPECT_GT(surface, 5000u);
  }
}

TEST(ViewSamples, LieOnTheirReceiverWithinFloatError) {
  const Case c = ground_and_wall(point_light({0, 5, 3}));
  const ViewSamples s = generate_view_samples(c);
  ASSERT_EQ(s.samples.size(), 96u * 64u);
  std::size_t surface = 0;
  for (const ViewSample& v : s.samples) {
    if (v.sample_class == SampleClass::sky) continue;
    ++surface;
    ASSERT_LT(v.receiver, c.triangles.size());
    const Triangle& t = c.triangles[v.receiver];
    const glm::dvec3 a(t.v0), b(t.v1), cc(t.v2), p(v.position);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, cc - a));
    // Distance to the receiver's plane is a few float ulps of the coordinates (at most ~8).
    EXPECT_LT(std::fabs(glm::dot(p - a, n)), 8.0 * 20.0 * 0x1p-24) << v.pixel_x << "," << v.pixel_y;
    // The stored normal is the receiver's normal up to sign, unit length.
    EXPECT_NEAR(std::fabs(glm::dot(glm::dvec3(v.normal), n)), 1.0, 1e-6);
    EXPECT_NEAR(glm::length(glm::dvec3(v.normal)), 1.0, 1e-6);
  }
  EXPECT_GT(surface, s.samples.size() / 2);
}

// Samples cast from the camera lie inside their own pixel's view frustum (the test a variant
// declaring SHADOWCTS_VARIANT_NEEDS_SAMPLES_IN_THEIR_PIXELS is planned with), and not inside a
// neighbour's.
TEST(ViewSamples, LieInTheirOwnPixelsFrustum) {
  const Case c = ground_and_wall(point_light({0, 5, 3}));
  const ViewSamples s = generate_view_samples(c);
  const CameraFrame frame = camera_frame(c.camera);
  std::size_t surface = 0;
  for (const ViewSample& v : s.samples) {
    if (v.sample_class == SampleClass::sky) continue;
    ++surface;
    const glm::dvec3 p(v.position);
    EXPECT_TRUE(in_pixel_wedge(frame, s.width, s.height, v.pixel_x, v.pixel_y, p))
        << v.pixel_x << "," << v.pixel_y;
    EXPECT_FALSE(in_pixel_wedge(frame, s.width, s.height, v.pixel_x + 1, v.pixel_y, p));
    EXPECT_FALSE(in_pixel_wedge(frame, s.width, s.height, v.pixel_x, v.pixel_y + 1, p));
    // Behind the camera: the point mirrored through the eye.
    EXPECT_FALSE(
        in_pixel_wedge(frame, s.width, s.height, v.pixel_x, v.pixel_y, 2.0 * frame.origin - p));
  }
  EXPECT_GT(surface, s.samples.size() / 2);
}

TEST(ViewSamples, SkyAndBackFacingClasses) {
  // Light behind the wall (z < 0): the wall's camera-facing side (+z) is back-facing; the
  // camera looks down at the ground, the top rows see past the ground: sky.
  const Case c = ground_and_wall(point_light({0, 5, -3}));
  const ViewSamples s = generate_view_samples(c);
  std::size_t wall_back = 0;
  for (const ViewSample& v : s.samples) {
    if (v.sample_class == SampleClass::sky) {
      EXPECT_EQ(v.receiver, no_receiver);
      continue;
    }
    if (v.receiver >= 2) {
      EXPECT_EQ(v.sample_class, SampleClass::back_facing);
      ++wall_back;
    } else {
      EXPECT_EQ(v.sample_class, SampleClass::regular);  // ground faces up, light above
    }
  }
  EXPECT_GT(wall_back, 0u);
  EXPECT_GT(s.count(SampleClass::sky), 0u);
  // Pixel coordinates are row-major, top row first.
  EXPECT_EQ(s.samples[96 * 3 + 5].pixel_x, 5u);
  EXPECT_EQ(s.samples[96 * 3 + 5].pixel_y, 3u);
}

TEST(ViewSamples, ByteIdenticalForOneAndTwoThreads) {
  const Case c = ground_and_wall(point_light({0, 5, 3}));
  ViewSamples one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = generate_view_samples(c);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = generate_view_samples(c);
  }
  ASSERT_EQ(one.samples.size(), two.samples.size());
  EXPECT_EQ(0, std::memcmp(one.samples.data(), two.samples.data(),
                           one.samples.size() * sizeof(ViewSample)));
}

}  // namespace
}  // namespace shadowcts
