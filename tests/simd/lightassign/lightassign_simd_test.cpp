// The simd lightassign against the reference: every list (its lights in order), every declared
// box (bit for bit), list_of_sample and every counter identical, on the default fixtures with
// ranged lights, the light-assignment fixtures, the reference's stiff cases, for 1 and 2 threads
// and a second Highway target. The first difference is reported by list and position.
#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "reference/lightassign/unique_clusters.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/geometry/sphere_box.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/view_samples.h"
#include "simd/lightassign/light_bvh.h"
#include "simd/lightassign/lightassign_algorithm.h"
#include "simd/lightassign/lightassign_kernels.h"
#include "simd/lightassign/unique_clusters.h"
#include "tests/ports/output_difference.h"
#include "tests/reference/lightassign/stiff_scenes.h"

namespace shadowcts {
namespace {

using lightassign_test::small_city;

const Algorithm& reference() {
  static const std::unique_ptr<Algorithm> a = make_lightassign();
  return *a;
}

const Algorithm& ported() {
  static const std::unique_ptr<Algorithm> a = make_simd_lightassign();
  return *a;
}

bool same_float(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

// Every ported variant on one case: the reference's unsupported reasons, the same outputs.
void expect_identical(const Case& c, const ViewSamples& samples, const std::string& what) {
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string& variant : ported().info().variants) {
    SCOPED_TRACE(what + " " + variant);
    const auto why = reference().unsupported_reason(c, samples, variant);
    ASSERT_EQ(ported().unsupported_reason(c, samples, variant), why);
    if (why) continue;
    const AlgorithmOutput ref = reference().run(scene, variant);
    const AlgorithmOutput simd = ported().run(scene, variant);
    EXPECT_EQ(port_test::output_difference(ref, simd, false), "");
    EXPECT_GT(ref.light_lists.lights.size(), 0u) << "nothing listed: a weak case";
  }
}

ViewSamples samples_at(Case& c, std::uint32_t side) {
  c.camera.width = c.camera.height = side;
  return generate_view_samples(c);
}

TEST(SimdLightAssign, IdenticalToTheReferenceOnTheDefaultFixturesWithRangedLights) {
  int cases = 0;
  for (const std::string& name : default_fixtures()) {
    Case c = make_fixture(name);
    if (c.ranged_lights.empty()) continue;
    ++cases;
    const ViewSamples samples = generate_view_samples(c);
    expect_identical(c, samples, name);
  }
  EXPECT_GE(cases, 2);
}

TEST(SimdLightAssign, IdenticalToTheReferenceOnTheLightFixtures) {
  for (const auto& [name, side] : std::vector<std::pair<std::string, std::uint32_t>>{
           {"many_lights.20k", 200}, {"depth_gaps.20k", 160}, {"many_lights.2k", 77}}) {
    Case c = make_fixture(name);
    const ViewSamples samples = samples_at(c, side);
    expect_identical(c, samples, name);
  }
}

// The reference's stiff cases (tests/reference/lightassign/lightassign_stiff_test.cpp).
TEST(SimdLightAssign, IdenticalWithLightsLargerThanTheSceneAndAroundTheCamera) {
  const Case c = lightassign_test::city_with_lights_around_the_camera();
  expect_identical(c, generate_view_samples(c), "around the camera");
}

TEST(SimdLightAssign, IdenticalWithANearFarRatioOf1e7) {
  const Case c = lightassign_test::city_with_near_far_1e7();
  expect_identical(c, generate_view_samples(c), "near/far 1e-7");
}

// Samples past the far plane (the far plane moved in after they were cast): the slices reach the
// deepest sample, more of them than the far plane needs.
TEST(SimdLightAssign, IdenticalWithSamplesPastTheFarPlane) {
  Case c = small_city();
  const ViewSamples samples = generate_view_samples(c);
  c.camera.far_plane *= 0.25f;
  expect_identical(c, samples, "samples past the far plane");
}

// Samples before the near plane (the near plane moved out after they were cast): slice 0 takes
// them and its implicit box grows to hold them, member by member.
TEST(SimdLightAssign, IdenticalWithSamplesBeforeTheNearPlane) {
  Case c = small_city();
  const ViewSamples samples = generate_view_samples(c);
  double nearest = std::numeric_limits<double>::infinity();
  const ViewFrustum frustum(c.camera);
  for (const ViewSample& s : samples.samples)
    if (s.sample_class == SampleClass::regular)
      nearest = std::min(nearest, frustum.depth(glm::dvec3(s.position)));
  c.camera.near_plane = float(nearest * 1.5);
  ASSERT_LT(c.camera.near_plane, c.camera.far_plane);
  for (const std::string variant : {"clustered", "clustered+en"}) {
    const AlgorithmOutput ref = reference().run(c, samples, variant);
    const auto grown =
        std::find_if(ref.counters.begin(), ref.counters.end(),
                     [](const auto& counter) { return counter.first == "bounds_grown_samples"; });
    ASSERT_NE(grown, ref.counters.end());
    EXPECT_GT(grown->second, 0u) << variant << ": no box grew, a weak case";
  }
  expect_identical(c, samples, "samples before the near plane");
}

// Lights whose spheres touch cluster boxes within rounding: the exact fallback decides them.
TEST(SimdLightAssign, IdenticalWithLightsTangentToTheBoxes) {
  Case c = small_city();
  const ViewSamples samples = generate_view_samples(c);
  std::mt19937_64 random(7);
  std::vector<RangedLight> lights;
  std::vector<Aabb> all_boxes;
  for (const std::string variant : {"clustered", "clustered+eb", "tiled"}) {
    const std::vector<Aabb> boxes = reference().run(c, samples, variant).light_lists.bounds;
    all_boxes.insert(all_boxes.end(), boxes.begin(), boxes.end());
    const std::vector<RangedLight> tangent = lightassign_test::lights_tangent_to(boxes, random);
    lights.insert(lights.end(), tangent.begin(), tangent.end());
  }
  c.ranged_lights = lights;
  validate(c);
  // The double filter (the one the lanes evaluate) leaves some of these pairs to the exact path.
  std::size_t undecided = 0;
  for (const RangedLight& l : lights)
    for (const Aabb& b : all_boxes)
      undecided += geometry::sphere_meets_box_filter(l.centre, l.range, b.min, b.max) == 0;
  EXPECT_GT(undecided, 0u);
  expect_identical(c, samples, "tangent lights");
}

// Depths on, beside and between the slice boundaries (where eq. 2's floor is decided by the
// rounding of the reference's logarithm), before the near plane and past the last slice: the
// slice table's certain ranges, and the keys of samples at those depths.
TEST(SimdLightAssign, SlicesInLanesAreTheReferenceSlices) {
  for (const float near : {0.1f, 1e-5f, 3.0f}) {
    Camera camera;
    camera.width = 1920;
    camera.height = 1080;
    camera.near_plane = near;
    camera.far_plane = 1000.0f;
    const ClusterGrid grid(camera, 32, 0, 1000.0);
    std::vector<double> depth = {0.0, -1.0, double(near), 1e9, std::nextafter(double(near), 0.0)};
    std::mt19937_64 random(11);
    for (std::uint64_t k = 0; k <= grid.slices(); ++k) {
      double boundary = grid.slice_near(k);
      for (int step = 0; step < 3; ++step) boundary = std::nextafter(boundary, 0.0);
      for (int step = 0; step < 7; ++step, boundary = std::nextafter(boundary, 1e300))
        depth.push_back(boundary);
      depth.push_back(grid.slice_near(k) *
                      (1.0 + 0.5 * std::uniform_real_distribution<>()(random)));
    }
    // The table's certain ranges hold only their slice, boundaries included.
    const simd::SliceTable table(grid);
    ASSERT_EQ(table.low.size(), grid.slices());
    for (const double d : depth)
      for (std::size_t k = 0; k < table.low.size(); ++k)
        if (table.low[k] <= d && d < table.high[k]) {
          ASSERT_EQ(k, grid.slice_of(d)) << "depth " << d << " near " << near;
        }
    // The lanes, on samples along the camera's axis (from an eye at the origin looking down -z,
    // the view depth of (0, 0, -d) is d exactly): those depths as floats and the floats around
    // every boundary, each in pixel 0 of a row whose tile key is 0, so the keys are the slices.
    std::vector<float> z;
    for (const double d : depth) z.push_back(-float(d));
    for (std::uint64_t k = 0; k <= grid.slices(); ++k) {
      float boundary = float(grid.slice_near(k));
      for (int step = 0; step < 3; ++step) boundary = std::nextafter(boundary, 0.0f);
      for (int step = 0; step < 7; ++step, boundary = std::nextafter(boundary, 1e30f))
        z.push_back(-boundary);
    }
    camera.position = {0.0f, 0.0f, 0.0f};
    camera.target = {0.0f, 0.0f, -1.0f};
    camera.up = {0.0f, 1.0f, 0.0f};
    const simd::ViewFrame frame(camera);
    const std::vector<float> x(z.size(), 0.0f), y = x;
    const std::vector<std::uint32_t> pixel(z.size(), 0), tile_key(1, 0);
    std::vector<std::uint32_t> slices(z.size());
    double deepest = 0.0;
    simd::row_cluster_keys(frame, table, 0, tile_key.data(), 0, pixel.data(), x.data(), y.data(),
                           z.data(), z.size(), slices.data(), deepest);
    for (std::size_t i = 0; i < z.size(); ++i)
      ASSERT_EQ(slices[i], grid.slice_of(-double(z[i]))) << "depth " << -z[i] << " near " << near;
    EXPECT_EQ(deepest, -double(*std::min_element(z.begin(), z.end())));
  }
}

// Empty when the lanes' BVH is the reference's (order, leaf boxes, node boxes bit for bit), else
// the first difference.
std::string bvh_difference(const std::vector<RangedLight>& lights) {
  const LightBvh ref(lights);
  const simd::LightBvhLanes lanes(lights);
  std::ostringstream why;
  if (!std::equal(lanes.order.begin(), lanes.order.end(), ref.light_order().begin(),
                  ref.light_order().end())) {
    for (std::size_t i = 0; i < std::min(lanes.order.size(), ref.light_order().size()); ++i)
      if (lanes.order[i] != ref.light_order()[i]) {
        why << "leaf " << i << ": light " << ref.light_order()[i] << " vs " << lanes.order[i];
        return why.str();
      }
    return "leaf counts differ";
  }
  auto box_difference = [&](const Aabb& a, const simd::BoxArrays& b, std::size_t i) {
    for (int k = 0; k < 3; ++k)
      if (!same_float(a.min[k], b.min[k][i]) || !same_float(a.max[k], b.max[k][i])) return true;
    return false;
  };
  for (std::size_t i = 0; i < lanes.order.size(); ++i) {
    const RangedLight& l = lights[lanes.order[i]];
    for (int k = 0; k < 3; ++k)
      if (!same_float(lanes.sphere[k][i], l.centre[k]))
        return "leaf " + std::to_string(i) + ": centre differs";
    if (!same_float(lanes.sphere[3][i], l.range))
      return "leaf " + std::to_string(i) + ": range differs";
  }
  if (lanes.levels.size() != ref.levels().size()) return "level counts differ";
  for (std::size_t level = 0; level < lanes.levels.size(); ++level) {
    if (lanes.levels[level].count != ref.levels()[level].size())
      return "level " + std::to_string(level) + ": node counts differ";
    for (std::size_t i = 0; i < lanes.levels[level].count; ++i)
      if (box_difference(ref.levels()[level][i], lanes.levels[level], i)) {
        why << "level " << level << " node " << i << ": box differs";
        return why.str();
      }
  }
  return {};
}

// Light sets for the BVH: a fixture's, and random ones with shared centres (equal Morton codes,
// ordered by index), centres within a few ulps of each other (codes equal in their upper half),
// tiny ranges and huge ones (rounding at every magnitude, subnormal floats included), negative and
// mixed coordinates.
std::vector<std::vector<RangedLight>> bvh_light_sets() {
  std::vector<std::vector<RangedLight>> sets;
  sets.push_back(make_fixture("many_lights.20k").ranged_lights);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<float> coordinate(-50.0f, 50.0f), unit(0.0f, 1.0f);
  for (const std::size_t n : {1, 2, 31, 32, 33, 1023, 1025, 40000}) {
    std::vector<RangedLight> lights(n);
    for (std::size_t i = 0; i < n; ++i) {
      RangedLight& l = lights[i];
      switch (i % 5) {
        case 0:
          l.centre = {coordinate(random), coordinate(random), coordinate(random)};
          break;
        case 1:  // a centre shared with an earlier light
          l.centre = lights[random() % i].centre;
          break;
        case 2: {  // a few ulps from an earlier centre
          l.centre = lights[random() % i].centre;
          for (int k = 0; k < 3; ++k)
            for (int step = int(random() % 4); step > 0; --step)
              l.centre[k] = std::nextafter(l.centre[k], 1e30f);
          break;
        }
        case 3:
          l.centre = {1e-30f * coordinate(random), -3e5f * unit(random), coordinate(random)};
          if (i % 3 == 0) l.centre[2] = 1e-40f * coordinate(random);  // subnormal
          break;
        default:
          l.centre = {coordinate(random), 2.0f, -coordinate(random)};
      }
      const float ranges[] = {1e-30f, 2e-41f, 1e-7f, 0.3f * unit(random) + 1e-3f, 7.0f, 1e6f};
      l.range = ranges[random() % 6];
    }
    sets.push_back(std::move(lights));
  }
  return sets;
}

TEST(SimdLightAssign, LightBvhIsTheReferencesOnEveryHighwayTarget) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  for (const std::vector<RangedLight>& lights : bvh_light_sets()) {
    SCOPED_TRACE(std::to_string(lights.size()) + " lights");
    for (const std::int64_t target : targets) {
      SCOPED_TRACE(hwy::TargetName(target));
      hwy::SetSupportedTargetsForTest(target);
      const std::string difference = bvh_difference(lights);
      hwy::SetSupportedTargetsForTest(0);
      EXPECT_EQ(difference, "");
    }
  }
}

// The traversal in lanes against LightBvh::traverse with the exact sphere/box cull: boxes that
// touch a leaf box on a face (equal floats), stop one float short of it, hold it or are a point,
// where the leaf test on the sphere must give the leaf box's answer.
TEST(SimdLightAssign, QueriesAreTheReferenceTraversalOnEveryHighwayTarget) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  std::mt19937_64 random(5);
  for (const std::vector<RangedLight>& lights : bvh_light_sets()) {
    if (lights.size() > 2000) continue;
    const LightBvh ref(lights);
    std::vector<Aabb> boxes;
    for (std::size_t leaf = 0; leaf < lights.size(); leaf += 3) {
      const Aabb& b = ref.leaf_box(std::uint32_t(leaf));
      const int k = int(random() % 3);
      Aabb touch = b;
      touch.min[k] = b.max[k];
      touch.max[k] = b.max[k] + 1.0f;
      boxes.push_back(touch);
      touch.min[k] = std::nextafter(b.max[k], 1e30f);
      boxes.push_back(touch);
      touch = b;
      touch.max[k] = b.min[k];
      touch.min[k] = b.min[k] - 1.0f;
      boxes.push_back(touch);
      touch.max[k] = std::nextafter(b.min[k], -1e30f);
      boxes.push_back(touch);
      boxes.push_back(b);
      Aabb point;
      point.min = point.max = lights[ref.light_order()[leaf]].centre;
      boxes.push_back(point);
    }
    for (const std::int64_t target : targets) {
      SCOPED_TRACE(hwy::TargetName(target));
      hwy::SetSupportedTargetsForTest(target);
      const simd::LightBvhLanes lanes(lights);
      for (std::size_t q = 0; q < boxes.size(); ++q) {
        const Aabb& box = boxes[q];
        std::vector<std::uint32_t> expected, got;
        ListWork want;
        want.nodes_tested = ref.traverse(box, [&](std::uint32_t index) {
          ++want.light_tests;
          if (geometry::sphere_meets_box(lights[index].centre, lights[index].range, box.min,
                                         box.max))
            expected.push_back(index);
        });
        const ListWork work = simd::query_light_bvh(lanes, box, got);
        ASSERT_EQ(got, expected) << lights.size() << " lights, box " << q;
        ASSERT_EQ(work.nodes_tested, want.nodes_tested) << lights.size() << " lights, box " << q;
        ASSERT_EQ(work.light_tests, want.light_tests) << lights.size() << " lights, box " << q;
      }
      hwy::SetSupportedTargetsForTest(0);
    }
  }
}

// The unique clusters band by band against the reference's find_unique_clusters on the same
// keys: partial tiles at the image's edges, pixels without a sample, tiles with one key, with a
// few, and with more keys than a counting sort over their range would take (std::sort).
TEST(SimdLightAssign, UniqueClustersAreTheReferences) {
  std::mt19937_64 random(9);
  for (const auto& [width, height] :
       {std::pair(100u, 70u), std::pair(64u, 64u), std::pair(33u, 95u)}) {
    RegularSamples regular;
    std::vector<std::uint32_t> key,
        sample_tile(std::size_t(width) * height, UniqueClusters::no_cluster),
        sample_key(sample_tile.size(), 0);
    const std::uint32_t tiles_x = (width + 31) / 32;
    for (std::uint32_t s = 0; s < width * height; ++s) {
      if (random() % 7 == 0) continue;  // sky
      const std::uint32_t x = s % width, y = s / width, tile = (y / 32) * tiles_x + x / 32;
      std::uint32_t k;
      switch (tile % 4) {
        case 0:
          k = 5;
          break;
        case 1:
          k = std::uint32_t(random() % 3) << 8 | tile << 20;
          break;
        case 2:
          k = std::uint32_t(random() % 40) * 997 + (tile << 24);
          break;
        default:
          k = std::uint32_t(random());
          break;
      }
      regular.index.push_back(s);
      key.push_back(k);
      sample_tile[s] = tile;
      sample_key[s] = k;
    }
    regular.px.assign(regular.index.size(), 0.0f);
    regular.py = regular.pz = regular.px;
    const UniqueClusters want =
        find_unique_clusters(sample_tile, sample_key, tiles_x * ((height + 31) / 32));
    simd::UninitializedVector<std::uint32_t> member_regular;
    const UniqueClusters got =
        simd::find_unique_clusters(regular, key.data(), width, height, 32, member_regular);
    SCOPED_TRACE(std::to_string(width) + " x " + std::to_string(height));
    EXPECT_EQ(got.keys, want.keys);
    EXPECT_EQ(got.tiles, want.tiles);
    EXPECT_EQ(got.member_offsets, want.member_offsets);
    EXPECT_EQ(got.members, want.members);
    EXPECT_EQ(got.cluster_of_sample, want.cluster_of_sample);
    ASSERT_EQ(member_regular.size(), got.members.size());
    for (std::size_t e = 0; e < member_regular.size(); ++e)
      ASSERT_EQ(regular.index[member_regular[e]], got.members[e]) << e;
  }
}

// The clustered variants' keys and unique clusters in one pass (cluster_samples, and their
// members by cluster_members) against the reference's keys (ClusterGrid of ViewFrustum::depth,
// quantize_normal) and find_unique_clusters: keys, tiles, members in order, every sample's
// cluster, and each cluster's members' box.
TEST(SimdLightAssign, ClusterSamplesAreTheReferencesKeysAndClusters) {
  for (const auto& [name, side] :
       {std::pair("depth_gaps.20k", 160u), std::pair("many_lights.20k", 123u)})
    for (const std::uint32_t normal_divisions : {0u, 3u}) {
      Case c = make_fixture(name);
      const ViewSamples samples = samples_at(c, side);
      const PreparedScene scene = prepare_scene(c, samples);
      const ViewFrustum frustum(c.camera);
      double deepest = 0.0;
      for (const ViewSample& s : samples.samples)
        if (s.sample_class == SampleClass::regular)
          deepest = std::max(deepest, frustum.depth(glm::dvec3(s.position)));
      const ClusterGrid grid(c.camera, 32, normal_divisions, deepest);
      std::vector<std::uint32_t> sample_tile(samples.samples.size(), UniqueClusters::no_cluster),
          sample_key(samples.samples.size(), 0);
      for (std::size_t s = 0; s < samples.samples.size(); ++s) {
        const ViewSample& sample = samples.samples[s];
        if (sample.sample_class != SampleClass::regular) continue;
        ClusterCoordinates key{.i = sample.pixel_x / 32,
                               .j = sample.pixel_y / 32,
                               .k = grid.slice_of(frustum.depth(glm::dvec3(sample.position))),
                               .normal = 0};
        if (normal_divisions > 0) key.normal = quantize_normal(sample.normal, normal_divisions);
        sample_tile[s] = key.j * grid.tiles_x() + key.i;
        sample_key[s] = grid.pack(key);
      }
      const UniqueClusters want =
          find_unique_clusters(sample_tile, sample_key, grid.tiles_x() * grid.tiles_y());
      const simd::SampleClusters got = simd::cluster_samples(
          scene.samples, simd::ViewFrame(c.camera), grid, samples.width, samples.height);
      SCOPED_TRACE(std::string(name) + " normal divisions " + std::to_string(normal_divisions));
      EXPECT_EQ(got.deepest, deepest);
      EXPECT_EQ(got.clusters.keys, want.keys);
      EXPECT_EQ(got.clusters.tiles, want.tiles);
      EXPECT_EQ(got.clusters.member_offsets, want.member_offsets);
      EXPECT_EQ(got.clusters.cluster_of_sample, want.cluster_of_sample);
      const simd::UninitializedVector<std::uint32_t> members =
          simd::cluster_members(got.clusters, scene.samples, samples.width, samples.height, 32);
      ASSERT_EQ(members.size(), want.members.size());
      for (std::size_t e = 0; e < want.members.size(); ++e)
        ASSERT_EQ(scene.samples.index[members[e]], want.members[e]) << e;
      ASSERT_GT(want.keys.size(), 1u);
      for (std::size_t k = 0; k < want.keys.size(); ++k) {
        Aabb box;
        box.min = box.max = samples.samples[want.members[want.member_offsets[k]]].position;
        for (std::uint32_t e = want.member_offsets[k] + 1; e < want.member_offsets[k + 1]; ++e)
          grow_to_contain(box, samples.samples[want.members[e]].position);
        for (int a = 0; a < 3; ++a) {
          ASSERT_TRUE(same_float(got.low[k][a], box.min[a])) << "cluster " << k;
          ASSERT_TRUE(same_float(got.high[k][a], box.max[a])) << "cluster " << k;
        }
      }
    }
}

TEST(SimdLightAssign, ResultsDoNotDependOnTheThreadCountOrTheHighwayTarget) {
  Case c = make_fixture("depth_gaps.20k");
  const ViewSamples samples = samples_at(c, 96);
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string& variant : ported().info().variants) {
    SCOPED_TRACE(variant);
    AlgorithmOutput one, two;
    {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = ported().run(scene, variant);
    }
    {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = ported().run(scene, variant);
    }
    EXPECT_EQ(port_test::output_difference(one, two, false), "");
    // Every other target this CPU runs (SSE4 and AVX2 where AVX3 is the best, and so on).
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    for (std::size_t t = 1; t < targets.size(); ++t) {
      SCOPED_TRACE(hwy::TargetName(targets[t]));
      hwy::SetSupportedTargetsForTest(targets[t]);
      const AlgorithmOutput other = ported().run(scene, variant);
      hwy::SetSupportedTargetsForTest(0);
      EXPECT_EQ(port_test::output_difference(one, other, false), "");
    }
  }
}

TEST(SimdLightAssign, ReportsTheReferenceIdAndVariants) {
  const AlgorithmInfo& info = ported().info();
  EXPECT_EQ(info.id, "lightassign");
  EXPECT_EQ(info.backend, "simd");
  EXPECT_EQ(info.capabilities.output, OutputKind::light_lists);
  for (const std::string& v : info.variants)
    EXPECT_NE(std::find(reference().info().variants.begin(), reference().info().variants.end(), v),
              reference().info().variants.end())
        << v;
}

}  // namespace
}  // namespace shadowcts
