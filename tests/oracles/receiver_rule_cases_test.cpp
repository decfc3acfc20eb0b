// The stiff cases of the receiver half-space rule decide something for implementations too: on
// their rendered samples, some segments meet a caster only where the rule removes it (a coplanar
// neighbour below the floor's plane), and the exact oracle calls those samples robust-lit, so an
// implementation without the rule fails there.
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "oracles/caster_bvh.h"
#include "oracles/exact_segment_triangle.h"
#include "oracles/shadow_segment.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {
namespace {

class ReceiverRuleCases : public testing::TestWithParam<std::string> {};

TEST_P(ReceiverRuleCases, SomeRobustLitSamplesAreBlockedOnlyWithoutTheRule) {
  const Case c = make_fixture(GetParam());
  const ViewSamples samples = generate_view_samples(c);
  const HardShadowTruth truth = exact_hard_shadow_oracle(c, samples);
  const HardShadowLight light = hard_shadow_light(c);
  const CasterBvh casters(c);
  const ExactShadowPredicate predicate(light, c.scale());
  std::size_t only_without_rule = 0;
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class != SampleClass::regular || truth.band[i] != BandClass::robust_lit) continue;
    const glm::dvec3 p(s.position);
    bool blocked = false;
    casters.visit(make_shadow_segment(p, light, c.scale()), 0.0, [&](std::uint32_t t) {
      blocked = t != s.receiver && predicate.blocks(c.triangles[t], MovedPoint{p, 0.0, {0, 0, 0}});
      return blocked;
    });
    only_without_rule += blocked;
  }
  EXPECT_GE(only_without_rule, 20u) << "of " << samples.count(SampleClass::regular);
  std::cout << "[ COUNT    ] " << GetParam() << ": " << only_without_rule
            << " robust-lit samples blocked without the rule\n";
}

INSTANTIATE_TEST_SUITE_P(Stiff, ReceiverRuleCases,
                         testing::Values("stiff.tilted_floor_coplanar_neighbours",
                                         "stiff.tilted_floor_directional"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           for (char& ch : name)
                             if (ch == '.') ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace shadowcts
