// The band sensitivity is a true bound: moving a sample by the 14 band moves (at j = 0) changes its
// exact visible fraction by no more than the sensitivity the oracle reports for it.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "shadowcts/soft_shadow_oracle.h"
#include "tests/oracles/soft_shadow/soft_case.h"

namespace shadowcts {
namespace {

TEST(BandSensitivity, BoundsTheChangeUnderBandMoves) {
  const ShadowLight light = testing::sun_disk({0.3f, 1.0f, 0.2f}, 2.0);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  // A large band (eps_rel 2^-10: tau = 8 / 1024) so that the moves change fractions measurably.
  h.c.parameters.eps_rel = 1.0 / 1024.0;
  std::mt19937_64 random(21);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 40; ++i) {
    const glm::vec3 centre{-1.5f + 3 * unit(random), 0.4f + 1.5f * unit(random),
                           -1.5f + 3 * unit(random)};
    auto corner = [&] {
      return centre +
             0.7f * glm::vec3(unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f);
    };
    h.add_triangle(corner(), corner(), corner());
  }
  const glm::vec3 d = glm::normalize(light.direction);
  for (int s = 0; s < 150; ++s) {
    const glm::vec3 q{-1.5f + 3 * unit(random), 1.0f, -1.5f + 3 * unit(random)};
    const glm::vec3 p = q - (q.y / d.y) * d;
    h.add_ground_sample({p.x, 0.0f, p.z});
  }
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  // The moved samples as a second view (positions rounded to float: a move of tau = 2^-7 from a
  // coordinate below 8 is exact).
  const int moves[14][3] = {{1, 0, 0},  {-1, 0, 0},  {0, 1, 0},   {0, -1, 0},  {0, 0, 1},
                            {0, 0, -1}, {1, 1, 1},   {1, 1, -1},  {1, -1, 1},  {1, -1, -1},
                            {-1, 1, 1}, {-1, 1, -1}, {-1, -1, 1}, {-1, -1, -1}};
  ViewSamples moved;
  for (const ViewSample& sample : h.samples.samples)
    for (const auto& u : moves) {
      ViewSample m = sample;
      m.position += float(truth.tau) * glm::vec3(float(u[0]), float(u[1]), float(u[2]));
      moved.samples.push_back(m);
    }
  const SoftShadowTruth moved_truth = exact_soft_shadow_oracle(h.c, moved);
  int changed = 0, robust = 0;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    robust += truth.robust[i];
    for (int k = 0; k < 14; ++k) {
      const double change =
          std::fabs(moved_truth.visible_fraction[14 * i + k] - truth.visible_fraction[i]);
      EXPECT_LE(change, truth.band_sensitivity[i]) << "sample " << i << ", move " << k;
      changed += change > 1e-6;
    }
  }
  EXPECT_GT(changed, 50);  // the moves do matter at this band
  EXPECT_GT(robust, 20);   // and the bound is not so loose that nothing is robust
}

}  // namespace
}  // namespace shadowcts
