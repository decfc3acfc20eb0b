#pragma once
// glTF 2.0 scenes (.gltf, .glb) through tinygltf, validated here: tinygltf checks JSON syntax
// and little else.
#include <string>

#include "shadowcts/scene_file.h"

namespace shadowcts {

// The default scene (scene 0 when none is marked default) with node transforms applied in double
// precision and rounded to float. One Mesh per instantiated glTF mesh, named "<node>/<mesh>".
// KHR_lights_punctual lights attached to the scene's nodes become shadow lights (point without
// range, directional) or ranged lights (point with range, spot with range). Throws InputError
// naming the file and the glTF element (e.g. "meshes[2].primitives[0].indices (accessor 5)").
LoadedScene load_gltf_file(const std::string& path);

}  // namespace shadowcts
