// The candidate culling of the exact soft-shadow oracle is conservative: the angle bound never
// exceeds the true smallest angle (checked against dense sampling of the triangle), and the BVH
// visits every caster the angle test keeps.
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "oracles/soft_shadow/light_cone_bvh.h"
#include "oracles/soft_shadow/sun_disk_projection.h"
#include "tests/oracles/soft_shadow/soft_case.h"

namespace shadowcts {
namespace {

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

TEST(LightConeCulling, AngleToTriangleIsALowerBound) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.2, 1.0, -0.1));
  int tight = 0;
  for (int i = 0; i < 400; ++i) {
    std::array<glm::dvec3, 3> w;
    for (auto& v : w) v = glm::dvec3(unit(random), unit(random) + 0.8, unit(random)) * 2.0;
    const double bound = angle_to_triangle(d, w);
    double smallest = std::numbers::pi;
    constexpr int steps = 120;
    for (int a = 0; a <= steps; ++a)
      for (int b = 0; a + b <= steps; ++b) {
        const double u = double(a) / steps, v = double(b) / steps;
        smallest = std::min(smallest, angle_between(d, (1 - u - v) * w[0] + u * w[1] + v * w[2]));
      }
    ASSERT_LE(bound, smallest + 1e-12) << "triangle " << i;
    tight += smallest - bound < 0.02;
  }
  EXPECT_GT(tight, 390);  // and not uselessly loose
}

TEST(LightConeCulling, BvhVisitsEveryTriangleTheConeReaches) {
  testing::HandBuiltCase h =
      testing::make_hand_built_case(testing::sun_disk({0.3f, 1.0f, 0.2f}, 4.0));
  std::mt19937_64 random(9);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 3000; ++i) {
    const glm::vec3 centre{6 * unit(random), 2.5f + 2.5f * unit(random), 6 * unit(random)};
    h.add_triangle(centre + 0.3f * glm::vec3(unit(random), unit(random), unit(random)),
                   centre + 0.3f * glm::vec3(unit(random), unit(random), unit(random)),
                   centre + 0.3f * glm::vec3(unit(random), unit(random), unit(random)));
  }
  const SunDiskFrame frame = sun_disk_frame(h.c);
  const LightConeBvh bvh(h.c);
  std::size_t reached_total = 0;
  for (int s = 0; s < 200; ++s) {
    const glm::dvec3 p(6 * unit(random), 0.0, 6 * unit(random));
    for (double inflation : {0.0, 0.05}) {
      const LightCone cone{p, frame.direction, frame.angular_radius};
      std::set<std::uint32_t> visited;
      bvh.visit(cone, inflation, [&](std::uint32_t t) { visited.insert(t); });
      for (std::uint32_t t = 1; t < h.c.triangles.size(); ++t) {
        const Triangle& tri = h.c.triangles[t];
        const std::array<glm::dvec3, 3> w{glm::dvec3(tri.v0) - p, glm::dvec3(tri.v1) - p,
                                          glm::dvec3(tri.v2) - p};
        const bool reached = angle_to_triangle(frame.direction, w) <= frame.angular_radius;
        if (inflation == 0.0) reached_total += reached;
        if (reached) {
          EXPECT_TRUE(visited.count(t)) << "sample " << s << ", triangle " << t;
        }
        // Within `inflation` of the cone: some vertex is (a sufficient witness).
        for (const glm::vec3& v : {tri.v0, tri.v1, tri.v2})
          if (distance_to_cone(cone, glm::dvec3(v)) <= inflation) {
            EXPECT_TRUE(visited.count(t)) << "sample " << s << ", triangle " << t;
          }
      }
    }
  }
  EXPECT_GT(reached_total, 200u);  // the scene does put casters in the cones
}

}  // namespace
}  // namespace shadowcts
