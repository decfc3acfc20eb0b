// Every psv variant against the exact oracle on fixtures beyond the default set (the default set
// runs in tests/conformance): the watertightness fixture at other sizes and seeds, and the real
// models that the default set leaves out.
#include <string>

#include <gtest/gtest.h>

#include "reference/psv/psv_algorithm.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_comparison.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

struct FixtureCase {
  std::string generator;
  std::uint64_t triangles;
  std::uint64_t seed;
};

class PsvOnFixtures : public ::testing::TestWithParam<FixtureCase> {};

TEST_P(PsvOnFixtures, EveryVariantIsRightOnEveryRobustSample) {
  const FixtureCase& f = GetParam();
  Case c = make_fixture(f.generator, f.triangles, f.seed);
  if (c.light && c.light->kind == ShadowLightKind::sun_disk)
    c.light->kind = ShadowLightKind::directional;  // as the runner hands it to hard shadows
  const ViewSamples samples = generate_view_samples(c);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  const auto algorithm = make_psv();
  for (const std::string& variant : algorithm->info().variants) {
    const AlgorithmOutput output = algorithm->run(c, samples, variant);
    const HardShadowComparison comparison = compare_hard_shadows(output.shadowed, truth);
    EXPECT_GT(comparison.robust, 1000u) << variant;
    EXPECT_EQ(comparison.leaks, 0u) << variant << ": " << comparison.reason;
    EXPECT_EQ(comparison.false_shadows, 0u) << variant << ": " << comparison.reason;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, PsvOnFixtures,
    ::testing::Values(FixtureCase{"shared_edges", 2000, 1}, FixtureCase{"shared_edges", 5000, 7},
                      FixtureCase{"closed_shapes", 3000, 3}, FixtureCase{"gate_house", 4000, 1},
                      FixtureCase{"foliage", 3000, 2}, FixtureCase{"model.sphere_with_hole", 0, 1},
                      FixtureCase{"model.2cylinder_engine", 0, 1}),
    [](const ::testing::TestParamInfo<FixtureCase>& param_info) {
      return test_support::test_name(param_info.param.generator + "_" +
                                     std::to_string(param_info.param.triangles) + "_" +
                                     std::to_string(param_info.param.seed));
    });

}  // namespace
}  // namespace shadowcts
