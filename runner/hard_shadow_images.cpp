#include "hard_shadow_images.h"

#include "image_paths.h"
#include "sample_colours.h"

namespace shadowcts {
namespace {

constexpr Rgb lit_colour{235, 235, 235};
constexpr Rgb shadowed_colour{40, 40, 40};
constexpr Rgb agree_lit_colour{200, 200, 200};
constexpr Rgb agree_shadowed_colour{120, 120, 120};
constexpr Rgb leak_colour{255, 0, 0};
constexpr Rgb false_shadow_colour{0, 70, 255};
constexpr Rgb ambiguous_differs_colour{255, 220, 0};
constexpr Rgb ambiguous_agrees_colour{170, 150, 40};

template <class ColourOf>
RgbImage paint(const ViewSamples& samples, ColourOf colour_of) {
  RgbImage image;
  image.width = samples.width;
  image.height = samples.height;
  image.rgb.resize(samples.samples.size() * 3);
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const SampleClass cls = samples.samples[i].sample_class;
    const Rgb c = cls == SampleClass::sky           ? sky_colour
                  : cls == SampleClass::back_facing ? back_facing_colour
                                                    : colour_of(i);
    image.rgb[3 * i + 0] = c.r;
    image.rgb[3 * i + 1] = c.g;
    image.rgb[3 * i + 2] = c.b;
  }
  return image;
}

}  // namespace

RgbImage shadow_mask_image(const ViewSamples& samples, const std::vector<std::uint8_t>& shadowed) {
  return paint(samples, [&](std::size_t i) { return shadowed[i] ? shadowed_colour : lit_colour; });
}

RgbImage mismatch_image(const ViewSamples& samples, const std::vector<std::uint8_t>& shadowed,
                        const HardShadowTruth& truth) {
  return paint(samples, [&](std::size_t i) {
    const bool answer = shadowed[i] != 0, expected = truth.shadowed[i] != 0;
    switch (truth.band[i]) {
      case BandClass::ambiguous:
        return answer == expected ? ambiguous_agrees_colour : ambiguous_differs_colour;
      case BandClass::not_compared:
        return back_facing_colour;
      default:
        if (answer == expected) return expected ? agree_shadowed_colour : agree_lit_colour;
        return expected ? leak_colour : false_shadow_colour;
    }
  });
}

std::string write_oracle_images(const std::filesystem::path& out_dir,
                                const std::string& image_folder, const ViewSamples& samples,
                                const HardShadowTruth& truth) {
  return write_png_and_exr(out_dir, case_image_stem(image_folder) + "/oracle.mask",
                           shadow_mask_image(samples, truth.shadowed));
}

std::vector<std::string> write_algorithm_images(const std::filesystem::path& out_dir,
                                                const RunRecord& record, const ViewSamples& samples,
                                                const std::vector<std::uint8_t>& shadowed,
                                                const HardShadowTruth& truth) {
  const std::string stem = algorithm_image_stem(record);
  return {write_png_and_exr(out_dir, stem + ".mask", shadow_mask_image(samples, shadowed)),
          write_png_and_exr(out_dir, stem + ".mismatch", mismatch_image(samples, shadowed, truth))};
}

}  // namespace shadowcts
