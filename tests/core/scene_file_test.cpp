// Scene files: every malformed input becomes an InputError naming the file (or a warning when the
// geometry is still valid), real models load, glTF transforms and lights land where they should.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "memory_limited_child.h"
#include "shadowcts/errors.h"
#include "shadowcts/scene_file.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const fs::path assimp_models = SHADOWCTS_ASSIMP_MODELS_DIR;

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            (std::string("shadowcts_scene_file_") + info->test_suite_name() + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& contents) const {
    const fs::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << contents;
    return file;
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The InputError message of loading `path`, or "" (and a test failure) when none is thrown.
std::string load_error(const fs::path& path) {
  try {
    load_scene_file(path.string());
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " loaded without InputError";
  return "";
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void expect_plausible(const LoadedScene& scene, const std::string& what) {
  ASSERT_FALSE(scene.triangles.empty()) << what;
  ASSERT_FALSE(scene.meshes.empty()) << what;
  for (const Triangle& t : scene.triangles) {
    ASSERT_TRUE(finite(t.v0) && finite(t.v1) && finite(t.v2)) << what;
    ASSERT_LT(t.mesh, scene.meshes.size()) << what;
  }
}

bool any_warning_contains(const LoadedScene& scene, const std::string& text) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// ---- the deliberately malformed glTF files of assimp's test models ------------------------

// Per file, by reading it: either the error's element, or the warning that names the problem
// while the box geometry (12 triangles) still loads.
struct MalformedExpectation {
  bool loads;
  std::string text;  // in the error message, or in one warning
};

TEST(GltfMalformed, EveryAssimpFileIsAnErrorOrAWarning) {
  const std::map<std::string, MalformedExpectation> expectations = {
      // "primitives" is an object: the mesh has no geometry.
      {"wrongTypes/badArray.gltf", {false, "meshes[0].primitives"}},
      // Material and texture properties of the wrong type: shadows do not read them.
      {"wrongTypes/badExtension.gltf", {true, "extensions.KHR_texture_transform"}},
      {"wrongTypes/badNumber.gltf", {true, "materials[0].normalTexture.scale"}},
      {"wrongTypes/badObject.gltf", {true, "materials[0].pbrMetallicRoughness"}},
      {"wrongTypes/badString.gltf", {true, "scenes[0].name"}},
      {"wrongTypes/badUint.gltf", {true, "baseColorTexture.index"}},
      // "scene": "hello" (and its buffer file is not there either).
      {"SchemaFailures/sceneWrongType.gltf", {false, ": scene: "}},
      {"IndexOutOfRange/IndexOutOfRange.gltf",
       {false, "meshes[0].primitives[0].indices (accessor 0)"}},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf",
       {false, "meshes[0].primitives[0].indices (accessor 0)"}},
      {"MissingBin/BoxTextured.gltf", {false, "BoxTextured0.bin"}},
  };
  std::size_t seen = 0;
  for (const char* folder : {"wrongTypes", "SchemaFailures", "IndexOutOfRange", "MissingBin"}) {
    for (const auto& entry : fs::directory_iterator(assimp_models / "glTF2" / folder)) {
      if (entry.path().extension() != ".gltf") continue;
      const std::string key = std::string(folder) + "/" + entry.path().filename().string();
      const auto expectation = expectations.find(key);
      ASSERT_NE(expectation, expectations.end()) << "no expectation for " << key;
      ++seen;
      const std::string file = entry.path().string();
      if (expectation->second.loads) {
        const LoadedScene scene = load_scene_file(file);
        expect_plausible(scene, key);
        EXPECT_EQ(scene.triangles.size(), 12u) << key;
        EXPECT_TRUE(scene.meshes[0].closed) << key << ": the box is closed once welded";
        EXPECT_TRUE(any_warning_contains(scene, expectation->second.text))
            << key << ": no warning mentions " << expectation->second.text;
        EXPECT_TRUE(any_warning_contains(scene, file)) << key;
      } else {
        const std::string message = load_error(entry.path());
        EXPECT_NE(message.find(file), std::string::npos) << message;
        EXPECT_NE(message.find(expectation->second.text), std::string::npos) << message;
      }
    }
  }
  EXPECT_EQ(seen, expectations.size());
}

TEST(GltfMalformed, IndexOutOfRangeNamesTheIndex) {
  const std::string message =
      load_error(assimp_models / "glTF2/IndexOutOfRange/IndexOutOfRange.gltf");
  EXPECT_NE(message.find("out of range for 24 vertices"), std::string::npos) << message;
}

TEST(Glb, TruncatedCopyIsAnInputError) {
  const fs::path original = assimp_models / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  std::ifstream in(original, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 1000u);
  const TempDir dir;
  for (const std::size_t keep :
       {bytes.size() / 2, bytes.size() - 1, std::size_t{30}, std::size_t{3}}) {
    const fs::path truncated = dir.write("2CylinderEngine.glb", bytes.substr(0, keep));
    const std::string message = load_error(truncated);
    EXPECT_NE(message.find(truncated.string()), std::string::npos) << message;
  }
}

TEST(Glb, TwoCylinderEngineLoads) {
  const fs::path file = assimp_models / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  const LoadedScene scene = load_scene_file(file.string());
  expect_plausible(scene, file.string());
  std::cout << "2CylinderEngine.glb: " << scene.triangles.size() << " triangles, "
            << scene.meshes.size() << " mesh instances, "
            << std::count_if(scene.meshes.begin(), scene.meshes.end(),
                             [](const Mesh& m) { return m.closed; })
            << " closed\n";
  EXPECT_GT(scene.triangles.size(), 50'000u);
  EXPECT_LT(scene.triangles.size(), 500'000u);
  EXPECT_GT(scene.meshes.size(), 10u);
  // The same file loads the same way twice (deterministic).
  const LoadedScene again = load_scene_file(file.string());
  ASSERT_EQ(again.triangles.size(), scene.triangles.size());
  EXPECT_EQ(std::memcmp(again.triangles.data(), scene.triangles.data(),
                        scene.triangles.size() * sizeof(Triangle)),
            0);
}

// ---- hand-made glTF --------------------------------------------------------------------------

// A glTF document with its binary buffer written beside it as "buffer.bin".
class GltfBuilder {
 public:
  GltfBuilder() {
    doc_ = {{"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", Json::array({{{"nodes", Json::array()}}})},
            {"nodes", Json::array()},
            {"meshes", Json::array()},
            {"accessors", Json::array()},
            {"bufferViews", Json::array()}};
  }

  int add_accessor(const void* data, std::size_t bytes, int component_type, const char* type,
                   std::size_t count) {
    while (bin_.size() % 4 != 0) bin_.push_back('\0');
    const std::size_t offset = bin_.size();
    bin_.append(static_cast<const char*>(data), bytes);
    doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    doc_["accessors"].push_back({{"bufferView", doc_["bufferViews"].size() - 1},
                                 {"componentType", component_type},
                                 {"type", type},
                                 {"count", count}});
    return static_cast<int>(doc_["accessors"].size() - 1);
  }
  int add_positions(const std::vector<float>& xyz) {
    return add_accessor(xyz.data(), xyz.size() * sizeof(float), 5126, "VEC3", xyz.size() / 3);
  }
  int add_indices(const std::vector<std::uint16_t>& indices) {
    return add_accessor(indices.data(), indices.size() * 2, 5123, "SCALAR", indices.size());
  }
  // Positions then indices, in this order (function arguments have no evaluation order).
  int add_indexed_mesh(const std::vector<float>& xyz, const std::vector<std::uint16_t>& indices,
                       const std::string& name) {
    const int positions = add_positions(xyz);
    return add_mesh(positions, add_indices(indices), name);
  }
  int add_mesh(int positions, int indices, const std::string& name) {
    Json primitive = {{"attributes", {{"POSITION", positions}}}};
    if (indices >= 0) primitive["indices"] = indices;
    doc_["meshes"].push_back({{"name", name}, {"primitives", Json::array({primitive})}});
    return static_cast<int>(doc_["meshes"].size() - 1);
  }
  // Adds a node; a root unless some node lists it as a child later.
  int add_node(Json node, bool root = true) {
    doc_["nodes"].push_back(std::move(node));
    const int index = static_cast<int>(doc_["nodes"].size() - 1);
    if (root) doc_["scenes"][0]["nodes"].push_back(index);
    return index;
  }
  int add_light(Json light) {
    auto& lights = doc_["extensions"]["KHR_lights_punctual"]["lights"];
    lights.push_back(std::move(light));
    return static_cast<int>(lights.size() - 1);
  }
  Json& doc() { return doc_; }

  fs::path write(const TempDir& dir, const std::string& name) {
    doc_["buffers"] = Json::array({{{"uri", "buffer.bin"}, {"byteLength", bin_.size()}}});
    dir.write("buffer.bin", bin_);
    return dir.write(name, doc_.dump(2));
  }

 private:
  Json doc_;
  std::string bin_;
};

// A tetrahedron with outward-facing counter-clockwise triangles.
const std::vector<float> tetrahedron_positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
const std::vector<std::uint16_t> tetrahedron_indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};

TEST(GltfHandMade, TetrahedronUnderTranslateAndScaleIsClosed) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "tetra");
  gltf.add_node(
      {{"name", "placed"}, {"mesh", mesh}, {"translation", {1, 2, 3}}, {"scale", {2, 2, 2}}});
  const LoadedScene scene = load_scene_file(gltf.write(dir, "tetra.gltf").string());
  ASSERT_EQ(scene.triangles.size(), 4u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].name, "placed/tetra");
  EXPECT_TRUE(scene.meshes[0].closed);
  // Triangle 3 is (1,2,3) of the tetrahedron: x = (1,0,0) -> (3,2,3).
  EXPECT_EQ(scene.triangles[3].v0, glm::vec3(3, 2, 3));
  EXPECT_EQ(scene.triangles[3].v1, glm::vec3(1, 4, 3));
  EXPECT_EQ(scene.triangles[3].v2, glm::vec3(1, 2, 5));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(GltfHandMade, OpenOrInconsistentTetrahedronIsNotClosed) {
  const TempDir dir;
  GltfBuilder gltf;
  std::vector<std::uint16_t> three_faces(tetrahedron_indices.begin(),
                                         tetrahedron_indices.end() - 3);
  std::vector<std::uint16_t> flipped = tetrahedron_indices;
  std::swap(flipped[10], flipped[11]);
  const int positions = gltf.add_positions(tetrahedron_positions);
  gltf.add_node({{"mesh", gltf.add_mesh(positions, gltf.add_indices(three_faces), "open")}});
  gltf.add_node({{"mesh", gltf.add_mesh(positions, gltf.add_indices(flipped), "flipped")}});
  const LoadedScene scene = load_scene_file(gltf.write(dir, "open.gltf").string());
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_FALSE(scene.meshes[0].closed);
  EXPECT_FALSE(scene.meshes[1].closed);
  EXPECT_EQ(scene.triangles.size(), 7u);
}

TEST(GltfHandMade, ZeroAreaSliverWithRepeatedCornerKeepsATetrahedronClosed) {
  const TempDir dir;
  GltfBuilder gltf;
  std::vector<std::uint16_t> with_sliver = tetrahedron_indices;
  with_sliver.insert(with_sliver.end(), {0, 0, 1});
  gltf.add_node({{"mesh", gltf.add_indexed_mesh(tetrahedron_positions, with_sliver, "m")}});
  const LoadedScene scene = load_scene_file(gltf.write(dir, "sliver.gltf").string());
  EXPECT_EQ(scene.triangles.size(), 5u);
  EXPECT_TRUE(scene.meshes[0].closed);
}

TEST(GltfHandMade, MirroringNodeKeepsCounterClockwiseFrontFaces) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_mesh(gltf.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0}), -1, "tri");
  gltf.add_node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
  const LoadedScene scene = load_scene_file(gltf.write(dir, "mirror.gltf").string());
  ASSERT_EQ(scene.triangles.size(), 1u);
  const Triangle& t = scene.triangles[0];
  const glm::vec3 normal = glm::cross(t.v1 - t.v0, t.v2 - t.v0);
  EXPECT_GT(normal.z, 0.0f) << "front face of the mirrored triangle still faces +z";
  EXPECT_EQ(t.v0, glm::vec3(0, 0, 0));
}

TEST(GltfHandMade, NanPositionIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  std::vector<float> positions = tetrahedron_positions;
  positions[4] = std::numeric_limits<float>::quiet_NaN();  // vertex 1, y
  const int mesh = gltf.add_indexed_mesh(positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}});
  const fs::path file = gltf.write(dir, "nan.gltf");
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("meshes[0].primitives[0].attributes.POSITION (accessor 0)"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("vertex 1 is not finite"), std::string::npos) << message;
}

TEST(GltfHandMade, IndexOutOfRangeIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  std::vector<std::uint16_t> indices = tetrahedron_indices;
  indices[7] = 4;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, indices, "m");
  gltf.add_node({{"mesh", mesh}});
  const std::string message = load_error(gltf.write(dir, "index.gltf"));
  EXPECT_NE(message.find("meshes[0].primitives[0].indices (accessor 1)"), std::string::npos)
      << message;
  EXPECT_NE(message.find("index 4 at position 7 is out of range for 4 vertices"), std::string::npos)
      << message;
}

TEST(GltfHandMade, IndexCountNotMultipleOfThreeIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const std::vector<std::uint16_t> indices(tetrahedron_indices.begin(),
                                           tetrahedron_indices.end() - 1);
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, indices, "m");
  gltf.add_node({{"mesh", mesh}});
  const std::string message = load_error(gltf.write(dir, "count.gltf"));
  EXPECT_NE(message.find("not a multiple of 3"), std::string::npos) << message;
}

TEST(GltfHandMade, AccessorPastItsBufferViewIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const int positions = gltf.add_positions(tetrahedron_positions);
  gltf.doc()["accessors"][positions]["count"] = 5;  // one vertex more than the view holds
  gltf.add_node({{"mesh", gltf.add_mesh(positions, -1, "m")}});
  const std::string message = load_error(gltf.write(dir, "past.gltf"));
  EXPECT_NE(message.find("(accessor 0)"), std::string::npos) << message;
  EXPECT_NE(message.find("exceed bufferViews[0]"), std::string::npos) << message;
}

TEST(GltfHandMade, SingularNodeMatrixAboveAMeshIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  const int child = gltf.add_node({{"mesh", mesh}}, false);
  gltf.add_node(
      {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1}}, {"children", {child}}});
  const std::string message = load_error(gltf.write(dir, "singular.gltf"));
  EXPECT_NE(message.find("nodes[1].matrix: singular transform"), std::string::npos) << message;
}

TEST(GltfHandMade, NonFiniteMatrixIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e308, 0, 0, 1}}});
  gltf.doc()["nodes"][0]["matrix"][12] = 1e308;
  // JSON cannot hold inf: overflow it in the world transform instead, through a scaled parent.
  const int child = 0;
  gltf.doc()["scenes"][0]["nodes"] = Json::array();
  gltf.add_node({{"scale", {1e10, 1, 1}}, {"children", {child}}});
  const std::string message = load_error(gltf.write(dir, "overflow.gltf"));
  EXPECT_NE(message.find("nodes[0]"), std::string::npos) << message;
  EXPECT_NE(message.find("non-finite"), std::string::npos) << message;
}

TEST(GltfHandMade, ZeroScaleNodeWithoutContentIsHarmless) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}});
  gltf.add_node({{"scale", {0, 0, 0}}});
  EXPECT_EQ(load_scene_file(gltf.write(dir, "hidden.gltf").string()).triangles.size(), 4u);
}

TEST(GltfHandMade, NodeCycleIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}, {"children", {1}}});
  gltf.add_node({{"children", {0}}}, false);
  const std::string message = load_error(gltf.write(dir, "cycle.gltf"));
  EXPECT_NE(message.find("nodes[0]"), std::string::npos) << message;
}

TEST(GltfHandMade, NonTriangleModesAreSkippedWithAWarning) {
  const TempDir dir;
  GltfBuilder gltf;
  const int positions = gltf.add_positions(tetrahedron_positions);
  const int mesh = gltf.add_mesh(positions, gltf.add_indices(tetrahedron_indices), "m");
  gltf.doc()["meshes"][mesh]["primitives"].push_back(
      {{"attributes", {{"POSITION", positions}}}, {"mode", 1}});
  gltf.add_node({{"mesh", mesh}});
  const LoadedScene scene = load_scene_file(gltf.write(dir, "lines.gltf").string());
  EXPECT_EQ(scene.triangles.size(), 4u);
  EXPECT_TRUE(any_warning_contains(scene, "meshes[0].primitives[1]: mode 1"));
}

void expect_near(const glm::vec3& actual, const glm::vec3& expected, const char* what) {
  EXPECT_NEAR(actual.x, expected.x, 1e-6) << what;
  EXPECT_NEAR(actual.y, expected.y, 1e-6) << what;
  EXPECT_NEAR(actual.z, expected.z, 1e-6) << what;
}

TEST(GltfHandMade, PunctualLightsTakeTheirNodesWorldTransform) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}});
  const double h = std::sqrt(0.5);
  auto light_node = [&](int light, Json node) {
    node["extensions"]["KHR_lights_punctual"]["light"] = light;
    return node;
  };
  // Point light at (0, 10, 0) under a parent translated by (1, 0, 0): world (1, 10, 0).
  const int point = gltf.add_light({{"type", "point"}});
  const int point_node = gltf.add_node(light_node(point, {{"translation", {0, 10, 0}}}), false);
  gltf.add_node({{"translation", {1, 0, 0}}, {"children", {point_node}}});
  // Directional light turned -90 degrees about x: it shines along -y, so towards it is +y.
  const int sun = gltf.add_light({{"type", "directional"}});
  gltf.add_node(light_node(sun, {{"rotation", {-h, 0, 0, h}}}));
  // Spot light turned 90 degrees about y: its axis -z becomes -x.
  const int spot = gltf.add_light({{"type", "spot"},
                                   {"range", 5.0},
                                   {"spot", {{"innerConeAngle", 0.1}, {"outerConeAngle", 0.5}}}});
  gltf.add_node(light_node(spot, {{"translation", {0, 0, 4}}, {"rotation", {0, h, 0, h}}}));
  // Point light with range: a sphere; its range is unaffected by the node's scale (KHR spec).
  const int sphere = gltf.add_light({{"type", "point"}, {"range", 3.0}});
  gltf.add_node(light_node(sphere, {{"translation", {2, 0, 0}}, {"scale", {4, 4, 4}}}));
  // Spot light without range: skipped with a warning.
  const int unbounded = gltf.add_light({{"type", "spot"}, {"spot", Json::object()}});
  gltf.add_node(light_node(unbounded, {}));

  const LoadedScene scene = load_scene_file(gltf.write(dir, "lights.gltf").string());
  ASSERT_EQ(scene.shadow_lights.size(), 2u);
  EXPECT_EQ(scene.shadow_lights[0].kind, ShadowLightKind::point);
  expect_near(scene.shadow_lights[0].position, {1, 10, 0}, "point position");
  EXPECT_EQ(scene.shadow_lights[1].kind, ShadowLightKind::directional);
  expect_near(scene.shadow_lights[1].direction, {0, 1, 0}, "direction towards the light");
  ASSERT_EQ(scene.ranged_lights.size(), 2u);
  const RangedLight& spot_light = scene.ranged_lights[0];
  EXPECT_EQ(spot_light.kind, RangedLightKind::spot);
  expect_near(spot_light.centre, {0, 0, 4}, "spot centre");
  expect_near(spot_light.direction, {-1, 0, 0}, "spot axis");
  EXPECT_FLOAT_EQ(spot_light.range, 5.0f);
  EXPECT_FLOAT_EQ(spot_light.cone_half_angle, 0.5f);
  const RangedLight& sphere_light = scene.ranged_lights[1];
  EXPECT_EQ(sphere_light.kind, RangedLightKind::sphere);
  expect_near(sphere_light.centre, {2, 0, 0}, "sphere centre");
  EXPECT_FLOAT_EQ(sphere_light.range, 3.0f);
  EXPECT_TRUE(any_warning_contains(scene, "lights[4]: spot light without range"));
}

TEST(GltfHandMade, LightReferenceOutOfRangeIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}});
  gltf.add_light({{"type", "point"}});
  gltf.add_node({{"extensions", {{"KHR_lights_punctual", {{"light", 3}}}}}});
  const std::string message = load_error(gltf.write(dir, "badlight.gltf"));
  EXPECT_NE(message.find("nodes[1].extensions.KHR_lights_punctual.light"), std::string::npos)
      << message;
}

TEST(GltfHandMade, UnsupportedRequiredExtensionIsAnInputError) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}});
  gltf.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const std::string message = load_error(gltf.write(dir, "draco.gltf"));
  EXPECT_NE(message.find("KHR_draco_mesh_compression"), std::string::npos) << message;
}

TEST(GltfHandMade, SyntaxErrorIsAnInputError) {
  const TempDir dir;
  const fs::path file = dir.write("broken.gltf", "{\"asset\": {\"version\": \"2.0\"},");
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string() + ": JSON"), std::string::npos) << message;
}

// ---- OBJ / OFF / PLY / STL -------------------------------------------------------------------

TEST(MeshFiles, AssimpModelsLoad) {
  struct Model {
    const char* file;
    bool closed;
  };
  std::map<std::string, std::size_t> triangles;
  for (const Model& model : {Model{"STL/Spider_binary.stl", false},
                             Model{"STL/sphereWithHole.stl", false}, Model{"OFF/Wuson.off", false},
                             Model{"PLY/Wuson.ply", false}, Model{"OBJ/spider.obj", false}}) {
    const fs::path file = assimp_models / model.file;
    const LoadedScene scene = load_scene_file(file.string());
    expect_plausible(scene, model.file);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].name, file.stem().string());
    EXPECT_EQ(scene.meshes[0].closed, model.closed) << model.file;
    triangles[model.file] = scene.triangles.size();
    std::cout << model.file << ": " << scene.triangles.size() << " triangles, "
              << (scene.meshes[0].closed ? "closed" : "open") << ", " << scene.warnings.size()
              << " warnings\n";
    for (const auto& warning : scene.warnings) std::cout << "  " << warning << "\n";
  }
  // The same model in two formats has the same triangles.
  EXPECT_EQ(triangles["OFF/Wuson.off"], triangles["PLY/Wuson.ply"]);
}

const char* tetrahedron_off =
    "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST(MeshFiles, TetrahedronOffIsClosed) {
  const TempDir dir;
  const LoadedScene scene = load_scene_file(dir.write("tetra.off", tetrahedron_off).string());
  ASSERT_EQ(scene.triangles.size(), 4u);
  EXPECT_TRUE(scene.meshes[0].closed);
  EXPECT_EQ(scene.meshes[0].name, "tetra");
  EXPECT_EQ(scene.triangles[3].v0, glm::vec3(1, 0, 0));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(MeshFiles, TetrahedronInEveryFormatIsClosed) {
  const TempDir dir;
  const std::string obj =
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  std::string stl = "solid tetra\n";
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& f : faces) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (const int i : f) {
      stl += "vertex " + std::to_string(v[i][0]) + " " + std::to_string(v[i][1]) + " " +
             std::to_string(v[i][2]) + "\n";
    }
    stl += "endloop\nendfacet\n";
  }
  stl += "endsolid tetra\n";
  for (const auto& [name, text] : std::map<std::string, std::string>{
           {"t.obj", obj}, {"t.ply", ply}, {"t.stl", stl}, {"t.off", tetrahedron_off}}) {
    const LoadedScene scene = load_scene_file(dir.write(name, text).string());
    EXPECT_EQ(scene.triangles.size(), 4u) << name;
    EXPECT_TRUE(scene.meshes[0].closed) << name;
  }
}

// OpenMesh's readers feed an importer that keeps every face as the file gives it: a face that
// OpenMesh's own mesh would reject (a complex edge: a third face on an edge, or a halfedge used
// twice) is loaded with its corners unchanged, and not duplicated.
TEST(MeshFiles, FacesOnAComplexEdgeAreKeptAsTheFileGivesThem) {
  const TempDir dir;
  // Three faces on the edge 0-1, two of them traversing it 0 -> 1.
  const LoadedScene book =
      load_scene_file(dir.write("book.off",
                                "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 -1 0\n"
                                "3 0 1 2\n3 1 0 3\n3 0 1 4\n")
                          .string());
  ASSERT_EQ(book.triangles.size(), 3u);
  EXPECT_EQ(book.triangles[2].v0, glm::vec3(0, 0, 0));
  EXPECT_EQ(book.triangles[2].v1, glm::vec3(1, 0, 0));
  EXPECT_EQ(book.triangles[2].v2, glm::vec3(0, -1, 0));
  EXPECT_FALSE(book.meshes[0].closed);
  EXPECT_TRUE(book.warnings.empty()) << book.warnings.front();

  // A quad whose second fan triangle (1 3 4) reuses the halfedge 3 -> 4 of the face before it.
  // OpenMesh's TriMesh added the first fan triangle, rejected the second, and then added the
  // whole quad again on copied vertices: three triangles for a quad. Now: the face, then the
  // quad's two fan triangles, once each.
  const LoadedScene quad = load_scene_file(
      dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 1 1\nf 3 4 5\nf 1 2 3 4\n")
          .string());
  const std::vector<std::array<glm::vec3, 3>> expected = {
      {glm::vec3(1, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 1)},
      {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0)},
      {glm::vec3(0, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}};
  ASSERT_EQ(quad.triangles.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(quad.triangles[i].v0, expected[i][0]) << i;
    EXPECT_EQ(quad.triangles[i].v1, expected[i][1]) << i;
    EXPECT_EQ(quad.triangles[i].v2, expected[i][2]) << i;
  }
  EXPECT_TRUE(quad.warnings.empty()) << quad.warnings.front();
}

// A polygon becomes the fan (0 1 2), (0 2 3), ... from its first corner, in the file's order.
TEST(MeshFiles, ObjPolygonIsFanTriangulatedFromItsFirstCorner) {
  const TempDir dir;
  const LoadedScene scene = load_scene_file(
      dir.write("pentagon.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n")
          .string());
  const glm::vec3 v[5] = {{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {1, 2, 0}, {-1, 1, 0}};
  ASSERT_EQ(scene.triangles.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(scene.triangles[i].v0, v[0]) << i;
    EXPECT_EQ(scene.triangles[i].v1, v[i + 1]) << i;
    EXPECT_EQ(scene.triangles[i].v2, v[i + 2]) << i;
  }
  EXPECT_FALSE(scene.meshes[0].closed);
}

TEST(MeshFiles, InvalidOffIsAnInputError) {
  const TempDir dir;
  const fs::path file = dir.write("bad.off", "this is not an off file\n");
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
}

TEST(MeshFiles, OffFaceIndexOutOfRangeIsAnInputError) {
  const TempDir dir;
  const std::string message = load_error(dir.write(
      "oob.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 9\n3 0 3 2\n3 1 2 3\n"));
  EXPECT_NE(message.find("face 1 (line 8)"), std::string::npos) << message;
}

TEST(MeshFiles, TruncatedOffIsAnInputError) {
  const TempDir dir;
  const std::string message = load_error(dir.write("short.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n"));
  EXPECT_NE(message.find("vertex 2"), std::string::npos) << message;
}

TEST(MeshFiles, NonFiniteVerticesAreInputErrorsNamingTheVertex) {
  const TempDir dir;
  const std::string obj_message =
      load_error(dir.write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n"));
  EXPECT_NE(obj_message.find("v 3 (line 3)"), std::string::npos) << obj_message;
  const std::string off_message =
      load_error(dir.write("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n"));
  EXPECT_NE(off_message.find("vertex 1 (line 4)"), std::string::npos) << off_message;
  const std::string big_message =
      load_error(dir.write("big.off", "OFF\n3 1 0\n0 0 0\n1 0 1e39\n0 1 0\n3 0 1 2\n"));
  EXPECT_NE(big_message.find("out of float range"), std::string::npos) << big_message;
  const std::string stl_message = load_error(dir.write(
      "nan.stl",
      "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\n"
      "endloop\nendfacet\nendsolid t\n"));
  EXPECT_NE(stl_message.find("vertex 2 (line 6)"), std::string::npos) << stl_message;
  // Binary STL: the float arrives as NaN bits and is caught after reading.
  std::string binary(80, ' ');
  const std::uint32_t facets = 1;
  binary.append(reinterpret_cast<const char*>(&facets), 4);
  const float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::quiet_NaN(),
                           0};
  binary.append(reinterpret_cast<const char*>(facet), sizeof facet);
  binary.append(2, '\0');
  const std::string binary_message = load_error(dir.write("nan_binary.stl", binary));
  EXPECT_NE(binary_message.find("non-finite"), std::string::npos) << binary_message;
}

TEST(MeshFiles, UnknownExtensionAndMissingFileAreInputErrors) {
  const TempDir dir;
  const std::string extension_message = load_error(dir.write("scene.fbx", "x"));
  EXPECT_NE(extension_message.find("unsupported extension '.fbx'"), std::string::npos);
  const fs::path missing = dir.path() / "missing.obj";
  const std::string missing_message = load_error(missing);
  EXPECT_NE(missing_message.find(missing.string() + ": file: not found"), std::string::npos)
      << missing_message;
}

}  // namespace
}  // namespace shadowcts

namespace shadowcts {
namespace {

// Found by the PLY fuzz target: OpenMesh's reader loops forever on a header without end_header.
TEST(MeshFiles, PlyHeaderWithoutEndHeaderIsAnInputErrorNotAHang) {
  const TempDir dir;
  const fs::path file =
      dir.write("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  const std::string message = load_error(file);
  EXPECT_NE(message.find("end_header"), std::string::npos) << message;
  EXPECT_NE(message.find("no_end.ply"), std::string::npos) << message;
}

}  // namespace
}  // namespace shadowcts

namespace shadowcts {
namespace {

std::string binary_u32(std::uint32_t value) {
  std::string bytes(4, '\0');
  for (int i = 0; i < 4; ++i) bytes[i] = static_cast<char>((value >> (8 * i)) & 0xFF);
  return bytes;
}

// Found by the OFF fuzz target (oom-d1c3974a...): a vertex count that overflows 32 bits made
// OpenMesh reserve 17 GB (it reads the counts with `>>` and trusts whatever they become), and a
// count that parses but exceeds the file would make it allocate and loop as much. Counts are
// checked against what the file can hold before OpenMesh sees it.
TEST(MeshFiles, OffCountsBeyondTheFileAreInputErrorsNotAllocations) {
  const TempDir dir;
  // The fuzz input's shape: digits running past 32 bits, then garbage, where the counts belong.
  const fs::path overflow =
      dir.write("overflow.off", "OFF\n" + std::string(60, '5') + "=" + std::string(40, '5') +
                                    "0 0 1\n 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n");
  const std::string overflow_message = load_error(overflow);
  EXPECT_NE(overflow_message.find(overflow.string()), std::string::npos) << overflow_message;
  EXPECT_NE(overflow_message.find("header (line 2): '5555"), std::string::npos) << overflow_message;

  const fs::path huge =
      dir.write("huge.off", "OFF\n4294967295 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string huge_message = load_error(huge);
  EXPECT_NE(huge_message.find(huge.string()), std::string::npos) << huge_message;
  EXPECT_NE(huge_message.find("4294967295 vertices"), std::string::npos) << huge_message;

  const fs::path faces =
      dir.write("faces.off", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string faces_message = load_error(faces);
  EXPECT_NE(faces_message.find("4000000000 faces"), std::string::npos) << faces_message;

  // Binary OFF: the counts are raw 32-bit integers, and so is each face's corner count.
  std::string binary = "OFF BINARY\n" + binary_u32(4000000000u) + binary_u32(1) + binary_u32(0);
  const std::string binary_message = load_error(dir.write("binary.off", binary));
  EXPECT_NE(binary_message.find("4000000000 vertices"), std::string::npos) << binary_message;
  std::string corners = "OFF BINARY\n" + binary_u32(3) + binary_u32(1) + binary_u32(0);
  for (const float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
    corners.append(reinterpret_cast<const char*>(&v), sizeof v);
  corners += binary_u32(0xFFFFFFFFu) + binary_u32(0) + binary_u32(1) + binary_u32(2);
  const std::string corners_message = load_error(dir.write("corners.off", corners));
  EXPECT_NE(corners_message.find("face 0: the file ends"), std::string::npos) << corners_message;

  // Still read: a binary OFF triangle.
  std::string triangle = "OFF BINARY\n" + binary_u32(3) + binary_u32(1) + binary_u32(0);
  for (const float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
    triangle.append(reinterpret_cast<const char*>(&v), sizeof v);
  triangle += binary_u32(3) + binary_u32(0) + binary_u32(1) + binary_u32(2);
  EXPECT_EQ(load_scene_file(dir.write("triangle.off", triangle).string()).triangles.size(), 1u);
}

// OpenMesh's OFF reader takes the counts from the line after the keyword and does not skip
// comments: either would make it read other numbers than the file means.
TEST(MeshFiles, OffCountsOnTheKeywordLineOrCommentsAreInputErrors) {
  const TempDir dir;
  const std::string same_line =
      load_error(dir.write("same_line.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_NE(same_line.find("line 1"), std::string::npos) << same_line;
  const std::string comment = load_error(
      dir.write("comment.off", "OFF\n3 1 0\n# a comment\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_NE(comment.find("vertex 0 (line 3)"), std::string::npos) << comment;
}

const std::string ply_triangle_header =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n";
const std::string ply_triangle_body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

// Found by the PLY fuzz target (timeout-a4334fc3...): OpenMesh's header loop checks its stream
// only for I/O errors, so once a read fails (a count or version that does not parse, or the end
// of the file before end_header) it spins forever; a property line cut short swallows
// "end_header" as its name and sends it past the header. Each shape is an InputError now.
TEST(MeshFiles, PlyHeadersThatOpenMeshCannotFinishAreInputErrorsNotHangs) {
  const TempDir dir;
  // The fuzz input's shape: binary data after a misspelt end_header.
  std::string misspelt =
      "ply\nformat binary_little_endian 1.0\ncomment VCGLIB generated\nelement vertex 8\n"
      "property float x\nproperty float y\nproperty float z\nelement face 12\n"
      "property list uchar int vertex_indicees\nnd_header\n";
  misspelt.append(96, '\0');
  misspelt += std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
  const fs::path misspelt_file = dir.write("misspelt.ply", misspelt);
  const std::string misspelt_message = load_error(misspelt_file);
  EXPECT_NE(misspelt_message.find(misspelt_file.string()), std::string::npos) << misspelt_message;

  struct Shape {
    std::string name, header, expected;
  };
  const std::vector<Shape> shapes = {
      {"count_not_a_number",
       "ply\nformat ascii 1.0\nelement vertex three\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n",
       "count 'three'"},
      {"count_overflows",
       "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n",
       "count '99999999999'"},
      {"version_not_a_number", "ply\nformat ascii one\n" + ply_triangle_header.substr(21),
       "format version"},
      {"property_cut_short",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty float\n",
       "end_header"},
      {"property_before_element",
       "ply\nformat ascii 1.0\nproperty float x\n" + ply_triangle_header.substr(21),
       "property before any element"},
      {"count_beyond_the_file",
       "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n",
       "4000000000"},
  };
  for (const Shape& shape : shapes) {
    const fs::path file =
        dir.write(shape.name + ".ply", shape.header + "end_header\n" + ply_triangle_body);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find(shape.expected), std::string::npos) << shape.name << ": " << message;
  }
  // The triangle itself loads.
  EXPECT_EQ(load_scene_file(
                dir.write("triangle.ply", ply_triangle_header + "end_header\n" + ply_triangle_body)
                    .string())
                .triangles.size(),
            1u);
}

// Binary PLY face lists are read with the count the file gives: an int count of -1 would make
// OpenMesh read four billion indices. Lists are checked against the bytes left.
TEST(MeshFiles, PlyFaceListLongerThanTheFileIsAnInputError) {
  const TempDir dir;
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list int int vertex_indices\n"
      "end_header\n";
  for (const float v : {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
    ply.append(reinterpret_cast<const char*>(&v), sizeof v);
  const std::string good = ply + binary_u32(3) + binary_u32(0) + binary_u32(1) + binary_u32(2);
  EXPECT_EQ(load_scene_file(dir.write("good.ply", good).string()).triangles.size(), 1u);
  const std::string bad = ply + binary_u32(0xFFFFFFFFu) + binary_u32(0) + binary_u32(1);
  const std::string message = load_error(dir.write("bad.ply", bad));
  EXPECT_NE(message.find("face 0: the file ends"), std::string::npos) << message;
}

// Found by the OBJ fuzz target (crash-b3956210...): a face corner without a vertex index
// ("f /4 3 2 1") makes OpenMesh's reader fail an assertion and abort the process. Corners must
// start with an index that names a vertex.
TEST(MeshFiles, ObjCornerWithoutAVertexIndexIsAnInputErrorNotACrash) {
  const TempDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n";
  struct Shape {
    std::string name, face, expected;
  };
  for (const Shape& shape : std::vector<Shape>{
           {"texture_first", "f /4 3 2 1\n", "corner '/4'"},
           {"normal_first", "f //1 2//1 3//1\n", "corner '//1'"},
           {"zero", "f 0 1 2\n", "vertex index 0"},
           {"beyond", "f 1 2 7\n", "vertex index 7 is out of range (4 vertices so far"},
           {"before_first", "f -1 -2 -5\n", "relative vertex index -5"},
           {"garbage", "f 1 2 x3\n", "corner 'x3'"},
       }) {
    const fs::path file = dir.write(shape.name + ".obj", vertices + shape.face);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find("f 1 (line 6)"), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find(shape.expected), std::string::npos) << shape.name << ": " << message;
  }
  // Still read: texture and normal references, relative indices.
  const std::string good = "f 1/1/1 2//1 3\nf -1 -2 -3\n" + vertices + "f 5 6 7\n";
  EXPECT_EQ(load_scene_file(dir.write("good.obj", vertices + "vt 0 0\n" + good).string())
                .triangles.size(),
            3u);
}

// ---- hostile input (issue 14): no crash, no allocation from an unchecked size, the right words

// A chain of `depth` nodes, each the only child of the one before, the last holding a triangle.
fs::path deep_node_chain(const TempDir& dir, int depth, bool cycle_at_the_end) {
  GltfBuilder gltf;
  const int mesh = gltf.add_mesh(gltf.add_positions({0, 0, 0, 1, 0, 0, 0, 1, 0}), -1, "tri");
  for (int i = 0; i < depth; ++i) {
    Json node = {{"translation", {0.0, 0.0, 0.001}}};
    if (i + 1 < depth) node["children"] = {i + 1};
    if (i + 1 == depth) {
      node["mesh"] = mesh;
      if (cycle_at_the_end) node["children"] = {depth / 2};
    }
    gltf.add_node(std::move(node), i == 0);
  }
  return gltf.write(dir, "chain.gltf");
}

TEST(GltfHostile, NodeChainTwentyThousandDeepLoads) {
  const TempDir dir;
  const fs::path file = deep_node_chain(dir, 20'000, false);
  const auto outcome = testing::run_with_memory_limit([&] {
    const LoadedScene scene = load_scene_file(file.string());
    // 20,000 translations of 0.001 along z, rounded to float at the end.
    if (scene.triangles.size() != 1 || std::fabs(scene.triangles[0].v0.z - 20.0f) > 1e-3f)
      throw InputError(file.string(), "test", "wrong scene");
    throw InputError(file.string(), "test", "loaded");
  });
  EXPECT_TRUE(outcome.input_error) << outcome.message;
  EXPECT_NE(outcome.message.find("test: loaded"), std::string::npos) << outcome.message;
}

TEST(GltfHostile, CycleAtTheEndOfADeepChainIsAnInputError) {
  const TempDir dir;
  const fs::path file = deep_node_chain(dir, 5'000, true);
  const std::string message = load_error(file);
  EXPECT_NE(message.find("nodes[2500]: is its own ancestor"), std::string::npos) << message;
}

std::string nested(std::size_t depth, const std::string& inner = "0") {
  return std::string(depth, '[') + inner + std::string(depth, ']');
}

TEST(GltfHostile, ExtrasNestedHundredThousandDeepIsAnInputError) {
  const TempDir dir;
  const std::string text = R"({"asset": {"version": "2.0", "extras": )" + nested(100'000) + "}}";
  const fs::path file = dir.write("deep.gltf", text);
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string() + ": JSON: nesting deeper than 512"), std::string::npos)
      << message.substr(0, 300);
  // Brackets inside strings do not count.
  const std::string quoted =
      R"({"asset": {"version": "2.0", "extras": ")" + std::string(2000, '[') + R"("}})";
  EXPECT_EQ(load_error(dir.write("quoted.gltf", quoted)).find("nesting"), std::string::npos);
}

// A GLB container of `json` (padded) and an optional BIN chunk.
std::string glb(std::string json, const std::string& bin = "", const char* magic = "glTF") {
  while (json.size() % 4 != 0) json.push_back(' ');
  std::string out(magic, 4);
  auto u32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
  };
  const std::size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  u32(2);
  u32(static_cast<std::uint32_t>(total));
  u32(static_cast<std::uint32_t>(json.size()));
  out += "JSON" + json;
  if (!bin.empty()) {
    u32(static_cast<std::uint32_t>(bin.size()));
    out += std::string("BIN\0", 4) + bin;
  }
  return out;
}

TEST(GltfHostile, GlbJsonChunkNestedTooDeepIsAnInputError) {
  const TempDir dir;
  const fs::path file = dir.write(
      "deep.glb", glb(R"({"asset": {"version": "2.0", "extras": )" + nested(100'000) + "}}"));
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string() + ": GLB JSON chunk: nesting deeper than 512"),
            std::string::npos)
      << message.substr(0, 300);
}

TEST(GltfHostile, BadGlbMagicSaysNotAGlbFile) {
  const TempDir dir;
  const fs::path file = dir.write("bad.glb", glb(R"({"asset": {"version": "2.0"}})", "", "glTX"));
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string() + ": GLB header: not a GLB file (magic 67 6c 54 58 'glTX'"),
            std::string::npos)
      << message;
  EXPECT_NE(load_error(dir.write("short.glb", "gl")).find("not a GLB file (magic missing"),
            std::string::npos);
}

// Indices claiming 2^32 - 1 elements in a 598-byte file: refused by the bounds check before the
// 16 GB they would take are allocated.
TEST(GltfHostile, HugeAccessorCountIsRefusedBeforeAllocation) {
  const TempDir dir;
  GltfBuilder gltf;
  const int mesh = gltf.add_indexed_mesh(tetrahedron_positions, tetrahedron_indices, "m");
  gltf.add_node({{"mesh", mesh}});
  gltf.doc()["accessors"][1]["count"] = 4294967295u;
  const fs::path file = gltf.write(dir, "huge.gltf");
  const auto outcome = testing::run_with_memory_limit([&] { load_scene_file(file.string()); });
  EXPECT_TRUE(outcome.input_error) << outcome.message;
  EXPECT_NE(outcome.message.find("meshes[0].primitives[0].indices (accessor 1): byteOffset 0 + "
                                 "4294967295 elements of 2 bytes"),
            std::string::npos)
      << outcome.message;
  EXPECT_LT(outcome.seconds, 10.0);

  // Without a bufferView (zeros but for sparse values) nothing backs the count: capped.
  GltfBuilder sparse;
  const int positions = sparse.add_positions(tetrahedron_positions);
  const int values = sparse.add_positions({5, 5, 5});
  const std::vector<std::uint16_t> sparse_index = {1, 0};
  const int sparse_indices = sparse.add_indices(sparse_index);
  Json& accessor = sparse.doc()["accessors"][positions];
  accessor.erase("bufferView");
  accessor["count"] = 4294967295u;
  accessor["sparse"] = {
      {"count", 1},
      {"indices",
       {{"bufferView", sparse.doc()["accessors"][sparse_indices]["bufferView"]},
        {"componentType", 5123}}},
      {"values", {{"bufferView", sparse.doc()["accessors"][values]["bufferView"]}}}};
  sparse.add_node({{"mesh", sparse.add_mesh(positions, -1, "m")}});
  const fs::path sparse_file = sparse.write(dir, "sparse.gltf");
  const auto sparse_outcome =
      testing::run_with_memory_limit([&] { load_scene_file(sparse_file.string()); });
  EXPECT_TRUE(sparse_outcome.input_error) << sparse_outcome.message;
  EXPECT_NE(sparse_outcome.message.find("without a bufferView"), std::string::npos)
      << sparse_outcome.message;
}

TEST(GltfHostile, VertexBeyondCaseRangeNamesTheAccessorAndVertex) {
  const TempDir dir;
  GltfBuilder gltf;
  std::vector<float> positions = tetrahedron_positions;
  positions[6] = 1e38f;  // vertex 2, x
  gltf.add_node({{"mesh", gltf.add_indexed_mesh(positions, tetrahedron_indices, "m")}});
  const fs::path file = gltf.write(dir, "far.gltf");
  const std::string message = load_error(file);
  EXPECT_NE(message.find(file.string() + ": meshes[0].primitives[0].attributes.POSITION "
                                         "(accessor 0): vertex 2 lies at"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("beyond 1e30"), std::string::npos) << message;
}

std::string binary_stl(std::uint32_t declared, std::uint32_t held, const char* header = "") {
  std::string out(80, '\0');
  std::memcpy(out.data(), header, std::strlen(header));
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((declared >> (8 * i)) & 0xFF));
  const float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  for (std::uint32_t f = 0; f < held; ++f) {
    out.append(reinterpret_cast<const char*>(facet), sizeof facet);
    out.append(2, '\0');
  }
  return out;
}

TEST(MeshFilesHostile, BinaryStlCountThatDisagreesWithTheSizeSaysSo) {
  const TempDir dir;
  const fs::path five = dir.write("five.stl", binary_stl(5, 1));
  std::string message = load_error(five);
  EXPECT_NE(message.find(five.string() +
                         ": binary STL header: declares 5 triangles (84 + 50 x 5 = 334 bytes), "
                         "the file has 134 bytes (room for 1 triangle)"),
            std::string::npos)
      << message;
  const fs::path huge = dir.write("huge.stl", binary_stl(0xFFFFFFFFu, 1));
  message = load_error(huge);
  EXPECT_NE(message.find("declares 4294967295 triangles"), std::string::npos) << message;
  // A binary header that starts with "solid" is read as ASCII first; the message says both.
  const fs::path solid = dir.write("solid.stl", binary_stl(5, 1, "solid binary"));
  message = load_error(solid);
  EXPECT_NE(message.find("no 'facet' in it as ASCII STL, and as binary STL its header declares 5 "
                         "triangles"),
            std::string::npos)
      << message;
  EXPECT_EQ(load_scene_file(dir.write("one.stl", binary_stl(1, 1)).string()).triangles.size(), 1u);
}

TEST(MeshFilesHostile, ObjFacesSayWhatIsWrongAndWhere) {
  const TempDir dir;
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  struct Shape {
    std::string name, text, expected;
  };
  for (const Shape& shape : std::vector<Shape>{
           {"repeats", vertices + "f 1 1 2\nf 2 3 3\n",
            "faces: every face (2) repeats a vertex, so none has area (first: f 1 (line 4) uses "
            "vertex 1 more than once)"},
           {"two_corners", vertices + "f 1 2\n", "f 1 (line 4): has 2 corner(s)"},
           {"face_first", "f 1 2 3\n" + vertices,
            "f 1 (line 1): vertex index 1 is out of range (0 vertices so far; a face must come "
            "after its vertices)"},
           {"texture_letter", vertices + "f 1/a 2 3\n",
            "f 1 (line 4): corner '1/a': texture index 'a' is not a non-zero integer"},
           {"normal_letter", vertices + "f 1 2//b 3\n", "normal index 'b'"},
           {"four_parts", vertices + "f 1/1/1/1 2 3\n", "more than vertex/texture/normal"},
           {"far", "v 1e38 0 0\n" + vertices + "f 2 3 4\n",
            "v 1 (line 1): coordinate '1e38' is beyond 1e30"},
       }) {
    const fs::path file = dir.write(shape.name + ".obj", shape.text);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find(shape.expected), std::string::npos) << shape.name << ": " << message;
  }
  // Some faces repeating a vertex: dropped with a warning that names the first.
  const LoadedScene scene =
      load_scene_file(dir.write("some.obj", vertices + "f 1 2 3\nf 1 1 2\n").string());
  EXPECT_EQ(scene.triangles.size(), 1u);
  EXPECT_TRUE(any_warning_contains(scene, "first: f 2 (line 5) uses vertex 1 more than once"));
}

TEST(MeshFilesHostile, RepeatedVerticesAndShortFacesAreNamedInEveryFormat) {
  const TempDir dir;
  const std::string ply_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  struct Shape {
    std::string name, text, expected;
  };
  for (const Shape& shape : std::vector<Shape>{
           {"repeat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 0 1\n",
            "every face (1) repeats a vertex, so none has area (first: face 0 (line 6) uses "
            "vertex 0 more than once)"},
           {"two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
            "face 0 (line 6): has 2 corner(s); a face needs at least 3"},
           {"repeat.ply", ply_header + "3 0 0 1\n",
            "every face (1) repeats a vertex, so none has area (first: face 0 (line 13) uses "
            "vertex 0 more than once)"},
           {"two.ply", ply_header + "2 0 1\n", "face 0 (line 13): has 2 corner(s)"},
           {"repeat.stl",
            "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 1 0 "
            "0\nendloop\nendfacet\nendsolid x\n",
            "every face (1) repeats a vertex, so none has area (first: facet 0 (line 4) uses the "
            "point of corner 0 more than once)"},
       }) {
    const fs::path file = dir.write(shape.name, shape.text);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find(shape.expected), std::string::npos) << shape.name << ": " << message;
  }
}

// Found by replaying mutated seeds: OpenMesh's ASCII STL reader takes the 3 lines after
// "outer loop" as the corners whatever they hold; one without a word and 3 coordinates left the
// corner uninitialized (a triangle with garbage coordinates, different on every run).
TEST(MeshFilesHostile, StlCornerLinesWithoutCoordinatesAreInputErrorsNotGarbage) {
  const TempDir dir;
  const std::string head = "solid t\n  facet normal 0 0 1\n    outer loop\n";
  const std::string tail = "    endloop\n  endfacet\nendsolid t\n";
  struct Shape {
    std::string name, text, expected;
  };
  for (const Shape& shape : std::vector<Shape>{
           {"keyword_lost.stl",
            head + "      .0 0.0\n      vertex 1 0 0\n      vertex 0 1 0\n" + tail,
            "facet 0 (line 3): corner 0 (line 4) is not 'vertex x y z'"},
           {"endloop_early.stl", head + "      vertex 0 0 0\n      vertex 1 0 0\n" + tail,
            "facet 0 (line 3): corner 2 (line 6) is not 'vertex x y z'"},
           {"ends_in_loop.stl", head + "      vertex 0 0 0\n",
            "the file ends before the facet's 3 corners"},
       }) {
    const fs::path file = dir.write(shape.name, shape.text);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find(shape.expected), std::string::npos) << shape.name << ": " << message;
  }
  // Any word before the coordinates is what the reader accepts.
  const LoadedScene scene = load_scene_file(
      dir.write("word.stl",
                head + "      vertex 0 0 0\n      VERTEX 1 0 0\n      vertex 0 1 0\n" + tail)
          .string());
  ASSERT_EQ(scene.triangles.size(), 1u);
  EXPECT_EQ(scene.triangles[0].v1, glm::vec3(1, 0, 0));
}

TEST(MeshFilesHostile, Utf16ObjIsNamedAsUtf16) {
  const TempDir dir;
  const std::string ascii = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::string utf16 = "\xFF\xFE";
  for (const char c : ascii) {
    utf16.push_back(c);
    utf16.push_back('\0');
  }
  const fs::path file = dir.write("utf16.obj", utf16);
  std::string message = load_error(file);
  EXPECT_NE(message.find(file.string() + ": line 1: the file is UTF-16"), std::string::npos)
      << message;
  const fs::path no_mark = dir.write("nomark.obj", utf16.substr(2));
  message = load_error(no_mark);
  EXPECT_NE(message.find("line 1: contains a NUL byte"), std::string::npos) << message;
}

// OFF and PLY values are read by OpenMesh's readers from a stream whose numbers must be whole
// words of their kind: a read that would stop inside a word, or take a sign or an underflow as a
// count or a coordinate, fails there, and the importer names the element, the line and the word.
TEST(MeshFilesHostile, OffAndPlyValuesAreWholeWordsOfTheirKind) {
  const TempDir dir;
  const std::string ply_head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n";
  struct Shape {
    std::string name, text, expected;
  };
  for (const Shape& shape : std::vector<Shape>{
           // The reader reads the rest of a vertex line as colour: "1,5" would be read as 1.
           {"comma.off", "OFF\n3 1 0\n0 0 0\n1 0 1,5\n0 1 0\n3 0 1 2\n",
            "vertex 1 (line 4): coordinate '1,5' is not a number"},
           // A float where the edge count belongs: its ".5" would become the first coordinate.
           {"edges.off", "OFF\n3 1 0.5\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
            "header (line 2): '0.5' is not a whole number"},
           {"underflow.off", "OFF\n3 1 0\n0 0 0\n1 0 1e-400\n0 1 0\n3 0 1 2\n",
            "vertex 1 (line 4): coordinate '1e-400' is out of float range"},
           {"sign.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 +1 2\n",
            "face 0 (line 6): '+1' is not a whole number"},
           {"colour.ply", ply_head + "0 0 0 1\n1 0 0 1.5\n0 1 0 1\n3 0 1 2\n",
            "vertex 1 (line 12): '1.5' is not a whole number"},
           // The file ends right after a value: the reader's loop stops without a failed read.
           {"short.ply", ply_head + "0 0 0 1\n1 0 0 1\n0 1 0 1",
            "face 0: the file ends before the 1 faces its header declares"},
           {"index.ply", ply_head + "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 3\n",
            "face 0 (line 14): vertex index 3 is out of range (3 vertices read)"},
       }) {
    const fs::path file = dir.write(shape.name, shape.text);
    const std::string message = load_error(file);
    EXPECT_NE(message.find(file.string()), std::string::npos) << shape.name << ": " << message;
    EXPECT_NE(message.find(shape.expected), std::string::npos) << shape.name << ": " << message;
  }
  // Binary data: a NaN vertex is named by its number.
  std::string binary = "OFF BINARY\n" + binary_u32(3) + binary_u32(1) + binary_u32(0);
  for (const float v :
       {0.0f, 0.0f, 0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f, 0.0f, 1.0f, 0.0f})
    binary.append(reinterpret_cast<const char*>(&v), sizeof v);
  binary += binary_u32(3) + binary_u32(0) + binary_u32(1) + binary_u32(2);
  const std::string binary_message = load_error(dir.write("nan_binary.off", binary));
  EXPECT_NE(binary_message.find("vertex 1: non-finite coordinate"), std::string::npos)
      << binary_message;
  // Still read: a coloured OFF whose last face line has no newline (the reader's read of the
  // rest of that line fails after the last face), and signed PLY colours.
  const LoadedScene coloured = load_scene_file(
      dir.write("coloured.off",
                "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2 255 0 0")
          .string());
  EXPECT_EQ(coloured.triangles.size(), 1u);
  EXPECT_EQ(coloured.triangles[0].v1, glm::vec3(1, 0, 0));
  EXPECT_TRUE(coloured.warnings.empty()) << coloured.warnings.front();
}

TEST(MeshFilesHostile, OpenMeshUnsupportedKeywordDoesNotReachStderr) {
  const TempDir dir;
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nfoo bar\n"
      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const fs::path file = dir.write("keyword.ply", ply);
  ::testing::internal::CaptureStderr();
  const LoadedScene scene = load_scene_file(file.string());
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed.find("Unsupported keyword"), std::string::npos) << printed;
  EXPECT_EQ(scene.triangles.size(), 1u);
  EXPECT_TRUE(any_warning_contains(scene, "words the reader does not know, skipped: 'foo', 'bar'"));
}

}  // namespace
}  // namespace shadowcts
