#pragma once
// Cases the metric tests share: default fixtures at a reduced resolution (the structures do not
// depend on it, the tests' run time does), sun disks seen as directional lights as the runner
// shows them to hard-shadow algorithms.
#include <cstdint>
#include <string>
#include <vector>

#include "shadowcts/case.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::metric::testing {

struct FixtureCase {
  Case c;
  ViewSamples samples;
};

inline FixtureCase load_fixture(const std::string& name, std::uint32_t resolution = 96) {
  FixtureCase f;
  f.c = make_fixture(name);
  f.c.camera.width = f.c.camera.height = resolution;
  if (f.c.light && f.c.light->kind == ShadowLightKind::sun_disk) {
    f.c.light->kind = ShadowLightKind::directional;
    f.c.light->angular_radius = 0.0f;
  }
  f.samples = generate_view_samples(f.c);
  return f;
}

// The default fixtures with a point or directional light (or a sun disk): every one the metric
// algorithm runs on.
inline std::vector<std::string> hard_shadow_fixtures() {
  std::vector<std::string> names;
  for (const std::string& name : default_fixtures())
    if (make_fixture(name).light) names.push_back(name);
  return names;
}

}  // namespace shadowcts::metric::testing
