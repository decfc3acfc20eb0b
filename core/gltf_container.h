#pragma once
// A .gltf or .glb file's bytes and its JSON text: the GLB container's header and chunk lengths are
// checked here, and a .glb that is not one is named as such (parsed as JSON it would only say
// "syntax error at byte 1").
#include <string>
#include <vector>

namespace shadowcts {

struct GltfContainer {
  std::vector<unsigned char> bytes;  // the whole file
  bool binary = false;               // a GLB container
  std::string json_text;             // the JSON chunk, or the whole .gltf file
};

// Throws InputError naming the file and the part of the container at fault.
GltfContainer read_gltf_container(const std::string& path);

}  // namespace shadowcts
