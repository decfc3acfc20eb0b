// The CUDA ptsv kernels, run by the emulator, against the reference, structure by structure: every
// view sample's cluster key, every node (index, child mask, explicit bounds bit for bit, reject
// reach), every counter and every sample's answer, for each ported variant, on the default
// fixtures and the reference tests' big-shadow scenes (trivial accepts, where the order of the
// volumes matters to the counters); then the same outputs for 1 and 2 threads and under a random
// schedule. Each diff names the first difference.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/emulator/emulator.h"
#include "gpu/ptsv/ptsv_algorithm.h"
#include "gpu/ptsv/ptsv_kernels.h"
#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/ptsv_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "tests/ports/output_difference.h"
#include "tests/ports/ptsv_structure_difference.h"
#include "tests/reference/ptsv/big_shadow_case.h"
#include "tests/reference/ptsv/ptsv_test_support.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

namespace ref = ::shadowcts::ptsv;
const char* const variants[] = {"twopass", "explicit+planes", "implicit"};

// "" when the kernels' keys and hierarchy equal the reference's, else the first difference.
std::string diff_structures(const Case& c, const ViewSamples& samples, const PreparedScene& scene,
                            const std::string& variant) {
  const port_test::PtsvReferenceStructures reference =
      port_test::ptsv_reference_structures(c, samples, variant);
  if (!reference.problem.empty()) return reference.problem;
  const gpu_ptsv::KernelResult r =
      gpu_ptsv::run_ptsv_kernels_emulated(gpu_ptsv::kernel_input(scene, variant));
  if (r.first_bad_sample != gpu_ptsv::no_sample)
    return "kernels refuse view sample " + std::to_string(r.first_bad_sample);
  if (std::string d = port_test::ptsv_key_difference(r.key, reference.key); !d.empty()) return d;
  const ref::ClusterHierarchy& h = *reference.hierarchy;
  if (int(r.levels.size()) != h.leaf_level() + 1) return "number of levels";
  for (int l = 0; l <= h.leaf_level(); ++l) {
    const gpu_ptsv::Level& p = r.levels[std::size_t(l)];
    const std::string d =
        port_test::ptsv_level_difference(l, p.index.size(), h.level(l), [&](std::size_t n) {
          port_test::PtsvNode node{.index = p.index[n], .child_mask = p.child_mask[n]};
          for (std::size_t k = 0; k < 3; ++k) {
            node.lo[k] = p.lo[3 * n + k];
            node.hi[k] = p.hi[3 * n + k];
          }
          node.reach = p.reach[n];
          return node;
        });
    if (!d.empty()) return d;
  }
  return "";
}

void expect_like_reference(const Case& c, const ViewSamples& samples) {
  const auto reference = make_ptsv();
  const auto port = make_cuda_emu_ptsv();
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string variant : variants) {
    const auto why = reference->unsupported_reason(c, samples, variant);
    EXPECT_EQ(port->unsupported_reason(c, samples, variant), why) << variant;
    if (why) continue;
    EXPECT_EQ(diff_structures(c, samples, scene, variant), "") << c.name << " " << variant;
    EXPECT_EQ(port_test::output_difference(reference->run(scene, variant),
                                           port->run(scene, variant), true),
              "")
        << c.name << " " << variant << " (cuda-emu != reference)";
  }
}

class CudaEmuPtsvOnFixture : public ::testing::TestWithParam<std::string> {};

TEST_P(CudaEmuPtsvOnFixture, KeysNodesCountersAndMaskAreTheReferences) {
  const ptsv_test::FixtureWithSamples f = ptsv_test::load_fixture(GetParam());
  if (!f.c.light) GTEST_SKIP() << "no shadow light";
  expect_like_reference(f.c, f.samples);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CudaEmuPtsvOnFixture, ::testing::ValuesIn(default_fixtures()),
                         test_support::param_test_name);

TEST(CudaEmuPtsv, BigShadowWithTrivialAcceptsIsTheReferences) {
  for (const bool directional : {false, true}) {
    const Case c = ptsv_test::big_shadow_case(directional);
    const ViewSamples samples = generate_view_samples(c);
    const AlgorithmOutput out = make_cuda_emu_ptsv()->run(c, samples, "twopass");
    EXPECT_GT(ptsv_test::counter(out, "trivial_accepts"), 0u);
    expect_like_reference(c, samples);
  }
}

// Nothing depends on how the emulator schedules threads and blocks.
TEST(CudaEmuPtsv, SameOutputsForOneAndTwoThreadsAndARandomSchedule) {
  Case c = ptsv_test::big_shadow_case(false);
  const ViewSamples samples = generate_view_samples(c);
  const auto port = make_cuda_emu_ptsv();
  for (const std::string variant : variants) {
    c.parameters.threads = 1;
    const AlgorithmOutput one = port->run(c, samples, variant);
    c.parameters.threads = 2;
    const AlgorithmOutput two = port->run(c, samples, variant);
    EXPECT_EQ(port_test::output_difference(one, two, false), "") << variant;
    emu::Options options;
    options.schedule = emu::Schedule::random;
    options.seed = 7;
    const emu::ScopedOptions scoped(options);
    EXPECT_EQ(port_test::output_difference(one, port->run(c, samples, variant), false), "")
        << variant << " random";
  }
}

// The emulated kernels declare a size limit (samples x triangles) with its measured cost: a case
// above it is NotSupported with that reason, for every variant; the default fixtures stay far
// below it (their conformance cases run).
TEST(CudaEmuPtsv, CasesAboveTheSizeLimitAreNotSupportedWithTheReason) {
  const auto port = make_cuda_emu_ptsv();
  const std::uint64_t limit = port->info().capabilities.max_sample_triangle_pairs;
  ASSERT_GT(limit, 0u);
  Case c = make_fixture("gate_house.2k");
  ViewSamples samples = generate_view_samples(c);
  for (const std::string variant : variants)
    EXPECT_FALSE(port->unsupported_reason(c, samples, variant)) << variant;
  // Only the counts matter: 500k triangles and enough copies of a regular sample to pass it.
  const std::uint64_t triangles = 500'000;
  const std::uint64_t regular = limit / triangles + 1;
  ASSERT_LT(regular, 5'000'000u);
  c.triangles.resize(triangles, c.triangles.front());
  const auto first_regular =
      std::find_if(samples.samples.begin(), samples.samples.end(),
                   [](const ViewSample& s) { return s.sample_class == SampleClass::regular; });
  ASSERT_NE(first_regular, samples.samples.end());
  samples.samples.assign(regular, *first_regular);
  for (const std::string variant : variants) {
    const std::optional<std::string> reason = port->unsupported_reason(c, samples, variant);
    ASSERT_TRUE(reason) << variant;
    EXPECT_NE(reason->find("sample x triangle pairs (limit " + std::to_string(limit) + ")"),
              std::string::npos)
        << *reason;
    EXPECT_NE(reason->find("emulated kernels: ~"), std::string::npos) << *reason;
  }
}

}  // namespace
}  // namespace shadowcts
