// Normal cones contain their normals (implicit cube-face cells and explicit cones), and the
// back-face rule never drops a light in front of a sample of the cluster.
#include "reference/lightassign/normal_cone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "reference/lightassign/cluster_key.h"

namespace shadowcts {
namespace {

glm::vec3 random_direction(std::mt19937_64& engine) {
  std::normal_distribution<float> gauss;
  glm::vec3 d;
  do d = {gauss(engine), gauss(engine), gauss(engine)};
  while (glm::length(d) < 1e-3f);
  return glm::normalize(d);
}

TEST(NormalCone, CubeFaceCellConesContainTheirNormals) {
  std::mt19937_64 engine(5);
  for (int trial = 0; trial < 100000; ++trial) {
    glm::vec3 n = random_direction(engine);
    if (trial % 7 == 0) n = glm::vec3(1.0f, float(trial % 3) - 1.0f, float(trial % 5 - 2) / 2.0f);
    const std::uint32_t code = quantize_normal(n, 3);
    ASSERT_LT(code, 54u);
    const NormalCone cone = normal_cell_cone(code, 3);
    ASSERT_LE(angle_between(cone.axis, glm::dvec3(n)), cone.half_angle) << trial;
  }
  // A 3 x 3 cell's cone is narrow: well below the 54.7 degrees of a whole face.
  EXPECT_LT(normal_cell_cone(4, 3).half_angle, 0.5);
}

TEST(NormalCone, ExplicitConesContainTheirNormals) {
  std::mt19937_64 engine(9);
  for (int cluster = 0; cluster < 2000; ++cluster) {
    const glm::vec3 centre = random_direction(engine);
    std::vector<glm::vec3> normals;
    const int count = 1 + cluster % 40;
    const float spread = cluster % 3 == 0 ? 2.0f : 0.3f;
    for (int i = 0; i < count; ++i)
      normals.push_back(glm::normalize(centre + spread * random_direction(engine)));
    ExplicitNormalCone accumulate;
    for (const glm::vec3& n : normals) accumulate.add_direction(n);
    NormalCone cone = accumulate.axis_only();
    for (const glm::vec3& n : normals) ExplicitNormalCone::widen(cone, n);
    for (const glm::vec3& n : normals)
      ASSERT_LE(angle_between(cone.axis, glm::dvec3(n)), cone.half_angle) << cluster;
  }
}

TEST(NormalCone, BackFaceRuleDropsOnlyLightsBehindEverySample) {
  std::mt19937_64 engine(13);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  int culled = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    // A cluster: a small box with samples and normals around an axis.
    const glm::vec3 corner(unit(engine) * 10, unit(engine) * 10, unit(engine) * 10);
    const Aabb box{corner, corner + glm::vec3(0.5f, 0.2f, 0.4f)};
    const glm::vec3 axis = random_direction(engine);
    std::vector<std::pair<glm::vec3, glm::vec3>> samples;  // position, normal
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 p =
          corner + glm::vec3(0.5f, 0.2f, 0.4f) * glm::vec3(unit(engine) * 0.5f + 0.5f,
                                                           unit(engine) * 0.5f + 0.5f,
                                                           unit(engine) * 0.5f + 0.5f);
      samples.push_back({p, glm::normalize(axis + 0.2f * random_direction(engine))});
    }
    ExplicitNormalCone accumulate;
    for (const auto& s : samples) accumulate.add_direction(s.second);
    NormalCone cone = accumulate.axis_only();
    for (const auto& s : samples) ExplicitNormalCone::widen(cone, s.second);
    const glm::vec3 light = corner + glm::vec3(unit(engine), unit(engine), unit(engine)) * 20.0f;
    if (!light_behind_cone(cone, box, glm::dvec3(light))) continue;
    ++culled;
    for (const auto& [p, n] : samples)
      ASSERT_LE(glm::dot(glm::dvec3(n), glm::dvec3(light) - glm::dvec3(p)), 0.0) << trial;
  }
  EXPECT_GT(culled, 1000);  // the rule does cull
}

}  // namespace
}  // namespace shadowcts
