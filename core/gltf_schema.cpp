#include "gltf_schema.h"

#include "json_limits.h"

#include <string>

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

void check_root(SchemaCheck& check, const Json& root) {
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

}  // namespace

GltfSchemaReport check_gltf_schema(const nlohmann::json& root) {
  SchemaCheck check;
  check_root(check, root);
  return {std::move(check.errors), std::move(check.warnings)};
}

bool extension_keeps_geometry(const std::string& name) {
  return name == "KHR_lights_punctual" || name.starts_with("KHR_materials_") ||
         name.starts_with("KHR_texture_") || name == "EXT_texture_webp" ||
         name == "KHR_mesh_quantization";  // positions must still be FLOAT: checked per accessor
}

}  // namespace shadowcts
