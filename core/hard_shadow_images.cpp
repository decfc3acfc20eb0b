#include "hard_shadow_images.h"

#include <cctype>

namespace shadowcts {
namespace {

struct Rgb {
  std::uint8_t r, g, b;
};

constexpr Rgb sky_colour{110, 150, 200};
constexpr Rgb back_facing_colour{45, 50, 70};
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

// Case names may hold characters that are awkward in paths; dots and dashes stay readable.
std::string path_safe(const std::string& name) {
  std::string s = name;
  for (char& ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '_'))
      ch = '_';
  return s;
}

std::string write_both(const std::filesystem::path& out_dir, const std::string& relative_stem,
                       const RgbImage& image) {
  std::filesystem::create_directories((out_dir / relative_stem).parent_path());
  write_image((out_dir / (relative_stem + ".png")).string(), image);
  write_image((out_dir / (relative_stem + ".exr")).string(), image);
  return relative_stem + ".png";
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

std::string write_oracle_images(const std::filesystem::path& out_dir, const std::string& case_name,
                                const ViewSamples& samples, const HardShadowTruth& truth) {
  return write_both(out_dir, "images/" + path_safe(case_name) + "/oracle.mask",
                    shadow_mask_image(samples, truth.shadowed));
}

std::vector<std::string> write_algorithm_images(const std::filesystem::path& out_dir,
                                                const std::string& case_name,
                                                const RunRecord& record, const ViewSamples& samples,
                                                const std::vector<std::uint8_t>& shadowed,
                                                const HardShadowTruth& truth) {
  const std::string stem =
      "images/" + path_safe(case_name) + "/" +
      path_safe(record.algorithm + "." + record.variant + "." + record.backend);
  return {write_both(out_dir, stem + ".mask", shadow_mask_image(samples, shadowed)),
          write_both(out_dir, stem + ".mismatch", mismatch_image(samples, shadowed, truth))};
}

}  // namespace shadowcts
