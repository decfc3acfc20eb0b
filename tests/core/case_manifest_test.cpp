// Case manifests: generator and file scenes, overrides, and errors that name the JSON element.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadowcts/case_manifest.h"
#include "shadowcts/errors.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/gbuffer_exr.h"

namespace shadowcts {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / (std::string("shadowcts_manifest_") + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path write(const std::string& name, const std::string& contents) const {
    std::ofstream(path_ / name, std::ios::binary) << contents;
    return path_ / name;
  }

 private:
  fs::path path_;
};

const char* tetrahedron_off =
    "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

// A ground quad (two triangles) with a point light 5 above it, as glTF with an embedded buffer.
std::string ground_with_light_gltf() {
  const Json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes",
       {{{"name", "ground"}, {"mesh", 0}},
        {{"translation", {0, 5, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 6}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 72}}}},
      // Two triangles of the quad [-4, 4]^2 at y = 0, facing +y.
      {"buffers",
       {{{"byteLength", 72},
         {"uri",
          "data:application/octet-stream;base64,"
          "AACAwAAAAAAAAIDAAACAwAAAAAAAAIBAAACAQAAAAAAAAIBAAACAwAAAAAAAAIDAAACAQAAAAAAAAIBAAACAQAAA"
          "AAAAAIDA"}}}},
      {"extensions", {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}}}}};
  return doc.dump();
}

std::string load_error(const fs::path& manifest) {
  try {
    load_case_manifest(manifest.string());
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << manifest << " loaded without InputError";
  return "";
}

Json file_manifest() {
  return {
      {"name", "files"},
      {"scenes",
       {{{"file", "ground.gltf"}, {"caster", false}},
        {{"file", "tetra.off"},
         {"translate", {10, 0, 0}},
         {"scale", 2.0},
         {"rotate_y_degrees", 90}}}},
      {"camera", {{"position", {0, 3, 8}}, {"target", {0, 0, 0}}, {"width", 64}, {"height", 48}}},
      {"parameters", {{"eps_rel", 0.0009765625}, {"repeats", 1}, {"seed", 7}}}};
}

TEST(CaseManifest, FileScenesArePlacedAndTakeTheGltfLight) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  const fs::path manifest = dir.write("case.json", file_manifest().dump(2));
  const Case c = load_case_manifest(manifest.string());
  EXPECT_EQ(c.name, "files");
  EXPECT_EQ(c.source, manifest.string());
  ASSERT_EQ(c.meshes.size(), 2u);
  EXPECT_FALSE(c.meshes[0].caster);
  EXPECT_TRUE(c.meshes[1].caster);
  EXPECT_TRUE(c.meshes[1].closed);
  ASSERT_EQ(c.triangles.size(), 6u);
  EXPECT_EQ(c.triangles[2].mesh, 1u);
  // Tetrahedron triangle 3 = (1,0,0), (0,1,0), (0,0,1): scaled by 2, a quarter turn about y
  // (x -> -z, z -> x), then moved by (10, 0, 0).
  EXPECT_EQ(c.triangles[5].v0, glm::vec3(10, 0, -2));
  EXPECT_EQ(c.triangles[5].v1, glm::vec3(10, 2, 0));
  EXPECT_EQ(c.triangles[5].v2, glm::vec3(12, 0, 0));
  ASSERT_TRUE(c.light.has_value());
  EXPECT_EQ(c.light->kind, ShadowLightKind::point);
  EXPECT_EQ(c.light->position, glm::vec3(0, 5, 0));
  EXPECT_EQ(c.camera.width, 64u);
  EXPECT_EQ(c.camera.height, 48u);
  EXPECT_EQ(c.camera.position, glm::vec3(0, 3, 8));
  EXPECT_EQ(c.parameters.eps_rel, 0.0009765625);
  EXPECT_EQ(c.parameters.repeats, 1u);
  EXPECT_EQ(c.parameters.seed, 7u);
}

TEST(CaseManifest, ManifestLightsReplaceFileLights) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m["light"] = {{"type", "sun"}, {"direction", {0, 2, 0}}, {"angular_radius_degrees", 0.27}};
  m["ranged_lights"] = {{{"type", "sphere"}, {"centre", {0, 1, 0}}, {"range", 2}},
                        {{"type", "spot"},
                         {"centre", {0, 3, 0}},
                         {"range", 4},
                         {"direction", {0, -3, 0}},
                         {"cone_half_angle_degrees", 30}}};
  const Case c = load_case_manifest(dir.write("case.json", m.dump()).string());
  ASSERT_TRUE(c.light.has_value());
  EXPECT_EQ(c.light->kind, ShadowLightKind::sun_disk);
  EXPECT_EQ(c.light->direction, glm::vec3(0, 1, 0));
  EXPECT_NEAR(c.light->angular_radius, 0.27 * std::numbers::pi / 180.0, 1e-7);
  ASSERT_EQ(c.ranged_lights.size(), 2u);
  EXPECT_EQ(c.ranged_lights[1].kind, RangedLightKind::spot);
  EXPECT_EQ(c.ranged_lights[1].direction, glm::vec3(0, -1, 0));
  EXPECT_NEAR(c.ranged_lights[1].cone_half_angle, std::numbers::pi / 6.0, 1e-7);
}

TEST(CaseManifest, GeneratorSceneWithOverrides) {
  const auto& generators = fixture_generators();
  const auto scalable = std::find_if(generators.begin(), generators.end(),
                                     [](const FixtureGenerator& g) { return g.scalable; });
  ASSERT_NE(scalable, generators.end());
  const TempDir dir;
  const Json m = {{"scene", {{"generator", scalable->name}, {"triangles", 500}, {"seed", 3}}},
                  {"camera", {{"width", 32}, {"height", 16}}},
                  {"light", {{"type", "directional"}, {"direction", {1, 1, 0}}}}};
  const fs::path manifest = dir.write("gen.json", m.dump());
  const Case c = load_case_manifest(manifest.string());
  EXPECT_EQ(c.source, manifest.string());
  EXPECT_GE(c.triangles.size(), 250u);
  EXPECT_LE(c.triangles.size(), 1000u);
  EXPECT_EQ(c.camera.width, 32u);
  EXPECT_EQ(c.camera.height, 16u);
  ASSERT_TRUE(c.light.has_value());
  EXPECT_EQ(c.light->kind, ShadowLightKind::directional);
  EXPECT_NEAR(c.light->direction.x, std::sqrt(0.5), 1e-7);
  // Same manifest, same case (deterministic generator).
  const Case again = load_case_manifest(manifest.string());
  ASSERT_EQ(again.triangles.size(), c.triangles.size());
  EXPECT_EQ(again.triangles.front().v0, c.triangles.front().v0);
}

TEST(CaseManifest, UnknownKeyIsAnInputErrorWithASuggestion) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m["camrea"] = m["camera"];
  const fs::path manifest = dir.write("case.json", m.dump());
  const std::string message = load_error(manifest);
  EXPECT_NE(message.find(manifest.string() + ": camrea: unknown key (did you mean 'camera'?)"),
            std::string::npos)
      << message;
  Json nested = file_manifest();
  nested["camera"]["fov"] = 40;
  const std::string nested_message = load_error(dir.write("nested.json", nested.dump()));
  EXPECT_NE(nested_message.find("camera.fov: unknown key"), std::string::npos) << nested_message;
}

TEST(CaseManifest, WrongTypeNamesTheJsonPath) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m["camera"]["width"] = "256";
  EXPECT_NE(load_error(dir.write("a.json", m.dump()))
                .find("camera.width: must be a non-negative integer"),
            std::string::npos);
  Json n = file_manifest();
  n["scenes"][1]["translate"] = {1, "x", 3};
  EXPECT_NE(
      load_error(dir.write("b.json", n.dump())).find("scenes[1].translate[1]: must be a number"),
      std::string::npos);
}

TEST(CaseManifest, BadLightsNameTheElement) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m["light"] = {{"type", "directional"}, {"direction", {0, 0, 0}}};
  EXPECT_NE(load_error(dir.write("a.json", m.dump())).find("light.direction: has zero length"),
            std::string::npos);
  Json spot = file_manifest();
  spot["ranged_lights"] = {{{"type", "spot"},
                            {"centre", {0, 1, 0}},
                            {"range", 2},
                            {"direction", {0, -1, 0}},
                            {"cone_half_angle_degrees", 200}}};
  EXPECT_NE(load_error(dir.write("b.json", spot.dump()))
                .find("ranged_lights[0].cone_half_angle_degrees: must lie in (0, 180)"),
            std::string::npos);
  Json kind = file_manifest();
  kind["light"] = {{"type", "area"}};
  EXPECT_NE(load_error(dir.write("c.json", kind.dump())).find("light.type: 'area'"),
            std::string::npos);
}

TEST(CaseManifest, FileScenesNeedACameraAndExistingFiles) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m.erase("camera");
  EXPECT_NE(load_error(dir.write("a.json", m.dump())).find(": camera: is required"),
            std::string::npos);
  Json missing = file_manifest();
  missing["scenes"][0]["file"] = "nowhere.glb";
  EXPECT_NE(load_error(dir.write("b.json", missing.dump())).find("nowhere.glb: file: not found"),
            std::string::npos);
  Json both = file_manifest();
  both["scene"] = {{"generator", "x"}};
  EXPECT_NE(load_error(dir.write("c.json", both.dump())).find("scene/scenes"), std::string::npos);
}

TEST(CaseManifest, SyntaxErrorIsAnInputError) {
  const TempDir dir;
  const fs::path manifest = dir.write("broken.json", "{\"name\": \"x\",\n");
  const std::string message = load_error(manifest);
  EXPECT_NE(message.find(manifest.string() + ": JSON: "), std::string::npos) << message;
}

// Found by fuzz_case_manifest (a number like 4e938): the JSON library reports a number beyond
// double's range as out_of_range, not as a parse error, and it escaped as another exception.
TEST(CaseManifest, NumberBeyondDoubleRangeIsAnInputError) {
  const TempDir dir;
  const fs::path manifest =
      dir.write("overflow.json", "44444444444440000000000000000000000000000742e938585244124955");
  const std::string message = load_error(manifest);
  EXPECT_NE(message.find(manifest.string() + ": JSON: "), std::string::npos) << message;
  const fs::path nested =
      dir.write("nested.json", "{\"name\": \"x\", \"parameters\": {\"eps_rel\": 1e400}}");
  EXPECT_NE(load_error(nested).find(nested.string() + ": JSON: "), std::string::npos);
}

// ---- hostile manifests (issue 14) --------------------------------------------------------------

std::string nested(std::size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

TEST(CaseManifestHostile, HundredThousandNestedArraysAreAnInputErrorNotACrash) {
  const TempDir dir;
  const fs::path manifest = dir.write("deep.json", nested(100'000));
  const std::string message = load_error(manifest);
  EXPECT_NE(message.find(manifest.string() + ": JSON: nesting deeper than 512 levels"),
            std::string::npos)
      << message.substr(0, 300);
  // The library itself survives such nesting (Debian's nlohmann 3.11.2 parses and destroys
  // iteratively): the bound is for clear messages, not the only guard.
  EXPECT_EQ(Json::parse(nested(100'000)).size(), 1u);
}

TEST(CaseManifestHostile, WrongTypeIsDescribedByABoundedPrefix) {
  const TempDir dir;
  const fs::path manifest = dir.write("scenes.json", R"({"scenes": )" + nested(500) + "}");
  const std::string message = load_error(manifest);
  EXPECT_NE(message.find(": scenes[0]: must be an object, is array [[[[[[["), std::string::npos)
      << message;
  EXPECT_LT(message.size(), manifest.string().size() + 100) << message;
}

TEST(CaseManifestHostile, DuplicateKeysAreInputErrorsNamingTheElement) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  const std::string text = file_manifest().dump();
  struct Shape {
    std::string name, text, element;
  };
  for (const Shape& shape : std::vector<Shape>{
           {"top", R"({"name": "a", )" + text.substr(1), "name"},
           {"camera",
            std::string(text).replace(text.find(R"("width":64)"), 10, R"("width":64,"width":65)"),
            "camera.width"},
           {"array",
            std::string(text).replace(text.find(R"("file":"tetra.off")"), 18,
                                      R"("file":"tetra.off","file":"tetra.off")"),
            "scenes[1].file"},
       }) {
    const fs::path manifest = dir.write(shape.name + ".json", shape.text);
    const std::string message = load_error(manifest);
    EXPECT_NE(message.find(manifest.string() + ": " + shape.element + ": duplicate key"),
              std::string::npos)
        << shape.name << ": " << message;
  }
}

TEST(CaseManifestHostile, ADeviceOrFolderIsNotARegularFileRatherThanNotFound) {
  const TempDir dir;
  for (const std::string& path : {std::string("/dev/zero"), fs::temp_directory_path().string()}) {
    const std::string message = load_error(path);
    EXPECT_NE(message.find(path + ": file: not a regular file"), std::string::npos) << message;
  }
  EXPECT_NE(load_error(fs::temp_directory_path() / "shadowcts_no_such.json").find("not found"),
            std::string::npos);
}

TEST(CaseManifestHostile, HugeDirectionComponentsAreNormalizedNotZeroLength) {
  const auto& generators = fixture_generators();
  const auto scalable = std::find_if(generators.begin(), generators.end(),
                                     [](const FixtureGenerator& g) { return g.scalable; });
  ASSERT_NE(scalable, generators.end());
  const TempDir dir;
  for (const double component : {1e300, 1e-300}) {
    const Json m = {{"scene", {{"generator", scalable->name}, {"triangles", 200}}},
                    {"light", {{"type", "directional"}, {"direction", {component, component, 0}}}}};
    const Case c = load_case_manifest(dir.write("dir.json", m.dump()).string());
    ASSERT_TRUE(c.light.has_value());
    EXPECT_NEAR(c.light->direction.x, std::sqrt(0.5), 1e-7) << component;
    EXPECT_NEAR(c.light->direction.y, std::sqrt(0.5), 1e-7) << component;
  }
}

TEST(CaseManifestHostile, CoordinatesOutOfRangeBlameTheFileOrThePlacement) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m["scenes"][1]["scale"] = 1e300;
  const fs::path scaled = dir.write("scaled.json", m.dump());
  std::string message = load_error(scaled);
  EXPECT_NE(message.find(scaled.string() + ": scenes[1].scale: places triangle "),
            std::string::npos)
      << message;
  EXPECT_EQ(message.find("NaN"), std::string::npos) << message;

  m = file_manifest();
  m["scenes"][1]["translate"] = {1e31, 0, 0};
  message = load_error(dir.write("moved.json", m.dump()));
  EXPECT_NE(message.find(": scenes[1].translate: places triangle "), std::string::npos) << message;

  const fs::path far = dir.write("far.obj", "v 1e38 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  m = file_manifest();
  m["scenes"][1] = {{"file", "far.obj"}};
  message = load_error(dir.write("far.json", m.dump()));
  EXPECT_NE(message.find(far.string() + ": v 1 (line 1): coordinate '1e38' is beyond 1e30"),
            std::string::npos)
      << message;
}

TEST(CaseManifestHostile, EpsRelRangeIsTheValidatedOne) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  Json m = file_manifest();
  m["parameters"]["eps_rel"] = 0.5;  // inside the old (0, 1), outside [2^-24, 2^-4]
  const std::string message = load_error(dir.write("eps.json", m.dump()));
  EXPECT_NE(message.find("parameters.eps_rel: must lie in [2^-24, 2^-4]"), std::string::npos)
      << message;
  m["parameters"]["eps_rel"] = 0x1p-4;
  EXPECT_EQ(load_case_manifest(dir.write("edge.json", m.dump()).string()).parameters.eps_rel,
            0x1p-4);
  m["parameters"]["repeats"] = 1001;
  EXPECT_NE(load_error(dir.write("repeats.json", m.dump())).find("parameters.repeats"),
            std::string::npos);
}

TEST(CaseManifestHostile, GbufferResolutionIsCheckedAgainstTheCameraAtLoad) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  ViewSamples sky;
  sky.width = 32;
  sky.height = 24;
  for (std::uint32_t y = 0; y < sky.height; ++y) {
    for (std::uint32_t x = 0; x < sky.width; ++x) {
      ViewSample sample;
      sample.pixel_x = x;
      sample.pixel_y = y;
      sample.sample_class = SampleClass::sky;
      sky.samples.push_back(sample);
    }
  }
  const fs::path gbuffer = dir.write("g.exr", "");
  write_gbuffer_exr(gbuffer.string(), sky);
  Json m = file_manifest();
  m["gbuffer"] = "g.exr";  // the camera is 64x48
  const std::string message = load_error(dir.write("g.json", m.dump()));
  EXPECT_NE(message.find(gbuffer.string() + ": dataWindow: 32x24 differs from the case camera's "
                                            "64x48"),
            std::string::npos)
      << message;
  m["camera"]["width"] = 32;
  m["camera"]["height"] = 24;
  EXPECT_EQ(load_case_manifest(dir.write("ok.json", m.dump()).string()).gbuffer_path,
            gbuffer.string());
}

}  // namespace
}  // namespace shadowcts

namespace shadowcts {
namespace {

// Issue 24: "result" names the engine's frame result for `shadowcts check`.
TEST(CaseManifest, ResultNamesExactlyOneExistingFile) {
  const TempDir dir;
  dir.write("ground.gltf", ground_with_light_gltf());
  dir.write("tetra.off", tetrahedron_off);
  const fs::path mask = dir.write("mask.exr", "not read by the manifest");
  Json m = file_manifest();
  m["result"] = {{"mask", "mask.exr"}, {"mask_values", "visible"}};
  const Case c = load_case_manifest(dir.write("ok.json", m.dump()).string());
  EXPECT_EQ(c.external_result.kind, ExternalResultKind::mask);
  EXPECT_TRUE(c.external_result.mask_is_visibility);
  EXPECT_EQ(fs::path(c.external_result.path), mask);

  struct Bad {
    Json result;
    const char* message;
  };
  for (const Bad& bad :
       {Bad{Json::object(), "result: give exactly one of mask, visibility, light_lists"},
        Bad{{{"mask", "mask.exr"}, {"light_lists", "mask.exr"}},
            "result: give exactly one of mask, visibility, light_lists (has mask and light_lists)"},
        Bad{{{"visibility", "gone.exr"}}, "result.visibility: file"},
        Bad{{{"mask", "mask.exr"}, {"mask_values", "lit"}}, "result.mask_values: must be"},
        Bad{{{"visibility", "mask.exr"}, {"budget", {{"mean", 2}}}},
            "result.budget.mean: must lie in [0, 1]"},
        Bad{{{"mask", "mask.exr"}, {"maks_values", "visible"}},
            "result.maks_values: unknown key"}}) {
    Json n = file_manifest();
    n["result"] = bad.result;
    EXPECT_NE(load_error(dir.write("bad.json", n.dump())).find(bad.message), std::string::npos)
        << bad.message;
  }
}

}  // namespace
}  // namespace shadowcts
