#pragma once
// The body of the scene-file fuzz targets (one target per format, so that each takes the real
// files of that format as seeds).
#include <cstddef>
#include <cstdint>

namespace shadowcts::fuzzing {

// Loads `data` as a scene file with `extension` (".obj", ".glb", ...). The property: the loader
// either throws InputError or returns geometry that makes a valid case (finite coordinates,
// mesh ids in range, lights valid); anything else (another exception, a crash, a sanitizer
// report, a leak) is a finding.
void fuzz_scene_file(const std::uint8_t* data, std::size_t size, const char* extension);

}  // namespace shadowcts::fuzzing
