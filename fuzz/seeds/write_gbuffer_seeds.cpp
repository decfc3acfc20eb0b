// Writes the seed corpus of fuzz_gbuffer_exr into the folder given as the only argument: small
// valid G-buffers (all regular, with sky, a single pixel), written by the project's own writer so
// that the fuzzer starts from files the reader accepts.
#include <cstdint>
#include <cstdio>
#include <string>

#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/view_samples.h"

namespace {

shadowcts::ViewSamples grid(std::uint32_t width, std::uint32_t height, bool with_sky) {
  shadowcts::ViewSamples samples;
  samples.width = width;
  samples.height = height;
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      shadowcts::ViewSample s;
      s.pixel_x = x;
      s.pixel_y = y;
      if (with_sky && (x + y) % 3 == 0) {
        samples.samples.push_back(s);  // sky: no receiver
        continue;
      }
      s.position = {float(x) * 0.25f, 0.0f, float(y) * 0.25f};
      s.normal = {0.0f, 1.0f, 0.0f};
      s.receiver = (x + y) % 2;
      s.sample_class = shadowcts::SampleClass::regular;
      samples.samples.push_back(s);
    }
  return samples;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: write_gbuffer_seeds FOLDER\n");
    return 2;
  }
  const std::string folder = argv[1];
  shadowcts::write_gbuffer_exr(folder + "/regular_4x4.exr", grid(4, 4, false));
  shadowcts::write_gbuffer_exr(folder + "/sky_5x3.exr", grid(5, 3, true));
  shadowcts::write_gbuffer_exr(folder + "/single_1x1.exr", grid(1, 1, false));
  return 0;
}
