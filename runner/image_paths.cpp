#include "image_paths.h"

#include <cctype>
#include <set>
#include <system_error>

#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

constexpr std::size_t max_folder_length = 100;  // leaves room for the file names under it

// Names may hold characters that are awkward in paths; dots, dashes and pluses stay readable.
std::string path_safe(const std::string& name) {
  std::string s = name;
  for (char& ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == '_' ||
          ch == '+'))
      ch = '_';
  return s;
}

std::string lower(std::string s) {
  for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

}  // namespace

std::vector<std::string> case_image_folders(const std::vector<std::string>& case_names) {
  std::vector<std::string> folders;
  std::set<std::string> taken;  // lower case: distinct on case-insensitive file systems too
  for (const std::string& name : case_names) {
    std::string base = path_safe(name).substr(0, max_folder_length);
    // A leading dot would hide the folder, and "." or ".." would leave images/.
    if (base.empty() || base.front() == '.') base = "_" + base;
    std::string folder = base;
    for (int k = 2; taken.count(lower(folder)); ++k) folder = base + "-" + std::to_string(k);
    taken.insert(lower(folder));
    folders.push_back(folder);
  }
  return folders;
}

std::string case_image_stem(const std::string& image_folder) {
  return "images/" + image_folder;
}

std::string algorithm_image_stem(const RunRecord& record) {
  return case_image_stem(record.image_folder) + "/" +
         path_safe(record.algorithm + "." + record.variant + "." + record.backend);
}

std::string write_png_and_exr(const std::filesystem::path& out_dir, const std::string& stem,
                              const RgbImage& image) {
  const std::filesystem::path folder = (out_dir / stem).parent_path();
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw OutputError(folder.string(), "cannot create folder: " + ec.message());
  write_image((out_dir / (stem + ".png")).string(), image);
  write_image((out_dir / (stem + ".exr")).string(), image);
  return stem + ".png";
}

}  // namespace shadowcts
