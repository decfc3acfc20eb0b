// libFuzzer target: arbitrary bytes as a glTF 2.0 file through load_scene_file (tinygltf and
// the project's schema and accessor checks). Inputs that start with the GLB magic "glTF" are
// written as .glb, all others as .gltf, so both parsers get their own seeds. Seeds:
// fuzz/corpus/gltf_loader and the malformed glTF files of assimp-testmodels (wrongTypes,
// SchemaFailures, IndexOutOfRange, MissingBin, ...).
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "support/scene_file_fuzzing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  shadowcts::fuzzing::fuzz_scene_file(data, size, binary ? ".glb" : ".gltf");
  return 0;
}
