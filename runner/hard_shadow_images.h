#pragma once
// The images that explain a hard-shadow result: masks and the mismatch map.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "run_record.h"
#include "shadowcts/hard_shadow_truth.h"
#include "shadowcts/image_file.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {

// Mask colours: lit light grey, shadowed dark grey, sky blue, back-facing (unlit by orientation)
// dark slate.
RgbImage shadow_mask_image(const ViewSamples& samples, const std::vector<std::uint8_t>& shadowed);

// Mismatch map: leaks red, false shadows blue, ambiguous yellow (bright where the answer differs
// from the exact one), agreement grey (lighter where lit), sky and back-facing as in the mask.
RgbImage mismatch_image(const ViewSamples& samples, const std::vector<std::uint8_t>& shadowed,
                        const HardShadowTruth& truth);

// Writes images/<image_folder>/oracle.mask.{png,exr}; returns the PNG path relative to out_dir.
std::string write_oracle_images(const std::filesystem::path& out_dir,
                                const std::string& image_folder, const ViewSamples& samples,
                                const HardShadowTruth& truth);

// Writes images/<case>/<algorithm>.<variant>.<backend>.{mask,mismatch}.{png,exr}; returns the
// paths relative to out_dir.
std::vector<std::string> write_algorithm_images(const std::filesystem::path& out_dir,
                                                const RunRecord& record, const ViewSamples& samples,
                                                const std::vector<std::uint8_t>& shadowed,
                                                const HardShadowTruth& truth);

}  // namespace shadowcts
