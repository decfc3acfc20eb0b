#include "case_reproducer.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "manifest_lights.h"
#include "shadowcts/errors.h"
#include "shadowcts/gbuffer_exr.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

// JSON numbers are written as doubles with round-trip precision, so a float survives exactly.
Json vec3_json(const glm::vec3& v) {
  return Json::array({double(v.x), double(v.y), double(v.z)});
}

void write_binary(const fs::path& path, const std::vector<float>& values) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()),
            static_cast<std::streamsize>(values.size() * sizeof(float)));
  if (!out) throw InputError(path.string(), "file", "cannot be written");
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw InputError(path.string(), "file", "cannot be written");
}

// One glTF file with one node and one non-indexed TRIANGLES primitive.
void write_gltf(const fs::path& gltf_path, const Case& c, std::size_t first, std::size_t end) {
  std::vector<float> positions;
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::size_t i = first; i < end; ++i)
    for (const glm::vec3& v : {c.triangles[i].v0, c.triangles[i].v1, c.triangles[i].v2}) {
      positions.insert(positions.end(), {v.x, v.y, v.z});
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  const fs::path bin_path = fs::path(gltf_path).replace_extension(".bin");
  write_binary(bin_path, positions);
  const std::size_t bytes = positions.size() * sizeof(float);
  const Json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "shadowcts fuzz reproducer"}}},
      {"scene", 0},
      {"scenes", Json::array({{{"nodes", Json::array({0})}}})},
      {"nodes", Json::array({{{"mesh", 0}, {"name", c.meshes[c.triangles[first].mesh].name}}})},
      {"meshes",
       Json::array(
           {{{"primitives", Json::array({{{"attributes", {{"POSITION", 0}}}, {"mode", 4}}})}}})},
      {"accessors", Json::array({{{"bufferView", 0},
                                  {"componentType", 5126},
                                  {"count", positions.size() / 3},
                                  {"type", "VEC3"},
                                  {"min", vec3_json(lo)},
                                  {"max", vec3_json(hi)}}})},
      {"bufferViews", Json::array({{{"buffer", 0}, {"byteLength", bytes}}})},
      {"buffers", Json::array({{{"byteLength", bytes}, {"uri", bin_path.filename().string()}}})},
  };
  write_text(gltf_path, gltf.dump(1));
}

}  // namespace

std::string write_reproducer(const std::string& folder, const Case& c, const ViewSamples& samples) {
  fs::create_directories(folder);
  Json scenes = Json::array();
  // A glTF file per maximal run of one mesh keeps the triangle order, so receiver ids stay valid.
  for (std::size_t first = 0, part = 0; first < c.triangles.size(); ++part) {
    std::size_t end = first;
    while (end < c.triangles.size() && c.triangles[end].mesh == c.triangles[first].mesh) ++end;
    const std::string file = "part" + std::to_string(part) + ".gltf";
    write_gltf(fs::path(folder) / file, c, first, end);
    scenes.push_back({{"file", file}, {"caster", c.meshes[c.triangles[first].mesh].caster}});
    first = end;
  }
  write_gbuffer_exr((fs::path(folder) / "gbuffer.exr").string(), samples);
  const Camera& cam = c.camera;
  Json manifest = {
      {"name", c.name.empty() ? std::string("reproducer") : c.name},
      {"scenes", scenes},
      {"gbuffer", "gbuffer.exr"},
      {"camera",
       {{"position", vec3_json(cam.position)},
        {"target", vec3_json(cam.target)},
        {"up", vec3_json(cam.up)},
        {"fov_y_degrees", double(cam.vertical_fov_degrees)},
        {"near", double(cam.near_plane)},
        {"far", double(cam.far_plane)},
        {"width", cam.width},
        {"height", cam.height}}},
      {"parameters",
       {{"eps_rel", c.parameters.eps_rel},
        {"repeats", c.parameters.repeats},
        {"threads", c.parameters.threads},
        {"seed", c.parameters.seed}}},
  };
  if (c.light) manifest["light"] = shadow_light_json(*c.light);
  if (!c.ranged_lights.empty()) manifest["ranged_lights"] = ranged_lights_json(c.ranged_lights);
  const fs::path manifest_path = fs::path(folder) / "case.json";
  write_text(manifest_path, manifest.dump(2) + "\n");
  return manifest_path.string();
}

}  // namespace shadowcts
