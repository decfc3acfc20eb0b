#include "gltf_loader.h"

// tinygltf is the Debian shared library: TINYGLTF_IMPLEMENTATION must not be defined here.
#include <tiny_gltf.h>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gltf_container.h"
#include "gltf_scene.h"
#include "gltf_schema.h"
#include "json_limits.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

using Json = nlohmann::json;

// tinygltf decodes images with its callback; shadows need no textures, so nothing is decoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

std::string trim_trailing_newlines(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  for (auto& c : text) {
    if (c == '\n') c = ' ';
  }
  return text;
}

LoadedScene load_gltf_checked(const std::string& path) {
  const GltfContainer file = read_gltf_container(path);
  const std::vector<unsigned char>& bytes = file.bytes;
  const bool binary = file.binary;
  const std::string& json_text = file.json_text;
  // tinygltf converts the JSON recursively (extras nested 100,000 deep overflowed the stack).
  check_json_nesting(json_text, path, binary ? "GLB JSON chunk" : "JSON");

  LoadedScene scene;
  Json root;
  try {
    root = Json::parse(json_text);
  } catch (const Json::exception& e) {
    throw InputError(path, binary ? "GLB JSON chunk" : "JSON", e.what());
  }
  const GltfSchemaReport schema = check_gltf_schema(root);
  if (!schema.errors.empty()) {
    std::string problem = schema.errors.front().second;
    if (schema.errors.size() > 1) {
      problem += " (and " + std::to_string(schema.errors.size() - 1) +
                 " more schema errors, e.g. " + schema.errors[1].first + ": " +
                 schema.errors[1].second + ")";
    }
    throw InputError(path, schema.errors.front().first, problem);
  }
  for (const auto& warning : schema.warnings) scene.warnings.push_back(path + ": " + warning);
  if (const auto required = root.find("extensionsRequired"); required != root.end()) {
    for (const auto& name : *required) {
      if (!extension_keeps_geometry(name.get<std::string>())) {
        throw InputError(path, "extensionsRequired",
                         "extension " + name.get<std::string>() + " is not supported");
      }
    }
  }

  if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
    throw InputError(path, "file", "larger than 4 GiB (tinygltf's limit)");
  }
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  const bool loaded =
      binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(),
                                           static_cast<unsigned int>(bytes.size()), base_dir)
             : loader.LoadASCIIFromString(&model, &error, &warning,
                                          reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size()), base_dir);
  if (!loaded) {
    std::string problem = "tinygltf: " + trim_trailing_newlines(error);
    if (!warning.empty()) problem += " (warnings: " + trim_trailing_newlines(warning) + ")";
    throw InputError(path, "file", problem);
  }
  // tinygltf reports some problems in `error` and still succeeds (a texture reference without
  // index): they did not stop the geometry from loading.
  if (!error.empty())
    scene.warnings.push_back(path + ": tinygltf: " + trim_trailing_newlines(error));
  if (!warning.empty()) {
    scene.warnings.push_back(path + ": tinygltf: " + trim_trailing_newlines(warning));
  }

  add_gltf_scene(path, model, scene);
  if (scene.triangles.empty()) {
    throw InputError(path, "scene", "contains no triangles");
  }
  return scene;
}

}  // namespace

LoadedScene load_gltf_file(const std::string& path) {
  try {
    return load_gltf_checked(path);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // tinygltf, nlohmann-json and the standard library may throw (bad_alloc on absurd counts):
    // every such failure is still a failure of this input file.
    throw InputError(path, "file", std::string("cannot be loaded: ") + e.what());
  }
}

}  // namespace shadowcts
