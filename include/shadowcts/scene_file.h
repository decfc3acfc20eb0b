#pragma once
// Scene files: glTF 2.0 (.gltf/.glb, tinygltf) and OBJ/OFF/PLY/STL (OpenMesh).
#include <string>
#include <vector>

#include "shadowcts/case.h"

namespace shadowcts {

struct LoadedScene {
  std::vector<Mesh> meshes;
  std::vector<Triangle> triangles;         // world space; Triangle::mesh indexes `meshes`
  std::vector<ShadowLight> shadow_lights;  // KHR_lights_punctual point (no range) / directional
  std::vector<RangedLight> ranged_lights;  // KHR_lights_punctual point with range / spot
  std::vector<std::string> warnings;       // problems that still left valid geometry
};

// The largest absolute coordinate a case accepts (validate() refuses larger ones: float32
// differences of such coordinates overflow). Loaders refuse larger vertices themselves, so that
// the message names the file and the vertex rather than the manifest.
inline constexpr double max_scene_coordinate = 1e30;

// Dispatches on the extension. Throws InputError naming the file and element on malformed input.
LoadedScene load_scene_file(const std::string& path);

}  // namespace shadowcts
