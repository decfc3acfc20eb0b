// The 32-wide light BVH: Morton order is a permutation, every node box bounds its children and
// lights, and traversal finds the same lights as a plain loop over every light.
#include "reference/lightassign/light_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "oracles/light_assignment/light_volume_predicates.h"

namespace shadowcts {
namespace {

std::vector<RangedLight> random_lights(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<float> position(-50.0f, 50.0f), range(0.01f, 3.0f);
  std::vector<RangedLight> lights(n);
  for (RangedLight& l : lights) {
    l.centre = {position(engine), position(engine) * 0.2f, position(engine)};
    l.range = range(engine);
  }
  lights[n / 2].range = 1e4f;  // larger than the scene
  return lights;
}

bool inside(const Aabb& outer, const Aabb& inner) {
  for (int i = 0; i < 3; ++i)
    if (inner.min[i] < outer.min[i] || inner.max[i] > outer.max[i]) return false;
  return true;
}

TEST(LightBvh, NodesBoundTheirChildrenAndLights) {
  for (const std::size_t n : {1u, 31u, 32u, 33u, 1024u, 5000u}) {
    SCOPED_TRACE(n);
    const std::vector<RangedLight> lights = random_lights(n, n);
    const LightBvh bvh(lights);
    std::vector<std::uint32_t> order = bvh.light_order();
    std::sort(order.begin(), order.end());
    for (std::uint32_t i = 0; i < n; ++i) ASSERT_EQ(order[i], i);
    ASSERT_FALSE(bvh.levels().empty());
    EXPECT_EQ(bvh.levels().back().size(), 1u);
    EXPECT_LE(bvh.levels().size(), 5u);  // 32^5 = 32 M lights
    for (std::size_t leaf = 0; leaf < n; ++leaf) {
      const RangedLight& l = lights[bvh.light_order()[leaf]];
      const Aabb& box = bvh.leaf_box(std::uint32_t(leaf));
      for (int i = 0; i < 3; ++i) {
        // The box holds the sphere exactly: c - r and c + r computed in doubles.
        EXPECT_LE(double(box.min[i]), double(l.centre[i]) - double(l.range));
        EXPECT_GE(double(box.max[i]), double(l.centre[i]) + double(l.range));
      }
      EXPECT_TRUE(inside(bvh.levels()[0][leaf / LightBvh::branching], box));
    }
    for (std::size_t level = 1; level < bvh.levels().size(); ++level)
      for (std::size_t child = 0; child < bvh.levels()[level - 1].size(); ++child)
        EXPECT_TRUE(inside(bvh.levels()[level][child / LightBvh::branching],
                           bvh.levels()[level - 1][child]));
  }
}

TEST(LightBvh, TraversalFindsTheLightsOfABruteForceLoop) {
  const std::vector<RangedLight> lights = random_lights(5000, 3);
  const LightBvh bvh(lights);
  std::mt19937_64 engine(11);
  std::uniform_real_distribution<float> position(-55.0f, 55.0f), size(0.0f, 8.0f);
  for (int query = 0; query < 300; ++query) {
    Aabb box;
    box.min = {position(engine), position(engine) * 0.2f, position(engine)};
    box.max = box.min + glm::vec3(size(engine), size(engine), size(engine));
    if (query % 10 == 0) box.max = box.min;  // a point, as the brute variant queries
    std::vector<std::uint32_t> found;
    const std::uint64_t tested = bvh.traverse(box, [&](std::uint32_t light) {
      if (sphere_meets_box(lights[light].centre, lights[light].range, box)) found.push_back(light);
    });
    std::vector<std::uint32_t> expected;
    for (std::uint32_t i = 0; i < lights.size(); ++i)
      if (sphere_meets_box(lights[i].centre, lights[i].range, box)) expected.push_back(i);
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found, expected) << "query " << query;
    EXPECT_GE(tested, 1u);
    EXPECT_LT(tested, lights.size());  // the hierarchy prunes
  }
}

}  // namespace
}  // namespace shadowcts
