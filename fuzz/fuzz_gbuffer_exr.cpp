// libFuzzer target: arbitrary bytes as an EXR G-buffer through read_gbuffer_exr (OpenImageIO /
// OpenEXR and the project's channel checks), then classify_samples against a small case. The
// property: InputError, or samples of the declared size with finite positions where not sky;
// never a crash, leak or sanitizer report. Seeds: written by fuzz/build.sh with
// write_gbuffer_seeds (EXR files are not committed).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "shadowcts/case.h"
#include "shadowcts/errors.h"
#include "shadowcts/gbuffer_exr.h"
#include "support/temp_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts;
  const std::string path = fuzzing::write_scratch_file("gbuffer.exr", data, size);
  ViewSamples samples;
  try {
    samples = read_gbuffer_exr(path);
  } catch (const InputError&) {
    return 0;
  }
  if (samples.samples.size() != std::size_t(samples.width) * samples.height) {
    std::fprintf(stderr, "G-buffer of %ux%u has %zu samples\n", samples.width, samples.height,
                 samples.samples.size());
    std::abort();
  }
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class == SampleClass::sky) continue;
    if (!std::isfinite(s.position.x) || !std::isfinite(s.position.y) ||
        !std::isfinite(s.position.z)) {
      std::fprintf(stderr, "non-sky pixel (%u, %u) has a non-finite position\n", s.pixel_x,
                   s.pixel_y);
      std::abort();
    }
  }
  // Receiver ids come from the file: classification must reject those out of range cleanly.
  Case c;
  c.source = "fuzz";
  c.meshes = {Mesh{"m", false, true}};
  c.triangles = {Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0}};
  ShadowLight light;
  light.position = {0.0f, 4.0f, 0.0f};
  c.light = light;
  c.camera.width = samples.width;
  c.camera.height = samples.height;
  try {
    classify_samples(c, samples, path);
  } catch (const InputError&) {
  }
  return 0;
}
