#pragma once
// OBJ, OFF, PLY and STL meshes through OpenMesh's readers.
#include <string>

#include "shadowcts/scene_file.h"

namespace shadowcts {

// One Mesh named after the file stem. OpenMesh's reader feeds an importer that keeps every face as
// the file gives it (non-manifold ones included) and splits a polygon into the fan (0, i, i + 1).
// Throws InputError naming the file and the element (vertex, face) for unreadable, empty or
// non-finite input; faces with a repeated vertex (no area) are dropped and reported in
// LoadedScene::warnings. Mesh::closed is is_closed_surface() of the triangles.
LoadedScene load_mesh_file(const std::string& path);

}  // namespace shadowcts
