// libFuzzer target: arbitrary bytes as a JSON case manifest through load_case_manifest. The
// property: InputError, or a case that passes validate(); never a crash, leak or sanitizer
// report. The scratch folder holds a one-triangle OBJ, "tri.obj", so that manifests that name
// it (the seeds do) reach the scene-file branch, placements and lights.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "support/temp_input_file.h"

namespace {

// Generators build what they are asked for: a valid manifest may ask for 100 M triangles. The
// fuzzer explores the parser, so it leaves out manifests that ask for more than this.
constexpr double max_generated_triangles = 20000;

bool asks_for_a_large_scene(const std::uint8_t* data, std::size_t size) {
  const auto json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (!json.is_object() || !json.contains("scene") || !json["scene"].is_object()) return false;
  const auto& scene = json["scene"];
  if (scene.contains("triangles") && scene["triangles"].is_number() &&
      scene["triangles"].get<double>() > max_generated_triangles)
    return true;
  // Model fixtures load fixed-size files of up to ~100k triangles: slow, not interesting here.
  return scene.contains("generator") && scene["generator"].is_string() &&
         scene["generator"].get<std::string>().starts_with("model.");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts;
  static const bool scene_written = [] {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    fuzzing::write_scratch_file("tri.obj", reinterpret_cast<const std::uint8_t*>(obj.data()),
                                obj.size());
    return true;
  }();
  (void)scene_written;
  if (asks_for_a_large_scene(data, size)) return -1;  // -1: not added to the corpus
  const std::string path = fuzzing::write_scratch_file("case.json", data, size);
  try {
    const Case c = load_case_manifest(path);
    validate(c);  // the loader promises a validated case: this must not throw
  } catch (const InputError&) {
  }
  return 0;
}
