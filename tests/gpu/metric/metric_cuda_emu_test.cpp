// The CUDA `metric` (its kernel run by the emulator) against the reference `metric`: the tree as
// uploaded equals the reference's node for node, and the kernel's per-sample answers and work
// counters equal the reference's walk of each sample (the first differing node or sample is
// named), on the default fixtures, the reference's stiff cases and random cases; the kernel
// decides nearly every sample itself (the host's hand-back path cannot hide a kernel bug), and
// the results do not depend on the thread count or the emulator's schedule. Built a second time
// with SHADOWCTS_METRIC_TEST_DEVICE for the `cuda` backend (ci/device.sh; skipped without a
// device).
#ifndef SHADOWCTS_METRIC_TEST_DEVICE
#define SHADOWCTS_METRIC_TEST_DEVICE 0
#endif

#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "gpu/emulator/emulator.h"
#include "gpu/metric/metric_algorithm.h"
#include "gpu/metric/metric_shadows.h"
#include "gpu/metric/traversal.h"
#include "hand_built_case.h"
#include "metric_test_cases.h"
#include "reference/metric/metric_shadows.h"
#include "reference/metric/traversal.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "tests/test_name.h"
#if SHADOWCTS_METRIC_TEST_DEVICE
#include "gpu/device.h"
#endif

namespace shadowcts::gpu_metric {
namespace {

namespace ref = shadowcts::metric;

const char* const variants[] = {"capsules", "spheres", "capsules16"};

#if SHADOWCTS_METRIC_TEST_DEVICE
constexpr KernelRunner kernel = run_metric_traversal_kernel;
std::unique_ptr<Algorithm> make_backend() {
  return make_metric_cuda();
}
#define SKIP_WITHOUT_DEVICE() \
  if (const auto reason = cuda_unavailable_reason()) GTEST_SKIP() << *reason
#else
constexpr KernelRunner kernel = run_metric_traversal_kernel_emulated;
std::unique_ptr<Algorithm> make_backend() {
  return make_metric_cuda_emu();
}
#define SKIP_WITHOUT_DEVICE() static_cast<void>(0)
#endif

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

// Empty when the uploaded nodes are the reference's tree with its pivots' geometry and
// thresholds, else the first differing node and field.
std::string first_node_difference(const ref::LightStructure& structure,
                                  const std::vector<MetricNode>& nodes) {
  const ref::MetricTree& tree = structure.tree;
  const double slack = structure.frame.slack;
  if (tree.nodes.size() != nodes.size())
    return "node count " + std::to_string(nodes.size()) + ", expected " +
           std::to_string(tree.nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const ref::MetricTreeNode& e = tree.nodes[i];
    const MetricNode& a = nodes[i];
    const auto at = [&](const char* field) { return "node " + std::to_string(i) + ": " + field; };
    if (a.pivot != e.pivot) return at("pivot");
    for (int c = 0; c < 3; ++c)
      if (a.child[c] != e.child[c]) return at("child");
    if (!same_bits(a.light_distance, e.light_distance)) return at("light_distance");
    if (!same_bits(a.overlap_low, e.overlap_min - slack)) return at("overlap_low");
    if (!same_bits(a.overlap_high, e.overlap_max + slack)) return at("overlap_high");
    if (!same_bits(a.far_side, e.partition_distance - slack)) return at("far_side");
    if (!same_bits(a.near_side, e.partition_distance + slack)) return at("near_side");
    const ref::LightSpaceElement& pivot = structure.elements[e.pivot];
    if (a.cluster != pivot.cluster) return at("cluster");
    if (!same_bits(a.pivot_light_distance, pivot.light_distance)) return at("pivot_light_distance");
    if (a.kind == PivotKind::covers_everything) {
      if (!pivot.covers_everything) return at("kind");
      continue;
    }
    const bool point = pivot.centre == ref::CentreKind::point;
    const PivotKind kind = structure.frame.directional
                               ? (point ? PivotKind::disk : PivotKind::capsule_2d)
                               : (point ? PivotKind::point_cone : PivotKind::arc_cone);
    if (pivot.covers_everything || a.kind != kind) return at("kind");
    if (a.a != pivot.a || a.b != pivot.b || !same_bits(a.radius, pivot.radius)) return at("centre");
    if (kind == PivotKind::arc_cone && a.arc_normal != pivot.arc.normal) return at("arc_normal");
  }
  return {};
}

// Empty when the uploaded clusters and triangles are the reference's, else the first difference.
std::string first_cluster_difference(const Case& c, const ref::ClusteredScene& clustered,
                                     const ref::LightFrame& frame, const MetricInput& input) {
  const ref::Clustering& clustering = clustered.clustering;
  if (input.clusters.size() != clustering.cluster_count()) return "cluster count";
  for (std::size_t k = 0; k < input.clusters.size(); ++k) {
    const MetricCluster& a = input.clusters[k];
    const ref::ClusterVolume& v = clustered.volumes[k];
    if (a.begin != clustering.cluster_begin[k] || a.end != clustering.cluster_begin[k + 1] ||
        a.slab_normal != v.slab_normal || !same_bits(a.slab_low, v.slab_min - frame.margin) ||
        !same_bits(a.slab_high, v.slab_max + frame.margin))
      return "cluster " + std::to_string(k);
  }
  if (input.triangles.size() != clustering.triangles.size()) return "triangle count";
  for (std::size_t k = 0; k < input.triangles.size(); ++k) {
    const MetricTriangle& a = input.triangles[k];
    const Triangle& t = c.triangles[clustering.triangles[k]];
    if (a.triangle != clustering.triangles[k] || a.v0 != t.v0 || a.v1 != t.v1 || a.v2 != t.v2)
      return "triangle slot " + std::to_string(k);
  }
  return {};
}

struct KernelDiff {
  std::string first_difference;  // empty: every sample the kernel decided is the reference's
  std::size_t samples = 0, handed_back = 0, exact_tests = 0, stack_overflows = 0;
};

// Runs the kernel alone (no host hand-back) and compares every sample it decided with the
// reference's walk of that sample: answer and the three work counters.
KernelDiff diff_kernel_against_reference(const Case& c, const ViewSamples& samples,
                                         const std::string& variant,
                                         double decision_window = 0x1p-40,
                                         std::uint32_t stack_limit = stack_capacity) {
  const GpuMetricOptions options = parse_gpu_metric_variant(variant);
  const PreparedScene scene = prepare_scene(c, samples);
  const ref::ClusteredScene clustered = ref::cluster_scene(c, options.metric);
  const ref::LightStructure structure = ref::build_light_structure(c, clustered, options.metric);
  MetricInput input = metric_kernel_input(scene, clustered, structure, decision_window);
  input.stack_limit = stack_limit;
  const MetricResult result = kernel(input);

  ref::TraversalScene traversal;
  traversal.c = &c;
  traversal.light = hard_shadow_light(c);
  traversal.clustering = &clustered.clustering;
  traversal.volumes = &clustered.volumes;
  traversal.elements = &structure.elements;
  traversal.tree = &structure.tree;
  traversal.frame = structure.frame;
  traversal.ray_length = 4.0 * structure.frame.scale;
  KernelDiff diff;
  diff.samples = scene.samples.size();
  std::vector<std::uint32_t> stack;
  for (std::size_t i = 0; i < scene.samples.size(); ++i) {
    const std::uint8_t state = result.state[i];
    if (handed_to_host(state)) {
      ++diff.handed_back;
      if (state == sample_exact_test) ++diff.exact_tests;
      if (state == sample_stack_overflow) ++diff.stack_overflows;
      continue;
    }
    ref::TraversalCounters expected;
    const ViewSample& sample = samples.samples[scene.samples.index[i]];
    const bool shadowed = ref::sample_is_shadowed(traversal, sample, expected, stack);
    const auto at = [&](const std::string& what) {
      return "sample " + std::to_string(i) + " (pixel " + std::to_string(scene.samples.index[i]) +
             "): " + what;
    };
    if (state != (shadowed ? sample_shadowed : sample_lit))
      return {at("answer " + std::to_string(state)), diff.samples, diff.handed_back};
    if (result.sample_nodes_visited[i] != expected.nodes_visited)
      return {at("nodes_visited " + std::to_string(result.sample_nodes_visited[i]) + ", expected " +
                 std::to_string(expected.nodes_visited)),
              diff.samples, diff.handed_back};
    if (result.sample_clusters_tested_without_hit[i] != expected.clusters_tested_without_hit)
      return {at("clusters_tested_without_hit"), diff.samples, diff.handed_back};
    if (result.sample_triangle_tests[i] != expected.triangle_tests)
      return {at("triangle_tests"), diff.samples, diff.handed_back};
  }
  return diff;
}

// The whole backend (kernel and hand-backs) against the reference's run: answers and counters.
void expect_same_as_reference(const Case& c, const ViewSamples& samples, const std::string& variant,
                              double decision_window = 0x1p-40,
                              std::uint32_t stack_limit = stack_capacity) {
  SCOPED_TRACE(variant);
  const ref::MetricRun expected = ref::run_metric(c, samples, ref::parse_metric_variant(variant));
  const PreparedScene scene = prepare_scene(c, samples);
  GpuMetricOptions options = parse_gpu_metric_variant(variant);
  options.decision_window = decision_window;
  options.stack_limit = stack_limit;
  const GpuMetricRun actual = run_metric(scene, options, kernel);
  ASSERT_EQ(actual.output.shadowed.size(), expected.output.shadowed.size());
  for (std::size_t i = 0; i < expected.output.shadowed.size(); ++i)
    ASSERT_EQ(actual.output.shadowed[i], expected.output.shadowed[i]) << "view sample " << i;
  // The reference's counters first, then the hand-back counts.
  ASSERT_GE(actual.output.counters.size(), expected.output.counters.size());
  const Counters prefix(
      actual.output.counters.begin(),
      actual.output.counters.begin() + std::ptrdiff_t(expected.output.counters.size()));
  EXPECT_EQ(prefix, expected.output.counters);
}

class CudaEmuMetricOnFixtures : public ::testing::TestWithParam<std::string> {};

TEST_P(CudaEmuMetricOnFixtures, UploadedTreeIsTheReferencesNodeForNode) {
  SKIP_WITHOUT_DEVICE();
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 16);
  const PreparedScene scene = prepare_scene(f.c, f.samples);
  for (const char* variant : variants) {
    SCOPED_TRACE(variant);
    const ref::MetricOptions options = ref::parse_metric_variant(variant);
    const ref::ClusteredScene clustered = ref::cluster_scene(f.c, options);
    const ref::LightStructure structure = ref::build_light_structure(f.c, clustered, options);
    const MetricInput input = metric_kernel_input(scene, clustered, structure, 0x1p-40);
    EXPECT_GT(input.nodes.size(), 0u);
    EXPECT_EQ(first_node_difference(structure, input.nodes), "");
    EXPECT_EQ(first_cluster_difference(f.c, clustered, structure.frame, input), "");
  }
}

// The kernel's own answers and per-sample counters; at most 1 % of the samples handed back.
TEST_P(CudaEmuMetricOnFixtures, KernelWalksEachSampleAsTheReference) {
  SKIP_WITHOUT_DEVICE();
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 64);
  for (const char* variant : variants) {
    SCOPED_TRACE(variant);
    const KernelDiff diff = diff_kernel_against_reference(f.c, f.samples, variant);
    EXPECT_EQ(diff.first_difference, "");
    EXPECT_GT(diff.samples, 0u);
    EXPECT_LE(diff.handed_back * 100, diff.samples)
        << diff.handed_back << " handed back, " << diff.exact_tests << " for the exact test";
  }
}

TEST_P(CudaEmuMetricOnFixtures, SameAnswersAndCountersAsTheReference) {
  SKIP_WITHOUT_DEVICE();
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 64);
  for (const char* variant : variants) expect_same_as_reference(f.c, f.samples, variant);
}

// A band of 2^-5 (radians, or S for lengths) around every threshold hands many samples to the
// host: the kernel's decisions outside it and the host's walks must still add up to the
// reference's answers and counters.
TEST_P(CudaEmuMetricOnFixtures, SameResultsWhenManySamplesAreHandedBack) {
  SKIP_WITHOUT_DEVICE();
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 32);
  const KernelDiff diff = diff_kernel_against_reference(f.c, f.samples, "capsules", 0x1p-5);
  EXPECT_EQ(diff.first_difference, "");
  expect_same_as_reference(f.c, f.samples, "capsules", 0x1p-5);
}

// A stack of 4 entries overflows on the walks that keep more siblings pending: those samples go to
// the host (never silently dropped), and the results are still the reference's.
TEST_P(CudaEmuMetricOnFixtures, SameResultsWhenStacksOverflow) {
  SKIP_WITHOUT_DEVICE();
  const ref::testing::FixtureCase f = ref::testing::load_fixture(GetParam(), 32);
  const KernelDiff diff = diff_kernel_against_reference(f.c, f.samples, "capsules", 0x1p-40, 4);
  EXPECT_EQ(diff.first_difference, "");
  EXPECT_GT(diff.stack_overflows, 0u);
  expect_same_as_reference(f.c, f.samples, "capsules", 0x1p-40, 4);
}

INSTANTIATE_TEST_SUITE_P(DefaultFixtures, CudaEmuMetricOnFixtures,
                         ::testing::ValuesIn(ref::testing::hard_shadow_fixtures()),
                         test_support::param_test_name);

// The stiff cases metric's own traps live in, at their own resolution: identical answers.
class CudaEmuMetricOnStiffCases : public ::testing::TestWithParam<std::string> {};

TEST_P(CudaEmuMetricOnStiffCases, SameAnswersAndCountersAsTheReference) {
  SKIP_WITHOUT_DEVICE();
  ref::testing::FixtureCase f;
  f.c = make_fixture(GetParam());
  if (f.c.light && f.c.light->kind == ShadowLightKind::sun_disk) {
    f.c.light->kind = ShadowLightKind::directional;
    f.c.light->angular_radius = 0.0f;
  }
  f.samples = generate_view_samples(f.c);
  for (const char* variant : variants) {
    expect_same_as_reference(f.c, f.samples, variant);
    EXPECT_EQ(diff_kernel_against_reference(f.c, f.samples, variant).first_difference, "");
  }
}

INSTANTIATE_TEST_SUITE_P(
    Stiff, CudaEmuMetricOnStiffCases,
    ::testing::Values("stiff.light_1ulp_off_caster_face", "stiff.light_1e-6_from_caster",
                      "stiff.light_inside_cluster", "stiff.light_near_elongated_caster",
                      "stiff.capsule_zero_length", "stiff.tessellated_convex_sphere",
                      "stiff.walls_on_a_floor", "stiff.light_in_receiver_plane",
                      "stiff.sun_radius_45_degrees"),
    test_support::param_test_name);

// Random blockers with samples on shadow-boundary images, the light outside and inside the
// blocker field, point and directional.
class CudaEmuMetricOnRandomCases : public ::testing::TestWithParam<int> {};

TEST_P(CudaEmuMetricOnRandomCases, SameAnswersAndCountersAsTheReference) {
  SKIP_WITHOUT_DEVICE();
  const int k = GetParam();
  const ShadowLight light = k % 3 == 0 ? shadowcts::testing::point_light({1.5f, 10.0f, 0.75f})
                            : k % 3 == 1
                                ? shadowcts::testing::point_light({0.25f, 2.0f, 0.5f})
                                : shadowcts::testing::directional_light({0.25f, 1.0f, -0.375f});
  auto h = shadowcts::testing::make_random_case(500 + std::uint64_t(k), 8, 800, 0.75f, 1500, light);
  for (const char* variant : {"capsules", "spheres4", "capsules16"}) {
    expect_same_as_reference(h.c, h.samples, variant);
    EXPECT_EQ(diff_kernel_against_reference(h.c, h.samples, variant).first_difference, "");
  }
}

INSTANTIATE_TEST_SUITE_P(RandomCases, CudaEmuMetricOnRandomCases, ::testing::Range(0, 6));

TEST(CudaEmuMetric, LightInsideVolumesAndATJunction) {
  SKIP_WITHOUT_DEVICE();
  // Cones covering every direction.
  auto inside = shadowcts::testing::make_random_case(
      77, 4, 400, 1.5f, 600, shadowcts::testing::point_light({0.0f, 2.0f, 0.0f}));
  for (const char* variant : variants) {
    expect_same_as_reference(inside.c, inside.samples, variant);
    EXPECT_EQ(diff_kernel_against_reference(inside.c, inside.samples, variant).first_difference,
              "");
  }

  // The T-junction crack of fuzz_watertight-531e78eca2acc5e5: the float test misses both
  // triangles; the kernel hands the sample to the host for the exact segment test, which finds
  // the blocker.
  const auto [crack, sample] = shadowcts::testing::t_junction_crack();
  for (const char* variant : variants) {
    expect_same_as_reference(crack.c, crack.samples, variant);
    const KernelDiff diff = diff_kernel_against_reference(crack.c, crack.samples, variant);
    EXPECT_EQ(diff.first_difference, "");
    EXPECT_EQ(diff.exact_tests, 1u);
    EXPECT_EQ(diff.handed_back, 1u);
    EXPECT_EQ(make_backend()->run(crack.c, crack.samples, variant).shadowed[sample], 1);
  }
}

// Outputs and counters do not depend on the thread count or on the emulator's schedule.
TEST(CudaEmuMetric, DeterministicForAnyThreadCountAndSchedule) {
  SKIP_WITHOUT_DEVICE();
  const ref::testing::FixtureCase f = ref::testing::load_fixture("foliage.10k", 48);
  const auto algorithm = make_backend();
  AlgorithmOutput single;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    single = algorithm->run(f.c, f.samples, "capsules");
  }
  AlgorithmOutput two;
  {
    tbb::global_control both(tbb::global_control::max_allowed_parallelism, 2);
    two = algorithm->run(f.c, f.samples, "capsules");
  }
  EXPECT_EQ(single.shadowed, two.shadowed);
  EXPECT_EQ(single.counters, two.counters);
#if !SHADOWCTS_METRIC_TEST_DEVICE
  emu::Options options;
  options.schedule = emu::Schedule::random;
  options.seed = 12345;
  options.check_races = true;
  const emu::ScopedOptions scoped(options);
  const AlgorithmOutput shuffled = algorithm->run(f.c, f.samples, "capsules");
  EXPECT_EQ(shuffled.shadowed, single.shadowed);
  EXPECT_EQ(shuffled.counters, single.counters);
#endif
}

TEST(CudaEmuMetric, DescribesItselfAndRejectsTheMedianBuild) {
  SKIP_WITHOUT_DEVICE();
  const auto algorithm = make_backend();
  const AlgorithmInfo& info = algorithm->info();
  EXPECT_EQ(info.id, "metric");
  EXPECT_EQ(info.backend, SHADOWCTS_METRIC_TEST_DEVICE ? "cuda" : "cuda-emu");
  EXPECT_EQ(info.variants, (std::vector<std::string>{"capsules", "spheres", "capsules16"}));
  EXPECT_EQ(algorithm->timed_phases("capsules"),
            (std::vector<std::string>{"clustering", "build", "query"}));
  EXPECT_THROW(parse_gpu_metric_variant("median"), std::invalid_argument);
  const ref::testing::FixtureCase f = ref::testing::load_fixture("foliage.10k", 16);
  const AlgorithmOutput output = algorithm->run(f.c, f.samples, "capsules");
  bool emulated_threads = false;
  for (const auto& [name, value] : output.counters)
    if (name == "emulated_threads") emulated_threads = value > 0;
  EXPECT_EQ(emulated_threads, !SHADOWCTS_METRIC_TEST_DEVICE);
}

}  // namespace
}  // namespace shadowcts::gpu_metric
