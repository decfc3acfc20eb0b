#include "shadowcts/scene_file.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "gltf_loader.h"
#include "mesh_file_loader.h"
#include "shadowcts/errors.h"

namespace shadowcts {

LoadedScene load_scene_file(const std::string& path) {
  const std::filesystem::path file(path);
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(path, "file",
                     std::filesystem::exists(file, error) ? "not a regular file" : "not found");
  }
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".gltf" || extension == ".glb") return load_gltf_file(path);
  if (extension == ".obj" || extension == ".off" || extension == ".ply" || extension == ".stl") {
    return load_mesh_file(path);
  }
  throw InputError(
      path, "file",
      "unsupported extension '" + extension + "' (supported: .gltf .glb .obj .off .ply .stl)");
}

}  // namespace shadowcts
