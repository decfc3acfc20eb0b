#pragma once
// A case with explicitly placed view samples (one row of pixels), as the geometry fuzzers build
// them: samples sit where the fuzzer wants a shadow ray to go, not where a camera would look.
#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::fuzzing {

struct SampleCase {
  Case c;
  ViewSamples samples;
  // false: the samples came from the case's camera (generate_view_samples), which finish() then
  // keeps; algorithms that bound samples by their pixels' frusta only run on such samples.
  bool explicit_samples = true;

  // Starts a mesh; triangles added afterwards belong to it.
  std::uint32_t begin_mesh(const std::string& name, bool closed, bool caster = true);
  std::uint32_t add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& d);
  // A sample whose normal faces the light (so it is compared), on receiver `receiver`.
  void add_sample(const glm::vec3& position, std::uint32_t receiver);

  // Camera near the light (outside every shadow volume; the samples are given, so only its place,
  // planes and resolution matter), one row of width = sample count, then the sample classes by
  // the light. Idempotent: call after the last sample, and again after editing the case.
  void finish();

 private:
  std::uint32_t mesh_ = 0;
};

// Direction from `position` towards the case's point or directional light (not normalized).
glm::dvec3 towards_light(const ShadowLight& light, const glm::vec3& position);

}  // namespace shadowcts::fuzzing
