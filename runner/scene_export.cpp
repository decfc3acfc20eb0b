#include "scene_export.h"

#include <tiny_gltf.h>

#include <array>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "case_round_trip.h"
#include "interrupt_cleanup.h"
#include "manifest_lights.h"
#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/gbuffer_exr.h"
#include "shadowcts/manifest_direction.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

constexpr double pi = 3.14159265358979323846;

Json vec(const glm::vec3& v) {
  return Json::array({double(v.x), double(v.y), double(v.z)});
}

// Appends raw bytes to the model's one buffer as a buffer view + accessor; returns the accessor.
int add_accessor(tinygltf::Model& model, const void* data, std::size_t bytes, std::size_t count,
                 int type, int component, int target) {
  std::vector<unsigned char>& buffer = model.buffers[0].data;
  while (buffer.size() % 4) buffer.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buffer.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* begin = static_cast<const unsigned char*>(data);
  buffer.insert(buffer.end(), begin, begin + bytes);
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = int(model.bufferViews.size() - 1);
  accessor.count = count;
  accessor.type = type;
  accessor.componentType = component;
  model.accessors.push_back(accessor);
  return int(model.accessors.size() - 1);
}

// One node and mesh per case mesh, identity transforms so positions load back unchanged; vertices
// shared by bit pattern so that closed meshes load back closed (the loader decides closedness from
// the indices).
void add_mesh(tinygltf::Model& model, const Case& c, std::uint32_t mesh_id) {
  std::vector<float> positions;
  std::vector<std::uint32_t> indices;
  std::map<std::array<std::uint32_t, 3>, std::uint32_t> index_of;
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const Triangle& t : c.triangles) {
    if (t.mesh != mesh_id) continue;
    for (const glm::vec3& p : {t.v0, t.v1, t.v2}) {
      const std::array<std::uint32_t, 3> key{std::bit_cast<std::uint32_t>(p.x),
                                             std::bit_cast<std::uint32_t>(p.y),
                                             std::bit_cast<std::uint32_t>(p.z)};
      auto [it, inserted] = index_of.try_emplace(key, std::uint32_t(positions.size() / 3));
      if (inserted) {
        positions.insert(positions.end(), {p.x, p.y, p.z});
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
      indices.push_back(it->second);
    }
  }
  if (indices.empty()) return;  // the loader skips meshes without triangles
  const int position_accessor =
      add_accessor(model, positions.data(), positions.size() * sizeof(float), positions.size() / 3,
                   TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TARGET_ARRAY_BUFFER);
  model.accessors[std::size_t(position_accessor)].minValues = {lo.x, lo.y, lo.z};
  model.accessors[std::size_t(position_accessor)].maxValues = {hi.x, hi.y, hi.z};
  const int index_accessor =
      add_accessor(model, indices.data(), indices.size() * sizeof(std::uint32_t), indices.size(),
                   TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                   TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = position_accessor;
  primitive.indices = index_accessor;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.name = c.meshes[mesh_id].name;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = c.meshes[mesh_id].name;
  node.mesh = int(model.meshes.size() - 1);
  model.nodes.push_back(node);
  model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
}

// Rotation taking the node's -Z (where KHR_lights_punctual lights shine) onto `axis`.
std::vector<double> rotation_onto(const glm::dvec3& axis) {
  const glm::dvec3 a(0.0, 0.0, -1.0), b = glm::normalize(axis);
  const double w = 1.0 + glm::dot(a, b);
  if (w < 1e-12) return {1.0, 0.0, 0.0, 0.0};  // opposite: half a turn about x
  const glm::dvec3 v = glm::cross(a, b);
  const double n = std::sqrt(w * w + glm::dot(v, v));
  return {v.x / n, v.y / n, v.z / n, w / n};
}

void add_light(tinygltf::Model& model, tinygltf::Light light, const glm::vec3* position,
               const glm::vec3* shine) {
  light.color = {1.0, 1.0, 1.0};
  light.intensity = 1.0;
  model.lights.push_back(light);
  tinygltf::Node node;
  node.name = "light" + std::to_string(model.lights.size() - 1);
  if (position) node.translation = {position->x, position->y, position->z};
  if (shine) node.rotation = rotation_onto(glm::dvec3(*shine));
  tinygltf::Value::Object reference;
  reference["light"] = tinygltf::Value(int(model.lights.size() - 1));
  node.extensions["KHR_lights_punctual"] = tinygltf::Value(reference);
  model.nodes.push_back(node);
  model.scenes[0].nodes.push_back(int(model.nodes.size() - 1));
}

tinygltf::Model new_model() {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "shadowcts export";
  model.buffers.resize(1);
  model.scenes.resize(1);
  model.defaultScene = 0;
  return model;
}

void write_glb(const tinygltf::Model& model, const fs::path& path) {
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&model, path.string(), true, true, false, true))
    throw OutputError(path.string(), "cannot be written");
}

void write_json(const Json& j, const fs::path& path) {
  std::ofstream file(path);
  file << j.dump(2) << "\n";
  if (!file) throw OutputError(path.string(), "cannot be written");
}

}  // namespace

void export_case(const Case& original, const std::optional<ViewSamples>& given_samples,
                 const std::string& dir_text, std::ostream& out) {
  validate(original);
  const fs::path dir(dir_text);
  std::error_code ec;
  if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec)))
    throw UsageError("--out " + dir_text + ": exists and is not an empty folder");
  const InterruptCleanup unfinished = InterruptCleanup::remove_path(dir);
  fs::create_directories(dir, ec);
  if (ec) throw OutputError(dir_text, "cannot create folder: " + ec.message());
  try {
    // The case as case.json gives it back: the loader normalizes directions, so they are written
    // as directions that normalizing leaves alone (an ulp from the fixture's at most).
    Case c = original;
    if (c.light && c.light->kind != ShadowLightKind::point)
      c.light->direction = manifest_stable_direction(c.light->direction);
    for (RangedLight& r : c.ranged_lights)
      if (r.kind == RangedLightKind::spot) r.direction = manifest_stable_direction(r.direction);

    tinygltf::Model casters = new_model(), receivers = new_model();
    // The triangles in the order the manifest loads them (casters' meshes, then receivers'), and
    // where each of the case's triangles lands; from then on c is the case case.json gives back.
    std::vector<Triangle> load_order;
    load_order.reserve(c.triangles.size());
    std::vector<std::uint32_t> new_index(c.triangles.size(), no_receiver);
    for (bool caster : {true, false})
      for (std::uint32_t m = 0; m < c.meshes.size(); ++m) {
        if (c.meshes[m].caster != caster) continue;
        add_mesh(caster ? casters : receivers, c, m);
        for (std::size_t t = 0; t < c.triangles.size(); ++t)
          if (c.triangles[t].mesh == m) {
            new_index[t] = std::uint32_t(load_order.size());
            load_order.push_back(c.triangles[t]);
          }
      }
    c.triangles = std::move(load_order);
    casters.extensionsUsed.push_back("KHR_lights_punctual");
    if (c.light) {
      tinygltf::Light light;
      light.type = c.light->kind == ShadowLightKind::point ? "point" : "directional";
      const glm::vec3 shine = -c.light->direction;
      add_light(casters, light,
                c.light->kind == ShadowLightKind::point ? &c.light->position : nullptr,
                c.light->kind == ShadowLightKind::point ? nullptr : &shine);
    }
    for (const RangedLight& r : c.ranged_lights) {
      tinygltf::Light light;
      light.range = r.range;
      if (r.kind == RangedLightKind::spot) {
        light.type = "spot";
        // glTF spots open at most pi/2: wider cones are only in case.json.
        if (r.cone_half_angle > pi / 2) continue;
        light.spot.outerConeAngle = r.cone_half_angle;
        light.spot.innerConeAngle = 0.0;
      } else {
        light.type = "point";
      }
      add_light(casters, light, &r.centre,
                r.kind == RangedLightKind::spot ? &r.direction : nullptr);
    }
    write_glb(casters, dir / "scene.glb");
    Json scenes = Json::array({{{"file", "scene.glb"}}});
    if (!receivers.meshes.empty()) {
      write_glb(receivers, dir / "receivers.glb");
      scenes.push_back({{"file", "receivers.glb"}, {"caster", false}});
    }

    Json manifest;
    manifest["name"] = c.name;
    manifest["scenes"] = scenes;
    const Camera& cam = c.camera;
    manifest["camera"] = {{"position", vec(cam.position)},
                          {"target", vec(cam.target)},
                          {"up", vec(cam.up)},
                          {"fov_y_degrees", cam.vertical_fov_degrees},
                          {"near", cam.near_plane},
                          {"far", cam.far_plane},
                          {"width", cam.width},
                          {"height", cam.height}};
    if (c.light) manifest["light"] = shadow_light_json(*c.light);
    manifest["ranged_lights"] = ranged_lights_json(c.ranged_lights);
    manifest["parameters"] = {{"eps_rel", c.parameters.eps_rel},
                              {"repeats", c.parameters.repeats},
                              {"threads", c.parameters.threads},
                              {"seed", c.parameters.seed}};
    manifest["gbuffer"] = "gbuffer.exr";
    const fs::path manifest_path = dir / "case.json";
    write_json(manifest, manifest_path);

    // The case's own samples (their receivers renumbered to the load order), or the camera's.
    ViewSamples samples;
    if (given_samples) {
      samples = *given_samples;
      for (ViewSample& s : samples.samples)
        if (s.receiver != no_receiver) s.receiver = new_index[s.receiver];
    } else {
      samples = generate_view_samples(c);
    }
    write_gbuffer_exr((dir / "gbuffer.exr").string(), samples);

    // The engine renders what case.json loads: it must be this case, bit for bit.
    const std::string difference =
        first_difference(c, samples, load_case_with_gbuffer(manifest_path.string()));
    if (!difference.empty())
      throw std::logic_error("export: " + manifest_path.string() +
                             " loads back differently: " + difference);
    out << "wrote " << (dir / "scene.glb").string()
        << (receivers.meshes.empty() ? "" : ", " + (dir / "receivers.glb").string()) << ", "
        << manifest_path.string() << " and " << (dir / "gbuffer.exr").string() << ": "
        << c.triangles.size() << " triangles in " << casters.meshes.size() + receivers.meshes.size()
        << " meshes, " << samples.width << "x" << samples.height << " G-buffer"
        << (given_samples ? " of the case's own samples" : "") << "\n";
  } catch (...) {
    fs::remove_all(dir, ec);  // all or nothing
    throw;
  }
}

}  // namespace shadowcts
