#pragma once
// The glTF scene graph: node transforms in double precision (cycles and shared subtrees
// reported), one Mesh per instantiated glTF mesh named "<node>/<mesh>", and KHR_lights_punctual
// lights as shadow or ranged lights.
#include <string>

#include <tiny_gltf.h>

#include "shadowcts/scene_file.h"

namespace shadowcts {

// Adds the model's default scene (scene 0 when none is marked default; every root node when the
// file has no scene) to `scene`. Throws InputError naming the file and the glTF element.
void add_gltf_scene(const std::string& path, const tinygltf::Model& model, LoadedScene& scene);

}  // namespace shadowcts
