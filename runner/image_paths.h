#pragma once
// Where a run's images go: images/<case folder>/oracle.* and
// images/<case folder>/<algorithm>.<variant>.<backend>.*
#include <filesystem>
#include <string>
#include <vector>

#include "run_record.h"
#include "shadowcts/image_file.h"

namespace shadowcts {

// One image folder name per case, in case order: the name made safe for paths (only letters,
// digits and . - _ +; never empty, never starting with a dot, so never "." or ".."), at most
// 100 characters, and unique within the run ignoring letter case (a later case whose name is
// taken gets "-2", "-3", ...). The same case list gives the same folders.
std::vector<std::string> case_image_folders(const std::vector<std::string>& case_names);

// "images/<folder>" for a folder from case_image_folders.
std::string case_image_stem(const std::string& image_folder);

// "images/<record.image_folder>/<algorithm>.<variant>.<backend>".
std::string algorithm_image_stem(const RunRecord& record);

// Where a run writes its images: under out_dir, or nowhere (`run --no-images`, for CI gating that
// reads only the verdicts: no images to encode and no OpenImageIO to load, see core/image_codec.h).
struct ImageTarget {
  std::filesystem::path out_dir;
  bool enabled = true;
};

// Writes out_dir/stem.png and out_dir/stem.exr (creating folders); returns "stem.png".
// Throws OutputError naming the file or folder that cannot be written.
std::string write_png_and_exr(const std::filesystem::path& out_dir, const std::string& stem,
                              const RgbImage& image);

}  // namespace shadowcts
