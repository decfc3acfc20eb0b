#include "image_paths.h"

#include <cctype>

namespace shadowcts {
namespace {

// Names may hold characters that are awkward in paths; dots, dashes and pluses stay readable.
std::string path_safe(const std::string& name) {
  std::string s = name;
  for (char& ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '_' ||
          ch == '+'))
      ch = '_';
  return s;
}

}  // namespace

std::string case_image_stem(const std::string& case_name) {
  return "images/" + path_safe(case_name);
}

std::string algorithm_image_stem(const RunRecord& record) {
  return case_image_stem(record.case_name) + "/" +
         path_safe(record.algorithm + "." + record.variant + "." + record.backend);
}

std::string write_png_and_exr(const std::filesystem::path& out_dir, const std::string& stem,
                              const RgbImage& image) {
  std::filesystem::create_directories((out_dir / stem).parent_path());
  write_image((out_dir / (stem + ".png")).string(), image);
  write_image((out_dir / (stem + ".exr")).string(), image);
  return stem + ".png";
}

}  // namespace shadowcts
