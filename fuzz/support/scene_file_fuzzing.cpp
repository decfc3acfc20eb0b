#include "scene_file_fuzzing.h"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "shadowcts/errors.h"
#include "shadowcts/scene_file.h"
#include "temp_input_file.h"

namespace shadowcts::fuzzing {

void fuzz_scene_file(const std::uint8_t* data, std::size_t size, const char* extension) {
  const std::string path = write_scratch_file(std::string("input") + extension, data, size);
  LoadedScene scene;
  try {
    scene = load_scene_file(path);
  } catch (const InputError&) {
    return;  // a clear error is a correct answer to malformed input
  }
  if (scene.triangles.empty()) return;
  // What the loader returns must pass validation once a camera and a light are added: the
  // loader, not validate(), is responsible for rejecting NaN, Inf and dangling mesh ids.
  Case c;
  c.source = path;
  c.meshes = scene.meshes;
  c.triangles = scene.triangles;
  c.ranged_lights = scene.ranged_lights;
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = {0.0f, 1.0f, 0.0f};
  c.light = scene.shadow_lights.empty() ? light : scene.shadow_lights.front();
  c.camera.position = {0.0f, 0.0f, 0.0f};
  c.camera.target = {0.0f, 0.0f, -1.0f};
  try {
    validate(c);
  } catch (const InputError& e) {
    // Coordinates beyond 1e30 are a property of the case, not a loader failure.
    if (c.scale() > 1e30) return;
    std::fprintf(stderr, "loader returned an invalid case: %s\n", e.what());
    std::abort();
  }
}

}  // namespace shadowcts::fuzzing
