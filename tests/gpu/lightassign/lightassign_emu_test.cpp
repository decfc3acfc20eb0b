// The lightassign kernels under the emulator (the `cuda-emu` backend) against the reference:
// every sample's cluster key, the unique clusters (keys, tiles, members), the light BVH's Morton
// order, every list's box (bit for bit) and lights (as a set, and in the reference's order),
// list_of_sample and the counters, on the default fixtures with ranged lights and on the
// reference's stiff situations. The first difference is reported by sample, cluster or list.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gpu/emulator/emulator.h"
#include "gpu/lightassign/lightassign_algorithm.h"
#include "gpu/lightassign/lightassign_kernels.h"
#include "oracles/light_assignment/light_volume_predicates.h"
#include "reference/lightassign/cluster_key.h"
#include "reference/lightassign/light_bvh.h"
#include "reference/lightassign/lightassign_algorithm.h"
#include "reference/lightassign/unique_clusters.h"
#include "reference/lightassign/view_frustum.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/geometry/sphere_box.h"
#include "shadowcts/prepared_scene.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/view_samples.h"
#include "tests/ports/output_difference.h"
#include "tests/reference/lightassign/stiff_scenes.h"

namespace shadowcts {
namespace {

using lightassign_test::small_city;

const Algorithm& reference() {
  static const std::unique_ptr<Algorithm> a = make_lightassign();
  return *a;
}

const Algorithm& emulated() {
  static const std::unique_ptr<Algorithm> a = make_lightassign_cuda_emu();
  return *a;
}

bool same_float(float a, float b) {
  return std::memcmp(&a, &b, sizeof(float)) == 0;
}

// The reference's intermediate results for one variant: per regular sample its key, and the
// unique clusters (members as regular-sample indices).
struct ReferenceClusters {
  std::vector<std::uint32_t> sample_key;
  UniqueClusters clusters;
};

ReferenceClusters reference_clusters(const PreparedScene& scene, const std::string& variant) {
  const Case& c = scene.source;
  const ViewSamples& samples = scene.view_samples;
  const RegularSamples& regular = scene.samples;
  const ViewFrustum frustum(c.camera);
  const std::size_t n = samples.samples.size();
  ReferenceClusters out;
  std::vector<std::uint32_t> tile(n, UniqueClusters::no_cluster), key(n, 0);
  const std::uint32_t tiles_x = (samples.width + lightassign_tile_size - 1) / lightassign_tile_size;
  const std::uint32_t tiles_y =
      (samples.height + lightassign_tile_size - 1) / lightassign_tile_size;
  const auto settings = clustered_settings(variant);
  double deepest = 0.0;
  for (std::size_t i = 0; i < regular.size(); ++i)
    deepest = std::max(deepest, frustum.depth(glm::dvec3(regular.position(i))));
  std::optional<ClusterGrid> grid;
  if (settings) grid.emplace(c.camera, settings->tile_size, settings->normal_divisions, deepest);
  for (std::size_t i = 0; i < regular.size(); ++i) {
    const std::uint32_t s = regular.index[i];
    ClusterCoordinates k;
    k.i = samples.samples[s].pixel_x / lightassign_tile_size;
    k.j = samples.samples[s].pixel_y / lightassign_tile_size;
    tile[s] = k.j * tiles_x + k.i;
    if (grid) {
      k.k = grid->slice_of(frustum.depth(glm::dvec3(regular.position(i))));
      if (settings->normal_divisions > 0)
        k.normal = quantize_normal(regular.normal(i), settings->normal_divisions);
      key[s] = grid->pack(k);
    }
    out.sample_key.push_back(key[s]);
  }
  out.clusters = find_unique_clusters(tile, key, tiles_x * tiles_y);
  // Members as regular-sample indices, as the kernels return them (regular samples ascend).
  for (std::uint32_t& m : out.clusters.members)
    m = std::uint32_t(std::lower_bound(regular.index.begin(), regular.index.end(), m) -
                      regular.index.begin());
  return out;
}

// Empty when the kernels' intermediate results are the reference's, else the first difference.
std::string first_intermediate_difference(const PreparedScene& scene, const std::string& variant) {
  const ReferenceClusters ref = reference_clusters(scene, variant);
  LightAssignKernelResult got;
  run_with_thread_limit(
      2, [&] { got = run_lightassign_kernels_emulated(lightassign_kernel_input(scene, variant)); });
  std::ostringstream why;
  for (std::size_t i = 0; i < ref.sample_key.size(); ++i)
    if (i >= got.sample_key.size() || ref.sample_key[i] != got.sample_key[i]) {
      why << "sample " << scene.samples.index[i] << ": key " << ref.sample_key[i] << " vs "
          << (i < got.sample_key.size() ? got.sample_key[i] : 0u);
      return why.str();
    }
  const UniqueClusters& u = ref.clusters;
  if (u.keys.size() != got.cluster_keys.size()) {
    why << "unique clusters: " << u.keys.size() << " vs " << got.cluster_keys.size();
    return why.str();
  }
  for (std::size_t k = 0; k < u.keys.size(); ++k)
    if (u.keys[k] != got.cluster_keys[k] || u.tiles[k] != got.cluster_tiles[k] ||
        u.member_offsets[k] != got.member_offsets[k]) {
      why << "cluster " << k << ": key " << u.keys[k] << " tile " << u.tiles[k] << " first member "
          << u.member_offsets[k] << " vs key " << got.cluster_keys[k] << " tile "
          << got.cluster_tiles[k] << " first member " << got.member_offsets[k];
      return why.str();
    }
  if (u.members != got.members) return "cluster members differ";
  for (std::size_t i = 0; i < scene.samples.size(); ++i)
    if (u.cluster_of_sample[scene.samples.index[i]] != got.list_of_regular[i]) {
      why << "sample " << scene.samples.index[i] << ": cluster "
          << u.cluster_of_sample[scene.samples.index[i]] << " vs " << got.list_of_regular[i];
      return why.str();
    }
  if (variant != "tiled") {
    const LightBvh bvh(scene.source.ranged_lights);
    if (bvh.light_order() != got.light_order) {
      for (std::size_t leaf = 0; leaf < bvh.light_order().size(); ++leaf)
        if (leaf >= got.light_order.size() || bvh.light_order()[leaf] != got.light_order[leaf]) {
          why << "light BVH leaf " << leaf << ": light " << bvh.light_order()[leaf];
          return why.str();
        }
      return "light BVH: more leaves than the reference's";
    }
  }
  return {};
}

// Every emulated variant on one case: the reference's unsupported reasons, intermediates, outputs.
void expect_identical(const Case& c, const ViewSamples& samples, const std::string& what) {
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string& variant : emulated().info().variants) {
    SCOPED_TRACE(what + " " + variant);
    const auto why = reference().unsupported_reason(c, samples, variant);
    ASSERT_EQ(emulated().unsupported_reason(c, samples, variant), why);
    if (why) continue;
    EXPECT_EQ(first_intermediate_difference(scene, variant), "");
    const AlgorithmOutput ref = reference().run(scene, variant);
    const AlgorithmOutput emu = emulated().run(scene, variant);
    EXPECT_EQ(port_test::output_difference(ref, emu, true), "");
    EXPECT_GT(ref.light_lists.lights.size(), 0u) << "nothing listed: a weak case";
  }
}

TEST(LightAssignEmu, IdenticalToTheReferenceOnTheDefaultFixturesWithRangedLights) {
  int cases = 0;
  bool many_lights = false, depth_gaps = false;
  for (const std::string& name : default_fixtures()) {
    Case c = make_fixture(name);
    if (c.ranged_lights.empty()) continue;
    ++cases;
    many_lights = many_lights || name == "many_lights.10k";
    depth_gaps = depth_gaps || name == "depth_gaps.10k";
    expect_identical(c, generate_view_samples(c), name);
  }
  EXPECT_TRUE(many_lights && depth_gaps) << "the default fixtures changed";
  EXPECT_GE(cases, 2);
}

// Other sizes: partial tiles (77 = 2 x 32 + 13), more lights (a 3-level light BVH).
TEST(LightAssignEmu, IdenticalToTheReferenceOnTheLightFixtures) {
  for (const auto& [name, side] : std::vector<std::pair<std::string, std::uint32_t>>{
           {"many_lights.20k", 200}, {"depth_gaps.20k", 160}, {"many_lights.2k", 77}}) {
    Case c = make_fixture(name);
    c.camera.width = c.camera.height = side;
    expect_identical(c, generate_view_samples(c), name);
  }
}

// A full-HD view with many lights, when asked for (SHADOWCTS_LIGHTASSIGN_LARGE=1: 32k lights, about
// 40 s under the emulator).
TEST(LightAssignEmu, IdenticalAtFullHdWhenAskedFor) {
  if (!std::getenv("SHADOWCTS_LIGHTASSIGN_LARGE"))
    GTEST_SKIP() << "SHADOWCTS_LIGHTASSIGN_LARGE unset";
  Case c = make_fixture("many_lights", 128000, 1);
  c.camera.width = 1920;
  c.camera.height = 1080;
  expect_identical(c, generate_view_samples(c), "many_lights 1920x1080");
}

TEST(LightAssignEmu, OutputsDoNotDependOnTheThreadCount) {
  Case c = make_fixture("depth_gaps.10k");
  c.camera.width = c.camera.height = 96;
  const ViewSamples samples = generate_view_samples(c);
  for (const std::string variant : {"tiled", "clustered+en"}) {
    c.parameters.threads = 1;
    const AlgorithmOutput one = emulated().run(c, samples, variant);
    c.parameters.threads = 2;
    const AlgorithmOutput two = emulated().run(c, samples, variant);
    const LightLists &a = one.light_lists, &b = two.light_lists;
    EXPECT_EQ(a.offsets, b.offsets) << variant;
    EXPECT_EQ(a.lights, b.lights) << variant;
    EXPECT_EQ(a.list_of_sample, b.list_of_sample) << variant;
    ASSERT_EQ(a.bounds.size(), b.bounds.size()) << variant;
    for (std::size_t k = 0; k < a.bounds.size(); ++k) {
      for (int i = 0; i < 3; ++i) {
        EXPECT_TRUE(same_float(a.bounds[k].min[i], b.bounds[k].min[i]) &&
                    same_float(a.bounds[k].max[i], b.bounds[k].max[i]))
            << variant << " list " << k;
      }
    }
    EXPECT_EQ(one.counters, two.counters) << variant;
  }
}

// The reference's stiff situations (tests/reference/lightassign/lightassign_stiff_test.cpp).
TEST(LightAssignEmu, IdenticalWithLightsLargerThanTheSceneAndAroundTheCamera) {
  const Case c = lightassign_test::city_with_lights_around_the_camera();
  expect_identical(c, generate_view_samples(c), "around the camera");
}

TEST(LightAssignEmu, IdenticalWithANearFarRatioOf1e7) {
  const Case c = lightassign_test::city_with_near_far_1e7();
  expect_identical(c, generate_view_samples(c), "near/far 1e-7");
}

// Lights whose spheres touch list boxes within rounding: the filter cannot decide them and the
// expansions do.
TEST(LightAssignEmu, IdenticalWithLightsTangentToTheBoxes) {
  Case c = small_city();
  const ViewSamples samples = generate_view_samples(c);
  std::mt19937_64 random(7);
  std::vector<RangedLight> lights;
  for (const std::string variant : {"clustered", "clustered+eb", "tiled"}) {
    const std::vector<RangedLight> tangent = lightassign_test::lights_tangent_to(
        reference().run(c, samples, variant).light_lists.bounds, random);
    lights.insert(lights.end(), tangent.begin(), tangent.end());
  }
  c.ranged_lights = lights;
  validate(c);
  int undecided = 0;
  for (const std::string variant : {"clustered", "clustered+eb", "tiled"})
    for (const Aabb& b : reference().run(c, samples, variant).light_lists.bounds)
      for (const RangedLight& l : lights)
        undecided += geometry::sphere_meets_box_filter(l.centre, l.range, b.min, b.max) == 0;
  EXPECT_GT(undecided, 0) << "no pair for the exact path";
  expect_identical(c, samples, "tangent lights");
}

// The kernels' cull (shadowcts/geometry/sphere_box.h) against the oracle's exact predicate, on
// near ties (ranges within 2 ulps of the rounded distance) and exact ties.
TEST(LightAssignEmu, SharedSphereBoxEqualsTheExactPredicate) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<float> coordinate(-4.0f, 4.0f);
  int undecided = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Aabb box;
    for (int i = 0; i < 3; ++i) {
      const float a = coordinate(random), b = coordinate(random);
      box.min[i] = std::min(a, b);
      box.max[i] = std::max(a, b);
    }
    glm::vec3 centre(coordinate(random), coordinate(random), coordinate(random));
    double d2 = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double gap =
          std::max({0.0, double(box.min[i]) - centre[i], centre[i] - double(box.max[i])});
      d2 += gap * gap;
    }
    float r = float(std::sqrt(d2));
    for (int step = int(random() % 5) - 2; step != 0; step += step > 0 ? -1 : 1)
      r = std::nextafter(r, step > 0 ? 8.0f : 0.0f);
    if (!(r > 0.0f)) continue;
    undecided += geometry::sphere_meets_box_filter(centre, r, box.min, box.max) == 0;
    ASSERT_EQ(geometry::sphere_meets_box(centre, r, box.min, box.max),
              exact_only::sphere_meets_box(centre, r, box))
        << "centre (" << centre.x << ", " << centre.y << ", " << centre.z << ") r " << r;
    const int axis = trial % 3;
    centre = 0.5f * (box.min + box.max);
    centre[axis] = box.max[axis] + 0.375f;
    EXPECT_TRUE(geometry::sphere_meets_box(centre, 0.375f, box.min, box.max));
    EXPECT_FALSE(
        geometry::sphere_meets_box(centre, std::nextafter(0.375f, 0.0f), box.min, box.max));
  }
  EXPECT_GT(undecided, 0);
}

TEST(LightAssignEmu, NoLightsGiveEmptyLists) {
  Case c = small_city();
  const ViewSamples samples = generate_view_samples(c);
  c.ranged_lights.clear();
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string& variant : emulated().info().variants) {
    const AlgorithmOutput ref = reference().run(scene, variant);
    const AlgorithmOutput emu = emulated().run(scene, variant);
    EXPECT_EQ(port_test::output_difference(ref, emu, true), "") << variant;
    EXPECT_TRUE(emu.light_lists.lights.empty()) << variant;
  }
}

// Under the seeded random schedule with shared-memory race tracking (the tiled block reduction
// and the warp collectives), on a small case: the same lists, no emulator error.
TEST(LightAssignEmu, RandomScheduleWithRaceChecksGivesTheSameLists) {
  Case c = make_fixture("many_lights.2k");
  c.camera.width = c.camera.height = 40;
  const ViewSamples samples = generate_view_samples(c);
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string variant : {"tiled", "clustered+en"}) {
    const AlgorithmOutput ref = reference().run(scene, variant);
    emu::Options options;
    options.schedule = emu::Schedule::random;
    options.seed = 12345;
    options.check_races = true;
    const emu::ScopedOptions scoped(options);
    AlgorithmOutput emu;
    ASSERT_NO_THROW(emu = emulated().run(scene, variant)) << variant;
    EXPECT_EQ(port_test::output_difference(ref, emu, true), "") << variant;
  }
}

}  // namespace
}  // namespace shadowcts
