// The fast oracle is a separate oracle, not a shortcut of the exact one: on every default
// fixture with a shadow light they agree on every sample the exact oracle calls robust.
#include <gtest/gtest.h>

#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "tests/test_name.h"

namespace shadowcts {
namespace {

class DefaultFixtureAgreement : public testing::TestWithParam<std::string> {};

TEST_P(DefaultFixtureAgreement, ExactAndEmbreeAgreeOnRobustSamples) {
  Case c = make_fixture(GetParam());
  if (!c.light) GTEST_SKIP() << "no shadow light: nothing for a hard-shadow oracle to decide";
  if (c.light->kind == ShadowLightKind::sun_disk) {
    c.light->kind = ShadowLightKind::directional;  // hard shadows of the disk's centre
    c.light->angular_radius = 0;
  }
  const ViewSamples samples = generate_view_samples(c);
  const HardShadowTruth exact = exact_hard_shadow_oracle(c, samples);
  const HardShadowTruth fast = embree_hard_shadow_oracle(c, samples);
  ASSERT_TRUE(exact.exact);
  std::size_t robust = 0, disagreements = 0;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    if (exact.band[i] != BandClass::robust_lit && exact.band[i] != BandClass::robust_shadowed)
      continue;
    ++robust;
    if (exact.shadowed[i] != fast.shadowed[i]) {
      ++disagreements;
      ADD_FAILURE() << "pixel (" << samples.samples[i].pixel_x << ", " << samples.samples[i].pixel_y
                    << "): exact " << int(exact.shadowed[i]) << ", embree "
                    << int(fast.shadowed[i]);
      if (disagreements > 10) break;
    }
  }
  EXPECT_GT(robust, samples.samples.size() / 4);
}

INSTANTIATE_TEST_SUITE_P(Default, DefaultFixtureAgreement, testing::ValuesIn(default_fixtures()),
                         test_support::param_test_name);

}  // namespace
}  // namespace shadowcts
