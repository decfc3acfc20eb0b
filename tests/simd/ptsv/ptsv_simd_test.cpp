// simd ptsv against the reference, structure by structure: every view sample's cluster key, every
// node (index, child mask, explicit bounds bit for bit, reject reach), every counter and every
// sample's answer, for each ported variant, on the default fixtures, the stiff suite and the
// reference tests' big-shadow scenes; then the same outputs for 1 and 2 threads and for another
// Highway target. Each diff names the first difference.
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tbb/global_control.h>

#include "reference/ptsv/hierarchy.h"
#include "reference/ptsv/ptsv_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/prepared_scene.h"
#include "simd/ptsv/ptsv_algorithm.h"
#include "tests/ports/output_difference.h"
#include "tests/ports/ptsv_structure_difference.h"
#include "tests/reference/ptsv/big_shadow_case.h"
#include "tests/reference/ptsv/ptsv_test_support.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

namespace ref = ::shadowcts::ptsv;
const char* const variants[] = {"twopass", "explicit+planes", "implicit"};

// "" when the simd structures equal the reference's, else the first difference.
std::string diff_structures(const Case& c, const ViewSamples& samples, const PreparedScene& scene,
                            const std::string& variant) {
  const port_test::PtsvReferenceStructures reference =
      port_test::ptsv_reference_structures(c, samples, variant);
  if (!reference.problem.empty()) return reference.problem;
  const simd::ptsv::Structures s = simd::ptsv::build_structures(scene, variant);
  if (std::string d = port_test::ptsv_key_difference(s.key, reference.key); !d.empty()) return d;
  const ref::ClusterHierarchy& h = *reference.hierarchy;
  if (s.hierarchy.leaf_level() != h.leaf_level()) return "leaf level";
  for (int l = 0; l <= h.leaf_level(); ++l) {
    const simd::ptsv::Level& p = s.hierarchy.levels[std::size_t(l)];
    const std::string d =
        port_test::ptsv_level_difference(l, p.size(), h.level(l), [&](std::size_t n) {
          port_test::PtsvNode node{.index = p.index[n], .child_mask = p.child_mask[n]};
          for (std::size_t k = 0; k < 3; ++k) {
            node.lo[k] = p.lo[k][n];
            node.hi[k] = p.hi[k][n];
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
  const auto port = make_simd_ptsv();
  const PreparedScene scene = prepare_scene(c, samples);
  for (const std::string variant : variants) {
    const auto why = reference->unsupported_reason(c, samples, variant);
    EXPECT_EQ(port->unsupported_reason(c, samples, variant), why) << variant;
    if (why) continue;
    EXPECT_EQ(diff_structures(c, samples, scene, variant), "") << c.name << " " << variant;
    EXPECT_EQ(port_test::output_difference(reference->run(scene, variant),
                                           port->run(scene, variant), false),
              "")
        << c.name << " " << variant << " (simd != reference)";
  }
}

class SimdPtsvOnFixture : public ::testing::TestWithParam<std::string> {};

TEST_P(SimdPtsvOnFixture, KeysNodesCountersAndMaskAreTheReferences) {
  const ptsv_test::FixtureWithSamples f = ptsv_test::load_fixture(GetParam());
  if (!f.c.light) GTEST_SKIP() << "no shadow light";
  expect_like_reference(f.c, f.samples);
}

std::vector<std::string> fixtures_and_stiff_cases() {
  std::vector<std::string> names = default_fixtures();
  for (const std::string& s : stiff_fixtures()) names.push_back(s);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, SimdPtsvOnFixture,
                         ::testing::ValuesIn(fixtures_and_stiff_cases()),
                         test_support::param_test_name);

// The reference tests' scene whose caster covers whole clusters: trivial accepts clear bits, so
// the order of the volumes matters to the counters.
TEST(SimdPtsv, BigShadowWithTrivialAcceptsIsTheReferences) {
  for (const bool directional : {false, true}) {
    const Case c = ptsv_test::big_shadow_case(directional);
    const ViewSamples samples = generate_view_samples(c);
    const AlgorithmOutput out = make_simd_ptsv()->run(c, samples, "twopass");
    EXPECT_GT(ptsv_test::counter(out, "trivial_accepts"), 0u);
    expect_like_reference(c, samples);
  }
}

// The big shadow with 12,100 specks floating above its caster, half of them before the caster in
// the volume order and half after: the nodes around the shadow's centre have more visitors than
// one segment of the ordered pass holds, and the caster's trivial accepts fall in a middle
// segment, so the later segments must start from the mask the accepts left.
TEST(SimdPtsv, TrivialAcceptsAmongManyVisitorsOfANodeAreTheReferences) {
  Case c = ptsv_test::big_shadow_case(false);
  const Triangle caster = c.triangles.back();
  c.triangles.pop_back();
  c.meshes.push_back(Mesh{"specks", false, true});
  const std::uint32_t specks = std::uint32_t(c.meshes.size() - 1);
  constexpr int side = 110;
  for (int k = 0; k < side * side; ++k) {
    if (k == side * side / 2) c.triangles.push_back(caster);
    const float x = 0.25f + 0.002f * float(k % side), z = -0.2f + 0.002f * float(k / side);
    c.triangles.push_back(
        Triangle{{x, 3.5f, z}, {x + 0.001f, 3.5f, z}, {x, 3.5f, z + 0.001f}, specks});
  }
  const ViewSamples samples = generate_view_samples(c);
  const AlgorithmOutput out = make_simd_ptsv()->run(c, samples, "twopass");
  EXPECT_GT(ptsv_test::counter(out, "trivial_accepts"), 0u);
  expect_like_reference(c, samples);
}

TEST(SimdPtsv, SameOutputsForOneAndTwoThreadsAndAnotherTarget) {
  const ptsv_test::FixtureWithSamples f = ptsv_test::load_fixture("gate_house.20k");
  const auto port = make_simd_ptsv();
  const PreparedScene scene = prepare_scene(f.c, f.samples);
  for (const std::string variant : variants) {
    AlgorithmOutput one, two;
    {
      tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
      one = port->run(scene, variant);
    }
    {
      tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
      two = port->run(scene, variant);
    }
    EXPECT_EQ(port_test::output_difference(one, two, false), "") << variant;
    // The best target but one (AVX2 lanes are half as wide as AVX3's).
    const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
    if (targets.size() >= 2) {
      hwy::SetSupportedTargetsForTest(targets[1]);
      const AlgorithmOutput other = port->run(scene, variant);
      hwy::SetSupportedTargetsForTest(0);
      EXPECT_EQ(port_test::output_difference(one, other, false), "")
          << variant << " on " << hwy::TargetName(targets[1]);
    }
  }
}

}  // namespace
}  // namespace shadowcts
