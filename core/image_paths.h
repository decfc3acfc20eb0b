#pragma once
// Where a run's images go: images/<case>/oracle.* and
// images/<case>/<algorithm>.<variant>.<backend>.*
#include <filesystem>
#include <string>

#include "run_record.h"
#include "shadowcts/image_file.h"

namespace shadowcts {

// "images/<case>", the case name made safe for paths.
std::string case_image_stem(const std::string& case_name);

// "images/<case>/<algorithm>.<variant>.<backend>".
std::string algorithm_image_stem(const RunRecord& record);

// Writes out_dir/stem.png and out_dir/stem.exr (creating folders); returns "stem.png".
std::string write_png_and_exr(const std::filesystem::path& out_dir, const std::string& stem,
                              const RgbImage& image);

}  // namespace shadowcts
