#pragma once
// View samples: what the camera sees, one per pixel. They are the input of every algorithm.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace shadowcts {

struct Case;

enum class SampleClass : std::uint8_t {
  sky,          // the primary ray hit nothing: not compared
  back_facing,  // the normal faces away from the shadow light: unlit by orientation, not compared
  regular,
};

inline constexpr std::uint32_t no_receiver = std::numeric_limits<std::uint32_t>::max();

struct ViewSample {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};                // geometric, unit, facing the camera
  std::uint32_t receiver = no_receiver;  // triangle index into Case::triangles
  std::uint32_t pixel_x = 0, pixel_y = 0;
  SampleClass sample_class = SampleClass::sky;
};

// One sample per pixel, row-major, row 0 at the top of the image.
struct ViewSamples {
  std::uint32_t width = 0, height = 0;
  std::vector<ViewSample> samples;

  std::size_t count(SampleClass c) const;
};

// Casts one Embree primary ray through each pixel centre of the case's camera. Parallel and
// deterministic: the result does not depend on the thread count.
ViewSamples generate_view_samples(const Case& c);

// Re-derives the sample classes of samples that came from elsewhere (an EXR G-buffer): sky stays
// sky, the rest is back-facing or regular by the case's shadow light. Throws InputError naming
// `source` and the pixel when a receiver id is out of range for the case or the size differs
// from the camera's resolution.
void classify_samples(const Case& c, ViewSamples& samples, const std::string& source);

}  // namespace shadowcts
