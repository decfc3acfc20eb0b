// libFuzzer target: arbitrary bytes as a .ply file through load_scene_file (OpenMesh and the
// project's own checks). Seeds: fuzz/corpus/ply_loader and assimp-testmodels' PLY/ folder.
#include <cstddef>
#include <cstdint>

#include "support/scene_file_fuzzing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  shadowcts::fuzzing::fuzz_scene_file(data, size, ".ply");
  return 0;
}
