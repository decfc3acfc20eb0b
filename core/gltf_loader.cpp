#include "gltf_loader.h"

// tinygltf is the Debian shared library: TINYGLTF_IMPLEMENTATION must not be defined here.
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include "json_limits.h"
#include "mesh_closedness.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

using Json = nlohmann::json;

// ---------------------------------------------------------------------------------------------
// Schema types. tinygltf silently ignores properties of the wrong type (a "primitives" object
// instead of an array loads as a mesh without primitives), so the JSON is checked here first.
// A wrong type in anything that defines geometry or lights is an error; in anything else
// (names, materials, textures, foreign extensions) it is a warning and the geometry still loads.

enum class Severity { error, warning };

class SchemaCheck {
 public:
  std::vector<std::pair<std::string, std::string>> errors;  // element, problem
  std::vector<std::string> warnings;

  void report(Severity severity, const std::string& element, const std::string& problem) {
    if (severity == Severity::error) {
      errors.emplace_back(element, problem);
    } else {
      warnings.push_back(element + ": " + problem);
    }
  }

  // Each checker returns whether the value is there and has the right type.
  bool unsigned_integer(const Json& object, const char* key, const std::string& path,
                        Severity severity) {
    const Json* value = find(object, key);
    if (!value) return false;
    if (!value->is_number_unsigned() &&
        !(value->is_number_float() && value->get<double>() >= 0.0 &&
          std::floor(value->get<double>()) == value->get<double>() &&
          value->get<double>() <= 4294967295.0)) {
      report(severity, join(path, key), "must be a non-negative integer, is " + describe(*value));
      return false;
    }
    return true;
  }

  bool number(const Json& object, const char* key, const std::string& path, Severity severity) {
    const Json* value = find(object, key);
    if (!value) return false;
    if (!value->is_number()) {
      report(severity, join(path, key), "must be a number, is " + describe(*value));
      return false;
    }
    return true;
  }

  bool string(const Json& object, const char* key, const std::string& path, Severity severity) {
    const Json* value = find(object, key);
    if (!value) return false;
    if (!value->is_string()) {
      report(severity, join(path, key), "must be a string, is " + describe(*value));
      return false;
    }
    return true;
  }

  bool boolean(const Json& object, const char* key, const std::string& path, Severity severity) {
    const Json* value = find(object, key);
    if (!value) return false;
    if (!value->is_boolean()) {
      report(severity, join(path, key), "must be a boolean, is " + describe(*value));
      return false;
    }
    return true;
  }

  bool object(const Json& parent, const char* key, const std::string& path, Severity severity) {
    const Json* value = find(parent, key);
    if (!value) return false;
    if (!value->is_object()) {
      report(severity, join(path, key), "must be an object, is " + describe(*value));
      return false;
    }
    return true;
  }

  bool array(const Json& parent, const char* key, const std::string& path, Severity severity) {
    const Json* value = find(parent, key);
    if (!value) return false;
    if (!value->is_array()) {
      report(severity, join(path, key), "must be an array, is " + describe(*value));
      return false;
    }
    return true;
  }

  // An array of numbers (exactly `size` of them when size > 0).
  void number_array(const Json& parent, const char* key, const std::string& path, Severity severity,
                    std::size_t size = 0) {
    if (!array(parent, key, path, severity)) return;
    const Json& values = parent.at(key);
    if (size > 0 && values.size() != size) {
      report(
          severity, join(path, key),
          "must have " + std::to_string(size) + " elements, has " + std::to_string(values.size()));
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!values[i].is_number()) {
        report(severity, join(path, key) + "[" + std::to_string(i) + "]",
               "must be a number, is " + describe(values[i]));
      }
    }
  }

  void unsigned_array(const Json& parent, const char* key, const std::string& path,
                      Severity severity) {
    if (!array(parent, key, path, severity)) return;
    const Json& values = parent.at(key);
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (!values[i].is_number_unsigned()) {
        report(severity, join(path, key) + "[" + std::to_string(i) + "]",
               "must be a non-negative integer, is " + describe(values[i]));
      }
    }
  }

  // Calls `check(element, element_path)` for each object of the array `key`.
  void objects(const Json& parent, const char* key, const std::string& path, Severity severity,
               const std::function<void(const Json&, const std::string&)>& check) {
    if (!array(parent, key, path, severity)) return;
    const Json& values = parent.at(key);
    const std::string prefix = path.empty() ? std::string(key) : join(path, key);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::string element_path = prefix + "[" + std::to_string(i) + "]";
      if (!values[i].is_object()) {
        report(severity, element_path, "must be an object, is " + describe(values[i]));
        continue;
      }
      check(values[i], element_path);
    }
  }

  // "name", "extras" and foreign "extensions" never matter for geometry.
  void common(const Json& object_value, const std::string& path) {
    string(object_value, "name", path, Severity::warning);
    extensions(object_value, path, Severity::warning);
  }

  // Every extension's value must be an object.
  void extensions(const Json& object_value, const std::string& path, Severity severity) {
    if (!object(object_value, "extensions", path, severity)) return;
    for (const auto& [name, value] : object_value.at("extensions").items()) {
      if (!value.is_object()) {
        report(severity, path + ".extensions." + name, "must be an object, is " + describe(value));
      }
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  static const Json* find(const Json& object_value, const char* key) {
    const auto it = object_value.find(key);
    return it == object_value.end() ? nullptr : &*it;
  }

  static std::string describe(const Json& value) { return describe_json(value); }
};

void check_texture_info(SchemaCheck& check, const Json& parent, const char* key,
                        const std::string& path) {
  if (!check.object(parent, key, path, Severity::warning)) return;
  const Json& info = parent.at(key);
  const std::string info_path = SchemaCheck::join(path, key);
  if (!SchemaCheck::find(info, "index")) {
    check.report(Severity::warning, info_path + ".index", "is missing");
  }
  check.unsigned_integer(info, "index", info_path, Severity::warning);
  check.unsigned_integer(info, "texCoord", info_path, Severity::warning);
  check.number(info, "scale", info_path, Severity::warning);
  check.number(info, "strength", info_path, Severity::warning);
  check.extensions(info, info_path, Severity::warning);
}

void check_gltf_schema(SchemaCheck& check, const Json& root) {
  constexpr auto error = Severity::error;
  constexpr auto warning = Severity::warning;
  if (!root.is_object()) {
    check.report(error, "(root)", "must be a JSON object, is " + SchemaCheck::describe(root));
    return;
  }
  if (check.object(root, "asset", "", error)) {
    const Json& asset = root.at("asset");
    if (!check.string(asset, "version", "asset", error)) {
      if (!SchemaCheck::find(asset, "version")) check.report(error, "asset.version", "is missing");
    } else if (!asset.at("version").get<std::string>().starts_with("2.")) {
      check.report(error, "asset.version",
                   "glTF " + asset.at("version").get<std::string>() + " is not supported (2.x)");
    }
    check.string(asset, "generator", "asset", warning);
    check.string(asset, "copyright", "asset", warning);
  } else if (!SchemaCheck::find(root, "asset")) {
    check.report(error, "asset", "is missing");
  }
  check.unsigned_integer(root, "scene", "", error);
  check.objects(root, "scenes", "", error, [&](const Json& scene, const std::string& path) {
    check.unsigned_array(scene, "nodes", path, error);
    check.common(scene, path);
  });
  check.objects(root, "nodes", "", error, [&](const Json& node, const std::string& path) {
    check.unsigned_array(node, "children", path, error);
    check.unsigned_integer(node, "mesh", path, error);
    check.number_array(node, "matrix", path, error, 16);
    check.number_array(node, "translation", path, error, 3);
    check.number_array(node, "rotation", path, error, 4);
    check.number_array(node, "scale", path, error, 3);
    check.unsigned_integer(node, "camera", path, warning);
    check.unsigned_integer(node, "skin", path, warning);
    check.number_array(node, "weights", path, warning);
    check.string(node, "name", path, warning);
    if (check.object(node, "extensions", path, warning)) {
      for (const auto& [name, value] : node.at("extensions").items()) {
        const std::string extension_path = path + ".extensions." + name;
        const bool lights = name == "KHR_lights_punctual";
        if (!value.is_object()) {
          check.report(lights ? error : warning, extension_path,
                       "must be an object, is " + SchemaCheck::describe(value));
        } else if (lights) {
          if (!check.unsigned_integer(value, "light", extension_path, error) &&
              !SchemaCheck::find(value, "light")) {
            check.report(error, extension_path + ".light", "is missing");
          }
        }
      }
    }
  });
  check.objects(root, "meshes", "", error, [&](const Json& mesh, const std::string& path) {
    if (!SchemaCheck::find(mesh, "primitives"))
      check.report(error, path + ".primitives", "is missing");
    check.objects(mesh, "primitives", path, error,
                  [&](const Json& primitive, const std::string& primitive_path) {
                    if (check.object(primitive, "attributes", primitive_path, error)) {
                      for (const auto& [semantic, accessor] : primitive.at("attributes").items()) {
                        if (!accessor.is_number_unsigned()) {
                          check.report(
                              semantic == "POSITION" ? error : warning,
                              primitive_path + ".attributes." + semantic,
                              "must be an accessor index, is " + SchemaCheck::describe(accessor));
                        }
                      }
                    } else if (!SchemaCheck::find(primitive, "attributes")) {
                      check.report(error, primitive_path + ".attributes", "is missing");
                    }
                    check.unsigned_integer(primitive, "indices", primitive_path, error);
                    check.unsigned_integer(primitive, "mode", primitive_path, error);
                    check.unsigned_integer(primitive, "material", primitive_path, warning);
                    check.array(primitive, "targets", primitive_path, warning);
                    check.extensions(primitive, primitive_path, warning);
                  });
    if (SchemaCheck::find(mesh, "primitives") && mesh.at("primitives").is_array() &&
        mesh.at("primitives").empty()) {
      check.report(error, path + ".primitives", "must not be empty");
    }
    check.number_array(mesh, "weights", path, warning);
    check.common(mesh, path);
  });
  check.objects(root, "accessors", "", error, [&](const Json& accessor, const std::string& path) {
    check.unsigned_integer(accessor, "bufferView", path, error);
    check.unsigned_integer(accessor, "byteOffset", path, error);
    check.unsigned_integer(accessor, "componentType", path, error);
    check.unsigned_integer(accessor, "count", path, error);
    check.string(accessor, "type", path, error);
    check.boolean(accessor, "normalized", path, warning);
    check.number_array(accessor, "min", path, warning);
    check.number_array(accessor, "max", path, warning);
    if (check.object(accessor, "sparse", path, error)) {
      const Json& sparse = accessor.at("sparse");
      const std::string sparse_path = path + ".sparse";
      check.unsigned_integer(sparse, "count", sparse_path, error);
      if (check.object(sparse, "indices", sparse_path, error)) {
        check.unsigned_integer(sparse.at("indices"), "bufferView", sparse_path + ".indices", error);
        check.unsigned_integer(sparse.at("indices"), "byteOffset", sparse_path + ".indices", error);
        check.unsigned_integer(sparse.at("indices"), "componentType", sparse_path + ".indices",
                               error);
      }
      if (check.object(sparse, "values", sparse_path, error)) {
        check.unsigned_integer(sparse.at("values"), "bufferView", sparse_path + ".values", error);
        check.unsigned_integer(sparse.at("values"), "byteOffset", sparse_path + ".values", error);
      }
    }
    check.common(accessor, path);
  });
  check.objects(root, "bufferViews", "", error, [&](const Json& view, const std::string& path) {
    check.unsigned_integer(view, "buffer", path, error);
    check.unsigned_integer(view, "byteOffset", path, error);
    check.unsigned_integer(view, "byteLength", path, error);
    check.unsigned_integer(view, "byteStride", path, error);
    check.unsigned_integer(view, "target", path, warning);
    check.common(view, path);
  });
  check.objects(root, "buffers", "", error, [&](const Json& buffer, const std::string& path) {
    check.string(buffer, "uri", path, error);
    check.unsigned_integer(buffer, "byteLength", path, error);
    check.common(buffer, path);
  });
  check.objects(root, "materials", "", warning, [&](const Json& material, const std::string& path) {
    if (check.object(material, "pbrMetallicRoughness", path, warning)) {
      const Json& pbr = material.at("pbrMetallicRoughness");
      const std::string pbr_path = path + ".pbrMetallicRoughness";
      check.number_array(pbr, "baseColorFactor", pbr_path, warning, 4);
      check.number(pbr, "metallicFactor", pbr_path, warning);
      check.number(pbr, "roughnessFactor", pbr_path, warning);
      check_texture_info(check, pbr, "baseColorTexture", pbr_path);
      check_texture_info(check, pbr, "metallicRoughnessTexture", pbr_path);
    }
    check_texture_info(check, material, "normalTexture", path);
    check_texture_info(check, material, "occlusionTexture", path);
    check_texture_info(check, material, "emissiveTexture", path);
    check.number_array(material, "emissiveFactor", path, warning, 3);
    check.string(material, "alphaMode", path, warning);
    check.number(material, "alphaCutoff", path, warning);
    check.boolean(material, "doubleSided", path, warning);
    check.common(material, path);
  });
  check.objects(root, "textures", "", warning, [&](const Json& texture, const std::string& path) {
    check.unsigned_integer(texture, "sampler", path, warning);
    check.unsigned_integer(texture, "source", path, warning);
    check.common(texture, path);
  });
  check.objects(root, "images", "", warning, [&](const Json& image, const std::string& path) {
    check.string(image, "uri", path, warning);
    check.string(image, "mimeType", path, warning);
    check.unsigned_integer(image, "bufferView", path, warning);
    check.common(image, path);
  });
  check.objects(root, "samplers", "", warning, [&](const Json& sampler, const std::string& path) {
    for (const char* key : {"magFilter", "minFilter", "wrapS", "wrapT"}) {
      check.unsigned_integer(sampler, key, path, warning);
    }
    check.common(sampler, path);
  });
  for (const char* key : {"animations", "skins", "cameras"}) {
    check.objects(root, key, "", warning,
                  [&](const Json& value, const std::string& path) { check.common(value, path); });
  }
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (!check.array(root, key, "", error)) continue;
    const Json& names = root.at(key);
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!names[i].is_string()) {
        check.report(error, std::string(key) + "[" + std::to_string(i) + "]",
                     "must be a string, is " + SchemaCheck::describe(names[i]));
      }
    }
  }
  if (check.object(root, "extensions", "", warning)) {
    for (const auto& [name, value] : root.at("extensions").items()) {
      const std::string path = "extensions." + name;
      if (name != "KHR_lights_punctual") {
        if (!value.is_object()) {
          check.report(warning, path, "must be an object, is " + SchemaCheck::describe(value));
        }
        continue;
      }
      if (!value.is_object()) {
        check.report(error, path, "must be an object, is " + SchemaCheck::describe(value));
        continue;
      }
      check.objects(
          value, "lights", path, error, [&](const Json& light, const std::string& light_path) {
            if (!check.string(light, "type", light_path, error) &&
                !SchemaCheck::find(light, "type")) {
              check.report(error, light_path + ".type", "is missing");
            }
            check.number(light, "range", light_path, error);
            check.number(light, "intensity", light_path, warning);
            check.number_array(light, "color", light_path, warning, 3);
            if (check.object(light, "spot", light_path, error)) {
              check.number(light.at("spot"), "innerConeAngle", light_path + ".spot", error);
              check.number(light.at("spot"), "outerConeAngle", light_path + ".spot", error);
            }
            check.common(light, light_path);
          });
    }
  }
}

// Extensions a file may require without changing what its triangles and lights are.
bool extension_keeps_geometry(const std::string& name) {
  return name == "KHR_lights_punctual" || name.starts_with("KHR_materials_") ||
         name.starts_with("KHR_texture_") || name == "EXT_texture_webp" ||
         name == "KHR_mesh_quantization";  // positions must still be FLOAT: checked per accessor
}

// ---------------------------------------------------------------------------------------------
// File reading.

std::vector<unsigned char> read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "cannot be opened");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "file", "read error");
  return bytes;
}

std::uint32_t read_u32_le(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

bool is_glb(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

bool has_glb_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".glb";
}

// The first four bytes as hex and, when printable, as text: "67 6c 54 46 'glTF'".
std::string magic_text(const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 4) return "missing: the file has " + std::to_string(bytes.size()) + " bytes";
  static constexpr char digits[] = "0123456789abcdef";
  std::string hex, printable = "'";
  for (std::size_t i = 0; i < 4; ++i) {
    hex += (i ? " " : "") + std::string{digits[bytes[i] >> 4], digits[bytes[i] & 15]};
    printable += std::isprint(bytes[i]) ? static_cast<char>(bytes[i]) : '.';
  }
  return hex + " " + printable + "', expected 67 6c 54 46 'glTF'";
}

// The JSON chunk of a GLB container, after checking the container's own lengths.
std::string glb_json_chunk(const std::string& path, const std::vector<unsigned char>& bytes) {
  if (bytes.size() < 20) throw InputError(path, "GLB header", "file is shorter than a GLB header");
  const std::uint32_t version = read_u32_le(bytes.data() + 4);
  const std::uint32_t length = read_u32_le(bytes.data() + 8);
  if (version != 2) {
    throw InputError(path, "GLB header",
                     "container version " + std::to_string(version) + " is not supported (2)");
  }
  if (length != bytes.size()) {
    throw InputError(path, "GLB header",
                     "declares " + std::to_string(length) + " bytes, the file has " +
                         std::to_string(bytes.size()) +
                         (length > bytes.size() ? " (truncated)" : ""));
  }
  const std::uint32_t chunk_length = read_u32_le(bytes.data() + 12);
  if (std::memcmp(bytes.data() + 16, "JSON", 4) != 0) {
    throw InputError(path, "GLB chunk 0", "is not the JSON chunk");
  }
  if (chunk_length > bytes.size() - 20) {
    throw InputError(path, "GLB chunk 0", "JSON chunk extends past the end of the file");
  }
  return std::string(reinterpret_cast<const char*>(bytes.data()) + 20, chunk_length);
}

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

// ---------------------------------------------------------------------------------------------
// Accessor reading with every bound checked.

std::string accessor_element(const std::string& user, int accessor_index) {
  return user + " (accessor " + std::to_string(accessor_index) + ")";
}

class ModelReader {
 public:
  // Elements of an accessor without a bufferView (2^24: 192 MiB of float positions).
  static constexpr std::size_t max_elements_without_view = std::size_t{1} << 24;

  ModelReader(const std::string& path, const tinygltf::Model& model, LoadedScene& scene)
      : path_(path), model_(model), scene_(scene) {}

  // Reads the accessor as `components` values per element of component type `component_type`,
  // converted to uint32 (indices) or float (positions). `user` names the referencing element.
  template <typename Value>
  std::vector<Value> read(int accessor_index, const std::string& user, int expected_type,
                          const std::vector<int>& allowed_component_types) {
    const std::string element = accessor_element(user, accessor_index);
    if (accessor_index < 0 || static_cast<std::size_t>(accessor_index) >= model_.accessors.size()) {
      throw InputError(path_, element,
                       "accessor index out of range (" + std::to_string(model_.accessors.size()) +
                           " accessors)");
    }
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(accessor_index)];
    const std::string accessor_path = "accessors[" + std::to_string(accessor_index) + "]";
    if (accessor.type != expected_type) {
      throw InputError(
          path_, element,
          "type must be " + type_name(expected_type) + ", is " + type_name(accessor.type));
    }
    if (std::find(allowed_component_types.begin(), allowed_component_types.end(),
                  accessor.componentType) == allowed_component_types.end()) {
      std::string allowed;
      for (const int t : allowed_component_types) {
        allowed += (allowed.empty() ? "" : " or ") + component_type_name(t);
      }
      throw InputError(path_, element,
                       "componentType must be " + allowed + ", is " +
                           component_type_name(accessor.componentType));
    }
    const std::size_t components = static_cast<std::size_t>(
        tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)));
    const std::size_t component_size = static_cast<std::size_t>(
        tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType)));
    const std::size_t element_size = components * component_size;

    // Every range is checked before anything is allocated: `count` is only a claim of the file
    // (2^32 - 1 indices in a 598-byte file took 16.9 GB before the bounds check).
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
    if (accessor.bufferView >= 0) {
      std::tie(data, stride) = view_range(accessor.bufferView, accessor.byteOffset, accessor.count,
                                          element_size, element, accessor_path);
    } else if (!accessor.sparse.isSparse) {
      throw InputError(path_, element, "has neither a bufferView nor sparse values");
    } else if (accessor.count > max_elements_without_view) {
      // Zeros but for the sparse values: no byte of the file backs them, so they are capped.
      throw InputError(path_, element,
                       "count " + std::to_string(accessor.count) +
                           " without a bufferView (zeros but for the sparse values) exceeds " +
                           std::to_string(max_elements_without_view) +
                           " elements; give the base values in a bufferView");
    }

    const unsigned char* index_data = nullptr;
    const unsigned char* value_data = nullptr;
    std::size_t index_size = 0, sparse_count = 0;
    int index_type = 0;
    const std::string sparse_element = element + " sparse";
    if (accessor.sparse.isSparse) {
      // Sparse substitution: count (index, value) pairs replace elements of the base data.
      if (accessor.sparse.count <= 0 ||
          static_cast<std::size_t>(accessor.sparse.count) > accessor.count) {
        throw InputError(path_, sparse_element,
                         "count " + std::to_string(accessor.sparse.count) +
                             " must be in [1, accessor count " + std::to_string(accessor.count) +
                             "]");
      }
      sparse_count = static_cast<std::size_t>(accessor.sparse.count);
      index_type = accessor.sparse.indices.componentType;
      if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
          index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        throw InputError(path_, sparse_element + ".indices",
                         "componentType must be unsigned, is " + component_type_name(index_type));
      }
      index_size = static_cast<std::size_t>(
          tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(index_type)));
      index_data =
          view_range(accessor.sparse.indices.bufferView,
                     static_cast<std::size_t>(std::max(0, accessor.sparse.indices.byteOffset)),
                     sparse_count, index_size, sparse_element + ".indices",
                     accessor_path + ".sparse.indices")
              .first;
      value_data =
          view_range(accessor.sparse.values.bufferView,
                     static_cast<std::size_t>(std::max(0, accessor.sparse.values.byteOffset)),
                     sparse_count, element_size, sparse_element + ".values",
                     accessor_path + ".sparse.values")
              .first;
    }

    std::vector<Value> values(accessor.count * components, Value(0));
    if (data) {
      for (std::size_t i = 0; i < accessor.count; ++i) {
        for (std::size_t c = 0; c < components; ++c) {
          values[i * components + c] =
              decode<Value>(data + i * stride + c * component_size, accessor.componentType);
        }
      }
    }
    for (std::size_t k = 0; k < sparse_count; ++k) {
      const std::uint32_t target = decode<std::uint32_t>(index_data + k * index_size, index_type);
      if (target >= accessor.count) {
        throw InputError(path_, sparse_element + ".indices",
                         "index " + std::to_string(target) + " at position " + std::to_string(k) +
                             " is out of range for " + std::to_string(accessor.count) +
                             " elements");
      }
      for (std::size_t c = 0; c < components; ++c) {
        values[target * components + c] = decode<Value>(
            value_data + k * element_size + c * component_size, accessor.componentType);
      }
    }
    return values;
  }

 private:
  // Start of the data and the stride of `count` elements of `element_size` bytes at `offset`
  // in buffer view `view_index`, after checking that all of them lie inside the view and the
  // view inside its buffer.
  std::pair<const unsigned char*, std::size_t> view_range(int view_index, std::size_t offset,
                                                          std::size_t count,
                                                          std::size_t element_size,
                                                          const std::string& element,
                                                          const std::string& accessor_path) {
    if (view_index < 0 || static_cast<std::size_t>(view_index) >= model_.bufferViews.size()) {
      throw InputError(path_, element,
                       accessor_path + ".bufferView " + std::to_string(view_index) +
                           " is out of range (" + std::to_string(model_.bufferViews.size()) +
                           " buffer views)");
    }
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(view_index)];
    const std::string view_path = "bufferViews[" + std::to_string(view_index) + "]";
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size()) {
      throw InputError(path_, view_path,
                       "buffer " + std::to_string(view.buffer) + " is out of range (" +
                           std::to_string(model_.buffers.size()) + " buffers)");
    }
    const std::size_t buffer_size =
        model_.buffers[static_cast<std::size_t>(view.buffer)].data.size();
    if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset) {
      throw InputError(path_, view_path,
                       "byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                           std::to_string(view.byteLength) + " exceeds buffer " +
                           std::to_string(view.buffer) + " (" + std::to_string(buffer_size) +
                           " bytes)");
    }
    const std::size_t stride = view.byteStride == 0 ? element_size : view.byteStride;
    if (stride < element_size) {
      throw InputError(path_, view_path,
                       "byteStride " + std::to_string(view.byteStride) +
                           " is smaller than the element size " + std::to_string(element_size) +
                           " of " + element);
    }
    // The last element ends at offset + (count - 1) * stride + element_size (glTF 2.0, 3.6.2.4);
    // computed without overflow.
    const bool fits =
        count == 0 ||
        (offset <= view.byteLength && count - 1 <= (view.byteLength - offset) / stride &&
         element_size <= view.byteLength - offset - (count - 1) * stride);
    if (!fits) {
      throw InputError(path_, element,
                       "byteOffset " + std::to_string(offset) + " + " + std::to_string(count) +
                           " elements of " + std::to_string(element_size) + " bytes (stride " +
                           std::to_string(stride) + ") exceed " + view_path + " (" +
                           std::to_string(view.byteLength) + " bytes)");
    }
    const auto& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    return {data.data() + view.byteOffset + offset, stride};
  }

  template <typename Value>
  static Value decode(const unsigned char* p, int component_type) {
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return static_cast<Value>(*p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, sizeof v);
        return static_cast<Value>(v);
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, sizeof v);
        return static_cast<Value>(v);
      }
      case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        float v;
        std::memcpy(&v, p, sizeof v);
        return static_cast<Value>(v);
      }
      default:
        return Value(0);  // unreachable: component types are checked before decoding
    }
  }

  static std::string type_name(int type) {
    switch (type) {
      case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
      case TINYGLTF_TYPE_VEC2:
        return "VEC2";
      case TINYGLTF_TYPE_VEC3:
        return "VEC3";
      case TINYGLTF_TYPE_VEC4:
        return "VEC4";
      case TINYGLTF_TYPE_MAT2:
        return "MAT2";
      case TINYGLTF_TYPE_MAT3:
        return "MAT3";
      case TINYGLTF_TYPE_MAT4:
        return "MAT4";
      default:
        return "unknown (" + std::to_string(type) + ")";
    }
  }

  static std::string component_type_name(int component_type) {
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return "BYTE";
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return "UNSIGNED_BYTE";
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return "SHORT";
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return "UNSIGNED_SHORT";
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return "UNSIGNED_INT";
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return "FLOAT";
      default:
        return "unknown (" + std::to_string(component_type) + ")";
    }
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  LoadedScene& scene_;
};

// ---------------------------------------------------------------------------------------------
// Scene graph.

std::string coordinates(const glm::dvec3& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", p.x, p.y, p.z);
  return text;
}

bool all_finite(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

class SceneBuilder {
 public:
  SceneBuilder(const std::string& path, const tinygltf::Model& model, LoadedScene& scene)
      : path_(path), model_(model), scene_(scene), reader_(path, model, scene) {}

  void add_root(int node_index) { visit_tree(node_index); }

 private:
  // Local transform of a node: its matrix, or T * R * S (glTF 2.0, 3.5.3).
  glm::dmat4 local_transform(const tinygltf::Node& node, const std::string& node_path) {
    auto require_finite = [&](const std::vector<double>& values, const char* property) {
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
          throw InputError(path_, node_path + "." + property + "[" + std::to_string(i) + "]",
                           "is not finite");
        }
      }
    };
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) {
        throw InputError(path_, node_path + ".matrix", "must have 16 elements");
      }
      require_finite(node.matrix, "matrix");
      if (!node.translation.empty() || !node.rotation.empty() || !node.scale.empty()) {
        scene_.warnings.push_back(path_ + ": " + node_path +
                                  ": has both matrix and TRS properties; the matrix is used");
      }
      glm::dmat4 m(1.0);
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
      }
      if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
        throw InputError(path_, node_path + ".matrix", "is not affine (last row must be 0 0 0 1)");
      }
      return m;
    }
    glm::dvec3 translation(0.0), scale(1.0);
    glm::dquat rotation(1.0, 0.0, 0.0, 0.0);  // w, x, y, z
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) {
        throw InputError(path_, node_path + ".translation", "must have 3 elements");
      }
      require_finite(node.translation, "translation");
      translation = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) {
        throw InputError(path_, node_path + ".rotation", "must have 4 elements");
      }
      require_finite(node.rotation, "rotation");
      // glTF stores x, y, z, w.
      rotation = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      const double length = glm::length(rotation);
      if (length == 0.0) throw InputError(path_, node_path + ".rotation", "is a zero quaternion");
      rotation = rotation / length;
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3)
        throw InputError(path_, node_path + ".scale", "must have 3 elements");
      require_finite(node.scale, "scale");
      scale = glm::dvec3(node.scale[0], node.scale[1], node.scale[2]);
    }
    glm::dmat4 m = glm::mat4_cast(rotation);
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::dvec4(translation, 1.0);
    return m;
  }

  // Depth-first in the file's child order, with an explicit stack: a chain of 20,000 nodes
  // overflowed the call stack when this recursed (and copied the ancestor list per level, 426 MB
  // at depth 10,000). Memory is linear in the node count: one frame per level of the current
  // path and one on-path flag per node for the cycle check.
  void visit_tree(int root) {
    if (on_path_.empty()) {
      on_path_.assign(model_.nodes.size(), 0);
      visited_.assign(model_.nodes.size(), 0);
    }
    struct Frame {
      int node;
      glm::dmat4 world;
      int singular;  // the nearest node at or above this one with a singular transform, or -1
      std::size_t next_child;
    };
    std::vector<Frame> path;
    auto enter = [&](int node_index, const glm::dmat4& parent, int singular) {
      const glm::dmat4 world = place_node(node_index, parent, singular);
      on_path_[static_cast<std::size_t>(node_index)] = 1;
      path.push_back({node_index, world, singular, 0});
    };
    enter(root, glm::dmat4(1.0), -1);
    while (!path.empty()) {
      Frame& frame = path.back();
      const auto& children = model_.nodes[static_cast<std::size_t>(frame.node)].children;
      if (frame.next_child == children.size()) {
        on_path_[static_cast<std::size_t>(frame.node)] = 0;
        path.pop_back();
        continue;
      }
      const int child = children[frame.next_child++];
      const glm::dmat4 world = frame.world;  // `frame` dies when enter() grows `path`
      enter(child, world, frame.singular);
    }
  }

  // Checks one node reached below `parent` and adds its mesh and light; returns its world
  // transform. `singular` (in/out) is the nearest ancestor, or this node, whose linear part is
  // singular: meshes and lights below it are an error, empty subtrees are harmless.
  glm::dmat4 place_node(int node_index, const glm::dmat4& parent, int& singular) {
    const std::string node_path = "nodes[" + std::to_string(node_index) + "]";
    if (node_index < 0 || static_cast<std::size_t>(node_index) >= model_.nodes.size()) {
      throw InputError(
          path_, node_path,
          "node index out of range (" + std::to_string(model_.nodes.size()) + " nodes)");
    }
    const auto index = static_cast<std::size_t>(node_index);
    if (on_path_[index]) {
      throw InputError(path_, node_path, "is its own ancestor (cycle in the node hierarchy)");
    }
    if (visited_[index]) {
      throw InputError(path_, node_path,
                       "is reached twice (a node may have one parent and appear in one scene "
                       "only)");
    }
    visited_[index] = 1;
    const tinygltf::Node& node = model_.nodes[index];
    const glm::dmat4 local = local_transform(node, node_path);
    const double local_determinant = glm::determinant(glm::dmat3(local));
    if (singular < 0 && !(std::isfinite(local_determinant) && local_determinant != 0.0)) {
      singular = node_index;
    }
    const glm::dmat4 world = parent * local;
    if (!all_finite(world)) {
      throw InputError(path_, node_path, "world transform overflows (non-finite entries)");
    }
    const bool has_light = node.extensions.count("KHR_lights_punctual") > 0;
    if ((node.mesh >= 0 || has_light) && singular >= 0) {
      const tinygltf::Node& culprit = model_.nodes[static_cast<std::size_t>(singular)];
      throw InputError(
          path_,
          "nodes[" + std::to_string(singular) + "]" +
              (culprit.matrix.empty() ? ".scale" : ".matrix"),
          "singular transform (zero determinant) above the mesh or light of " + node_path);
    }
    if ((node.mesh >= 0 || has_light) && !(std::isfinite(glm::determinant(glm::dmat3(world))) &&
                                           glm::determinant(glm::dmat3(world)) != 0.0)) {
      throw InputError(path_, node_path, "world transform is singular (zero determinant)");
    }
    if (node.mesh >= 0) add_mesh_instance(node_index, node, world);
    if (has_light) add_light(node_index, node, world);
    return world;
  }

  void add_mesh_instance(int node_index, const tinygltf::Node& node, const glm::dmat4& world) {
    const std::string node_path = "nodes[" + std::to_string(node_index) + "]";
    if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
      throw InputError(path_, node_path + ".mesh",
                       "mesh " + std::to_string(node.mesh) + " is out of range (" +
                           std::to_string(model_.meshes.size()) + " meshes)");
    }
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(node.mesh)];
    const std::string mesh_path = "meshes[" + std::to_string(node.mesh) + "]";
    if (node.skin >= 0) {
      scene_.warnings.push_back(path_ + ": " + node_path +
                                ": skinned mesh: the bind pose under the node transform is used");
    }
    // A negative determinant mirrors: glTF then defines front faces as clockwise, so the winding
    // is flipped to keep counter-clockwise front faces in world space.
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    const auto mesh_id = static_cast<std::uint32_t>(scene_.meshes.size());
    const std::size_t first_triangle = scene_.triangles.size();

    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      const std::string primitive_path = mesh_path + ".primitives[" + std::to_string(p) + "]";
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        scene_.warnings.push_back(path_ + ": " + primitive_path + ": mode " +
                                  std::to_string(primitive.mode) +
                                  " is not TRIANGLES (4); the primitive is skipped");
        continue;
      }
      if (!primitive.targets.empty() && (std::any_of(mesh.weights.begin(), mesh.weights.end(),
                                                     [](double w) { return w != 0.0; }) ||
                                         std::any_of(node.weights.begin(), node.weights.end(),
                                                     [](double w) { return w != 0.0; }))) {
        scene_.warnings.push_back(path_ + ": " + primitive_path +
                                  ": morph target weights are ignored; the base shape is used");
      }
      const auto position_it = primitive.attributes.find("POSITION");
      if (position_it == primitive.attributes.end()) {
        throw InputError(path_, primitive_path + ".attributes", "has no POSITION");
      }
      const std::string positions_user = primitive_path + ".attributes.POSITION";
      const std::vector<float> positions = reader_.read<float>(
          position_it->second, positions_user, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
      const std::size_t vertex_count = positions.size() / 3;
      std::vector<glm::vec3> world_positions(vertex_count);
      for (std::size_t v = 0; v < vertex_count; ++v) {
        const glm::dvec3 local(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
        if (!std::isfinite(local.x) || !std::isfinite(local.y) || !std::isfinite(local.z)) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "vertex " + std::to_string(v) + " is not finite");
        }
        const glm::dvec3 placed = glm::dvec3(world * glm::dvec4(local, 1.0));
        world_positions[v] = glm::vec3(placed);
        if (!std::isfinite(world_positions[v].x) || !std::isfinite(world_positions[v].y) ||
            !std::isfinite(world_positions[v].z)) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "vertex " + std::to_string(v) + " leaves float range under " +
                               node_path + "'s world transform");
        }
        const double largest =
            std::max({std::fabs(placed.x), std::fabs(placed.y), std::fabs(placed.z)});
        if (largest > max_scene_coordinate) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "vertex " + std::to_string(v) + " lies at " + coordinates(placed) +
                               " under " + node_path +
                               "'s world transform, beyond 1e30 (the largest coordinate a case "
                               "accepts)");
        }
      }

      std::vector<std::uint32_t> indices;
      const std::string indices_user = primitive_path + ".indices";
      if (primitive.indices >= 0) {
        indices = reader_.read<std::uint32_t>(
            primitive.indices, indices_user, TINYGLTF_TYPE_SCALAR,
            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
        for (std::size_t i = 0; i < indices.size(); ++i) {
          if (indices[i] >= vertex_count) {
            throw InputError(path_, accessor_element(indices_user, primitive.indices),
                             "index " + std::to_string(indices[i]) + " at position " +
                                 std::to_string(i) + " is out of range for " +
                                 std::to_string(vertex_count) + " vertices");
          }
        }
        if (indices.size() % 3 != 0) {
          throw InputError(
              path_, accessor_element(indices_user, primitive.indices),
              "count " + std::to_string(indices.size()) + " is not a multiple of 3 (TRIANGLES)");
        }
      } else {
        if (vertex_count % 3 != 0) {
          throw InputError(path_, accessor_element(positions_user, position_it->second),
                           "count " + std::to_string(vertex_count) +
                               " is not a multiple of 3 (non-indexed TRIANGLES)");
        }
        indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
      }
      for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
        const glm::vec3& a = world_positions[indices[i]];
        const glm::vec3& b = world_positions[indices[i + 1]];
        const glm::vec3& c = world_positions[indices[i + 2]];
        scene_.triangles.push_back(mirrored ? Triangle{a, c, b, mesh_id}
                                            : Triangle{a, b, c, mesh_id});
      }
    }

    if (scene_.triangles.size() == first_triangle) {
      scene_.warnings.push_back(path_ + ": " + node_path + " (" + mesh_path +
                                "): no triangles; the mesh instance is skipped");
      return;
    }
    Mesh instance;
    instance.name = (node.name.empty() ? node_path : node.name) + "/" +
                    (mesh.name.empty() ? mesh_path : mesh.name);
    instance.closed =
        is_closed_surface(std::span<const Triangle>(scene_.triangles).subspan(first_triangle));
    scene_.meshes.push_back(std::move(instance));
  }

  void add_light(int node_index, const tinygltf::Node& node, const glm::dmat4& world) {
    const std::string node_path = "nodes[" + std::to_string(node_index) + "]";
    const tinygltf::Value& reference = node.extensions.at("KHR_lights_punctual");
    const std::string reference_path = node_path + ".extensions.KHR_lights_punctual.light";
    if (!reference.Has("light") || !reference.Get("light").IsNumber()) {
      throw InputError(path_, reference_path, "is missing");
    }
    const int light_index = reference.Get("light").GetNumberAsInt();
    if (light_index < 0 || static_cast<std::size_t>(light_index) >= model_.lights.size()) {
      throw InputError(path_, reference_path,
                       "light " + std::to_string(light_index) + " is out of range (" +
                           std::to_string(model_.lights.size()) + " lights)");
    }
    const tinygltf::Light& light = model_.lights[static_cast<std::size_t>(light_index)];
    const std::string light_path =
        "extensions.KHR_lights_punctual.lights[" + std::to_string(light_index) + "]";
    // Lights sit at the node's origin and shine along its local -Z (KHR_lights_punctual).
    const auto position = glm::vec3(glm::dvec3(world[3]));
    const glm::dvec3 axis = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double axis_length = glm::length(axis);
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z)) {
      throw InputError(path_, node_path, "light position leaves float range");
    }
    if (!(axis_length > 0.0) || !std::isfinite(axis_length)) {
      throw InputError(path_, node_path, "light direction is degenerate under the node transform");
    }
    const auto emission = glm::vec3(axis / axis_length);
    const bool has_range = light.range > 0.0;
    if (light.range < 0.0 || !std::isfinite(light.range)) {
      throw InputError(path_, light_path + ".range",
                       "must be positive and finite, is " + std::to_string(light.range));
    }
    if (light.type == "directional") {
      ShadowLight shadow_light;
      shadow_light.kind = ShadowLightKind::directional;
      shadow_light.direction = -emission;  // from the scene towards the light
      scene_.shadow_lights.push_back(shadow_light);
    } else if (light.type == "point") {
      if (has_range) {
        RangedLight ranged;
        ranged.kind = RangedLightKind::sphere;
        ranged.centre = position;
        ranged.range = static_cast<float>(light.range);
        scene_.ranged_lights.push_back(ranged);
      } else {
        ShadowLight shadow_light;
        shadow_light.kind = ShadowLightKind::point;
        shadow_light.position = position;
        scene_.shadow_lights.push_back(shadow_light);
      }
    } else if (light.type == "spot") {
      const double outer = light.spot.outerConeAngle;
      if (!(outer > 0.0 && outer <= glm::pi<double>() / 2.0)) {
        throw InputError(path_, light_path + ".spot.outerConeAngle",
                         "must be in (0, pi/2], is " + std::to_string(outer));
      }
      if (!has_range) {
        // Light assignment needs a bounded volume and the shadow oracles have no cone: a spot
        // light without range has no meaning for either, so it is left out, loudly.
        scene_.warnings.push_back(path_ + ": " + light_path +
                                  ": spot light without range is skipped (light assignment "
                                  "needs a finite range)");
        return;
      }
      RangedLight ranged;
      ranged.kind = RangedLightKind::spot;
      ranged.centre = position;
      ranged.range = static_cast<float>(light.range);
      ranged.direction = emission;
      ranged.cone_half_angle = static_cast<float>(outer);
      scene_.ranged_lights.push_back(ranged);
    } else {
      throw InputError(path_, light_path + ".type",
                       "'" + light.type + "' is not point, directional or spot");
    }
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  LoadedScene& scene_;
  ModelReader reader_;
  std::vector<char> on_path_, visited_;  // per node
};

LoadedScene load_gltf_checked(const std::string& path) {
  const std::vector<unsigned char> bytes = read_file_bytes(path);
  const bool binary = is_glb(bytes);
  if (!binary && has_glb_extension(path)) {
    // Parsed as JSON it would only say "syntax error at byte 1".
    throw InputError(path, "GLB header", "not a GLB file (magic " + magic_text(bytes) + ")");
  }
  const std::string json_text =
      binary ? glb_json_chunk(path, bytes) : std::string(bytes.begin(), bytes.end());
  // tinygltf converts the JSON recursively (extras nested 100,000 deep overflowed the stack).
  check_json_nesting(json_text, path, binary ? "GLB JSON chunk" : "JSON");

  LoadedScene scene;
  Json root;
  try {
    root = Json::parse(json_text);
  } catch (const Json::exception& e) {
    throw InputError(path, binary ? "GLB JSON chunk" : "JSON", e.what());
  }
  SchemaCheck schema;
  check_gltf_schema(schema, root);
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

  SceneBuilder builder(path, model, scene);
  if (!model.scenes.empty()) {
    int scene_index = model.defaultScene;
    if (scene_index < 0) scene_index = 0;
    if (static_cast<std::size_t>(scene_index) >= model.scenes.size()) {
      throw InputError(path, "scene",
                       std::to_string(scene_index) + " is out of range (" +
                           std::to_string(model.scenes.size()) + " scenes)");
    }
    for (const int root_node : model.scenes[static_cast<std::size_t>(scene_index)].nodes) {
      builder.add_root(root_node);
    }
  } else {
    // No scene at all: every node without a parent is a root (glTF leaves this to the loader).
    std::vector<bool> has_parent(model.nodes.size(), false);
    for (const auto& node : model.nodes) {
      for (const int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < model.nodes.size()) {
          has_parent[static_cast<std::size_t>(child)] = true;
        }
      }
    }
    if (!model.nodes.empty()) {
      scene.warnings.push_back(path + ": scenes: none; every root node is loaded");
    }
    for (std::size_t n = 0; n < model.nodes.size(); ++n) {
      if (!has_parent[n]) builder.add_root(static_cast<int>(n));
    }
  }
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
