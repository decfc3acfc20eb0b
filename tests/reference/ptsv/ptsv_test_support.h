#pragma once
// Shared by the ptsv tests: fixtures with their view samples, and running a variant.
#include <cstdint>
#include <string>

#include "reference/ptsv/ptsv_algorithm.h"
#include "shadowcts/algorithm.h"
#include "shadowcts/case.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::ptsv_test {

struct FixtureWithSamples {
  Case c;
  ViewSamples samples;
};

// The runner hands hard-shadow algorithms a sun disk as its centre direction.
inline Case hard_shadow_case(Case c) {
  if (c.light && c.light->kind == ShadowLightKind::sun_disk) {
    c.light->kind = ShadowLightKind::directional;
    c.light->angular_radius = 0.0f;
  }
  return c;
}

inline FixtureWithSamples load_fixture(const std::string& name) {
  FixtureWithSamples f;
  f.c = hard_shadow_case(make_fixture(name));
  f.samples = generate_view_samples(f.c);
  return f;
}

inline std::uint64_t counter(const AlgorithmOutput& output, const std::string& name) {
  for (const auto& [key, value] : output.counters)
    if (key == name) return value;
  return ~std::uint64_t(0);
}

}  // namespace shadowcts::ptsv_test
