// The psv query kernel run by the emulator (`cuda-emu`) diffed against the reference on its
// intermediate results: the uploaded TOP tree equals the reference's node for node, and for every
// variant (and stacks small enough to overflow) the mask, the node visits of every sample and
// every counter equal the reference's; the first difference is reported (which node, which
// sample, which counter). The same holds under random schedules with race checking and for any
// thread count.
#include <cstdint>
#include <cstring>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/emulator/emulator.h"
#include "gpu/psv/psv_kernels.h"
#include "gpu/psv/psv_shadows.h"
#include "reference/psv/psv_shadows.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/thread_limit.h"
#include "shadowcts/view_samples.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

struct FixtureCase {
  std::string generator;
  std::uint64_t triangles;
  std::uint64_t seed;
};

// Test names and failure messages show the fixture, not its bytes.
void PrintTo(const FixtureCase& f, std::ostream* out) {
  *out << f.generator << "." << f.triangles << " seed " << f.seed;
}

struct Scene {
  Case c;
  ViewSamples samples;
};

Scene load(Case c) {
  Scene s{std::move(c), {}};
  if (s.c.light && s.c.light->kind == ShadowLightKind::sun_disk)
    s.c.light->kind = ShadowLightKind::directional;  // as the runner hands it to hard shadows
  s.samples = generate_view_samples(s.c);
  return s;
}

Scene load(const FixtureCase& f) {
  return load(make_fixture(f.generator, f.triangles, f.seed));
}

std::uint64_t counter(const Counters& counters, const std::string& name) {
  for (const auto& [counter_name, value] : counters)
    if (counter_name == name) return value;
  ADD_FAILURE() << "no counter " << name;
  return 0;
}

std::string node_text(const PsvDeviceNode& n) {
  std::ostringstream out;
  out << "plane (" << n.plane[0] << ", " << n.plane[1] << ", " << n.plane[2] << ", " << n.plane[3]
      << ") positive " << n.positive << " intersection " << n.intersection << " wedge " << n.wedge
      << " volume word " << n.volume_word;
  return out.str();
}

// The first sample whose mask or node visits differ, the first counter that differs.
void expect_same_answers(const psv::PsvResult& reference, const psv::PsvResult& port,
                         const std::string& what) {
  ASSERT_EQ(port.shadowed.size(), reference.shadowed.size()) << what;
  ASSERT_EQ(port.nodes_visited.size(), reference.nodes_visited.size()) << what;
  for (std::size_t i = 0; i < reference.shadowed.size(); ++i) {
    ASSERT_EQ(int(port.shadowed[i]), int(reference.shadowed[i]))
        << what << ": the mask differs first at view sample " << i;
    ASSERT_EQ(port.nodes_visited[i], reference.nodes_visited[i])
        << what << ": nodes visited differ first at view sample " << i;
  }
  ASSERT_EQ(port.counters.size(), reference.counters.size()) << what;
  for (std::size_t k = 0; k < reference.counters.size(); ++k) {
    EXPECT_EQ(port.counters[k].first, reference.counters[k].first) << what;
    EXPECT_EQ(port.counters[k].second, reference.counters[k].second)
        << what << ": counter " << reference.counters[k].first;
  }
}

psv::PsvOptions options_of(const Case& c, const std::string& variant) {
  psv::PsvOptions options = psv::psv_variant_options(variant);
  options.seed = c.parameters.seed;
  return options;
}

class PsvCudaEmu : public ::testing::TestWithParam<FixtureCase> {};

TEST_P(PsvCudaEmu, UploadedTreeEqualsTheReferenceNodeForNode) {
  const Scene s = load(GetParam());
  const psv::PsvBuild build = psv::build_psv(s.c, s.samples, s.c.parameters.seed);
  ASSERT_GT(build.tree.nodes.size(), 100u);
  std::vector<std::size_t> regular;
  const PsvQueryInput input =
      gpu_psv::psv_query_input(s.c, s.samples, build, options_of(s.c, "hybrid"), regular);
  EXPECT_EQ(input.root, build.tree.root);
  ASSERT_EQ(input.nodes.size(), build.tree.nodes.size());
  for (std::size_t i = 0; i < input.nodes.size(); ++i) {
    PsvDeviceNode expected;
    std::memcpy(&expected, &build.tree.nodes[i], sizeof expected);
    ASSERT_EQ(std::memcmp(&input.nodes[i], &expected, sizeof expected), 0)
        << "node " << i << " differs: uploaded " << node_text(input.nodes[i]) << ", reference "
        << node_text(expected);
  }
  ASSERT_EQ(input.sources.size(), build.tree.sources.size());
  for (std::size_t v = 0; v < input.sources.size(); ++v) {
    const psv::VolumeSource& expected = build.tree.sources[v];
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_EQ(input.sources[v].edge[k][0], expected.edge[k][0]) << "volume " << v;
      ASSERT_EQ(input.sources[v].edge[k][1], expected.edge[k][1]) << "volume " << v;
    }
    for (std::size_t k = 0; k < 4; ++k)
      ASSERT_EQ(input.sources[v].orientation[k], expected.orientation[k]) << "volume " << v;
  }
  ASSERT_EQ(input.sample_positions.size(), regular.size());
  for (std::size_t i = 0; i < regular.size(); ++i) {
    ASSERT_EQ(s.samples.samples[regular[i]].sample_class, SampleClass::regular);
    ASSERT_EQ(input.sample_receivers[i], s.samples.samples[regular[i]].receiver);
  }
}

// The tree whose descents ran on the (emulated) device and whose batches the host committed: the
// reference's node for node, with the same statistics and the same exact plane tests.
TEST_P(PsvCudaEmu, TreeBuiltWithDeviceDescentsEqualsTheReferenceNodeForNode) {
  const Scene s = load(GetParam());
  const psv::PsvBuild reference = psv::build_psv(s.c, s.samples, s.c.parameters.seed);
  psv::BatchWork work;
  std::uint64_t device_exact_tests = 0;
  const psv::PsvBuild device =
      gpu_psv::build_psv_on_device(s.c, s.samples, s.c.parameters.seed,
                                   make_psv_descent_session_emulated, work, device_exact_tests);
  EXPECT_EQ(device.tree.root, reference.tree.root);
  ASSERT_EQ(device.tree.nodes.size(), reference.tree.nodes.size());
  for (std::size_t i = 0; i < reference.tree.nodes.size(); ++i)
    ASSERT_EQ(std::memcmp(&device.tree.nodes[i], &reference.tree.nodes[i], sizeof(psv::TopNode)), 0)
        << "node " << i << " differs";
  ASSERT_EQ(device.tree.sources.size(), reference.tree.sources.size());
  for (std::size_t v = 0; v < reference.tree.sources.size(); ++v)
    ASSERT_TRUE(device.tree.sources[v].edge == reference.tree.sources[v].edge &&
                device.tree.sources[v].orientation == reference.tree.sources[v].orientation)
        << "volume " << v;
  EXPECT_EQ(device.statistics.volumes, reference.statistics.volumes);
  EXPECT_EQ(device.statistics.dropped_in_shadow, reference.statistics.dropped_in_shadow);
  EXPECT_EQ(device.statistics.height, reference.statistics.height);
  EXPECT_EQ(device_exact_tests + device.planes->exact_fallbacks(),
            reference.planes->exact_fallbacks());
  EXPECT_GT(work.batches, 5u);
}

// Batches whose triangles meet in a child an earlier one filled: the host's resumed descents.
TEST(PsvCudaEmuBuild, ResumedDescentsOnTheHostKeepTheReferenceTree) {
  const Scene s = load({"gate_house", 20000, 1});
  const psv::PsvBuild reference = psv::build_psv(s.c, s.samples, s.c.parameters.seed);
  psv::BatchWork work;
  std::uint64_t device_exact_tests = 0;
  const psv::PsvBuild device =
      gpu_psv::build_psv_on_device(s.c, s.samples, s.c.parameters.seed,
                                   make_psv_descent_session_emulated, work, device_exact_tests);
  EXPECT_GT(work.resumed_descents, 100u);
  ASSERT_EQ(device.tree.nodes.size(), reference.tree.nodes.size());
  EXPECT_EQ(std::memcmp(device.tree.nodes.data(), reference.tree.nodes.data(),
                        reference.tree.nodes.size() * sizeof(psv::TopNode)),
            0);
}

void expect_every_variant_as_the_reference(const Scene& s, const std::string& name) {
  for (const std::string& variant : psv::psv_variants()) {
    const psv::PsvOptions options = options_of(s.c, variant);
    const psv::PsvResult reference = psv::psv_hard_shadows(s.c, s.samples, options);
    const psv::PsvResult port = gpu_psv::psv_hard_shadows(
        s.c, s.samples, options, run_psv_query_kernel_emulated, make_psv_descent_session_emulated);
    expect_same_answers(reference, port, name + " " + variant);
    EXPECT_GT(counter(port.counters, "queries"), 0u) << variant;
  }
}

TEST_P(PsvCudaEmu, EveryVariantAnswersAsTheReference) {
  expect_every_variant_as_the_reference(load(GetParam()), GetParam().generator);
}

// Stacks small enough to overflow (stack: answered by the stackless query) and to switch (hybrid):
// paths the default capacities rarely take on these cases.
TEST_P(PsvCudaEmu, OverflowingStacksAnswerAsTheReference) {
  const Scene s = load(GetParam());
  for (const psv::QueryKind kind : {psv::QueryKind::stack, psv::QueryKind::hybrid}) {
    psv::PsvOptions options;
    options.query = kind;
    options.stack_capacity = 1;
    options.seed = s.c.parameters.seed;
    const psv::PsvResult reference = psv::psv_hard_shadows(s.c, s.samples, options);
    const psv::PsvResult port = gpu_psv::psv_hard_shadows(
        s.c, s.samples, options, run_psv_query_kernel_emulated, make_psv_descent_session_emulated);
    const std::string what = GetParam().generator + " query " + std::to_string(int(kind));
    expect_same_answers(reference, port, what);
    // The test must reach the path it is about.
    const char* name = kind == psv::QueryKind::hybrid ? "hybrid_switches" : "stack_overflows";
    EXPECT_GT(counter(port.counters, name), 0u) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, PsvCudaEmu,
    ::testing::Values(FixtureCase{"ground_blockers", 2000, 1},
                      FixtureCase{"closed_shapes", 2000, 3}, FixtureCase{"gate_house", 3000, 1},
                      FixtureCase{"foliage", 2000, 2}, FixtureCase{"shared_edges", 2000, 1}),
    [](const ::testing::TestParamInfo<FixtureCase>& param_info) {
      return test_support::test_name(param_info.param.generator + "_" +
                                     std::to_string(param_info.param.triangles) + "_" +
                                     std::to_string(param_info.param.seed));
    });

// The numerical traps, where the float filter fails most often: the shared expansion-based
// predicates of the kernel must give the signs CGAL gives the reference, or a sample takes another
// path through the tree.
class PsvCudaEmuStiff : public ::testing::TestWithParam<std::string> {};

TEST_P(PsvCudaEmuStiff, EveryVariantAnswersAsTheReference) {
  expect_every_variant_as_the_reference(load(make_fixture(GetParam())), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Stiff, PsvCudaEmuStiff,
                         ::testing::Values("stiff.offset_1e7", "stiff.scale_1e-6",
                                           "stiff.light_1ulp_off_caster_edge",
                                           "stiff.directional_parallel_to_wall",
                                           "stiff.t_junctions"),
                         test_support::param_test_name);

// Nothing in the kernel depends on the order threads run or on how many OS threads run blocks:
// random interleavings with shared-memory race checks and 1 or 2 threads give the same result.
TEST(PsvCudaEmuSchedule, SameResultForAnySchedule) {
  Scene s = load({"shared_edges", 1000, 5});
  const psv::PsvOptions options = options_of(s.c, "hybrid4");
  const psv::PsvResult reference = psv::psv_hard_shadows(s.c, s.samples, options);
  for (const std::uint64_t seed : {1u, 2u}) {
    emu::Options emu_options;
    emu_options.schedule = emu::Schedule::random;
    emu_options.seed = seed;
    emu_options.check_races = true;
    const emu::ScopedOptions scoped(emu_options);
    psv::PsvResult port;
    run_with_thread_limit(1, [&] {
      port = gpu_psv::psv_hard_shadows(s.c, s.samples, options, run_psv_query_kernel_emulated,
                                       make_psv_descent_session_emulated);
    });
    expect_same_answers(reference, port, "random schedule " + std::to_string(seed));
  }
  for (const std::uint32_t threads : {1u, 2u}) {
    psv::PsvResult port;
    run_with_thread_limit(threads, [&] {
      port = gpu_psv::psv_hard_shadows(s.c, s.samples, options, run_psv_query_kernel_emulated,
                                       make_psv_descent_session_emulated);
    });
    expect_same_answers(reference, port, std::to_string(threads) + " threads");
  }
}

}  // namespace
}  // namespace shadowcts
