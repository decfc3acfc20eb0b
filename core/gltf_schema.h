#pragma once
// The glTF JSON checked against the parts of the schema the loader relies on, before tinygltf
// reads it: tinygltf silently ignores properties of the wrong type (a "primitives" object instead
// of an array loads as a mesh without primitives). A wrong type in anything that defines geometry
// or lights is an error; in anything else (names, materials, textures, foreign extensions) a
// warning, and the geometry still loads.
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowcts {

struct GltfSchemaReport {
  std::vector<std::pair<std::string, std::string>> errors;  // element, problem
  std::vector<std::string> warnings;                        // "element: problem"
};

GltfSchemaReport check_gltf_schema(const nlohmann::json& root);

// Extensions a file may require without changing what its triangles and lights are.
bool extension_keeps_geometry(const std::string& name);

}  // namespace shadowcts
