#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "shadowcts/case.h"
#include "shadowcts/errors.h"

namespace shadowcts {
namespace {

Case valid_case() {
  Case c;
  c.name = "test.valid";
  c.source = "cases/valid.json";
  c.meshes = {{"ground", false, true}};
  c.triangles = {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 0}};
  ShadowLight light;
  light.position = {0, 4, 0};
  c.light = light;
  return c;
}

// The message must name the file and the element.
void expect_error(const Case& c, const std::string& element) {
  try {
    validate(c);
    FAIL() << "expected an InputError naming " << element;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cases/valid.json"), std::string::npos) << what;
    EXPECT_NE(what.find(element), std::string::npos) << what;
  }
}

TEST(CaseValidation, AcceptsAValidCase) {
  EXPECT_NO_THROW(validate(valid_case()));
}

TEST(CaseValidation, ZeroAreaTrianglesAreValid) {
  Case c = valid_case();
  c.triangles.push_back({{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, 0});
  EXPECT_NO_THROW(validate(c));
}

TEST(CaseValidation, RejectsNanAndInfinity) {
  Case c = valid_case();
  c.triangles[0].v1.y = std::numeric_limits<float>::quiet_NaN();
  expect_error(c, "triangles[0]");
  c = valid_case();
  c.light->position.x = std::numeric_limits<float>::infinity();
  expect_error(c, "light.position");
  c = valid_case();
  c.camera.up.z = std::numeric_limits<float>::quiet_NaN();
  expect_error(c, "camera.up");
}

TEST(CaseValidation, RejectsOutOfRangeMeshIdsAndEmptyCases) {
  Case c = valid_case();
  c.triangles[0].mesh = 7;
  expect_error(c, "triangles[0].mesh");
  c = valid_case();
  c.triangles.clear();
  expect_error(c, "triangles");
  c = valid_case();
  c.meshes.clear();
  c.triangles.clear();
  expect_error(c, "meshes");
}

TEST(CaseValidation, RejectsImpossibleCameras) {
  Case c = valid_case();
  c.camera.target = c.camera.position;
  expect_error(c, "camera.target");
  c = valid_case();
  c.camera.up = glm::normalize(c.camera.target - c.camera.position);
  expect_error(c, "camera.up");
  c = valid_case();
  c.camera.vertical_fov_degrees = 180;
  expect_error(c, "camera.fov_y_degrees");
  c = valid_case();
  c.camera.near_plane = 10;
  c.camera.far_plane = 1;
  expect_error(c, "camera.near/far");
  c = valid_case();
  c.camera.width = 0;
  expect_error(c, "camera.width/height");
}

TEST(CaseValidation, RejectsImpossibleLights) {
  Case c = valid_case();
  c.light->kind = ShadowLightKind::directional;
  c.light->direction = {0, 0, 0};
  expect_error(c, "light.direction");
  c = valid_case();
  c.light->kind = ShadowLightKind::sun_disk;
  c.light->direction = {0, 1, 0};
  c.light->angular_radius = 0;
  expect_error(c, "light.angular_radius");
  c = valid_case();
  c.ranged_lights.push_back({RangedLightKind::sphere, {0, 1, 0}, -1.0f, {0, 0, -1}, 0});
  expect_error(c, "ranged_lights[0].range");
  c = valid_case();
  c.ranged_lights.push_back({RangedLightKind::spot, {0, 1, 0}, 1.0f, {0, 0, 0}, 0.5f});
  expect_error(c, "ranged_lights[0].direction");
  c = valid_case();
  c.light.reset();
  expect_error(c, "light");
}

TEST(CaseValidation, RejectsImpossibleParameters) {
  Case c = valid_case();
  c.parameters.eps_rel = 0;
  expect_error(c, "parameters.eps_rel");
  c = valid_case();
  c.parameters.repeats = 0;
  expect_error(c, "parameters.repeats");
}

TEST(CaseValidation, ScaleIsTheLargestAbsoluteCoordinate) {
  Case c = valid_case();
  c.camera.position = {0, 2, 5};
  c.light->position = {0, -9.5f, 0};
  EXPECT_EQ(c.scale(), 9.5);
  EXPECT_EQ(c.triangle_scale(), 1.0);
  c.triangles[0].v2.x = -12;
  EXPECT_EQ(c.scale(), 12.0);
  EXPECT_EQ(c.triangle_scale(), 12.0);
}

// Beyond 1e30 float differences overflow: the error names what lies there, not "triangles".
TEST(CaseValidation, RejectsCoordinatesBeyond1e30NamingTheElement) {
  Case c = valid_case();
  c.light->position = {0, 2e30f, 0};
  expect_error(c, "light.position");
  c = valid_case();
  c.camera.position = {-3e30f, 0, 1};
  c.camera.target = {0, 0, 0};
  expect_error(c, "camera.position");
  c = valid_case();
  c.triangles.push_back({{0, 0, 0}, {1, 0, 0}, {0, 0, 1.5e30f}, 0});
  expect_error(c, "triangles[1]");
}

}  // namespace
}  // namespace shadowcts
