#pragma once
// OBJ, OFF, PLY and STL meshes through OpenMesh.
#include <string>

#include "shadowcts/scene_file.h"

namespace shadowcts {

// One Mesh named after the file stem, triangulated by OpenMesh. Throws InputError naming the file
// and the element (vertex, face) for unreadable, empty or non-finite input; faces OpenMesh had to
// drop or split off (degenerate, non-manifold) are reported in LoadedScene::warnings.
LoadedScene load_mesh_file(const std::string& path);

}  // namespace shadowcts
