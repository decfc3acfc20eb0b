// The band sensitivity is a true bound: moving a sample by the 14 band moves (at j = 0) changes its
// exact visible fraction by no more than the sensitivity the oracle reports for it.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "oracles/soft_shadow/sun_disk_projection.h"
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

// fuzz_degenerate (seed 408, generated input 2): a sample 1.7e-9 from the plane of a needle (and
// under 1e-7 from its edge) that duplicates its receiver, under a 3.2-degree sun. By the
// definition its fraction is 0: the duplicate is not its receiver, and from just beneath its plane
// it hides the whole sky beyond. A move across the plane
// makes it 1, so the sample is ambiguous. The band's distance to the needle once came from a far
// vertex (the closest-point method's region tests lose all precision on a needle), the sample was
// called robust, and every rasterizer and ray caster failed on it.
TEST(BandSensitivity, ASampleOnADuplicatedNeedleIsAmbiguous) {
  const ShadowLight light = testing::sun_disk({0.0f, 0.5547002f, 0.83205032f}, 3.2291606140993494);
  testing::HandBuiltCase h = testing::make_hand_built_case(light);
  const glm::vec3 a(-0x1p-2f, 0x1.58p+1f, -0x1.ep-1f), b(-0x1.cp-1f, -0x1p-2f, 0x1.58p+1f),
      c(-0x1.cp-1f, -0x1.fffffep-3f, 0x1.57fffep+1f);
  const std::uint32_t receiver = h.add_triangle(a, b, c);
  h.add_triangle(a, b, c);
  const std::size_t sample = h.add_sample({-0x1.48p-1f, 0x1.b4p-1f, 0x1.53fffep+0f}, receiver);
  h.samples.samples[sample].normal = {0.0f, 0.0f, 1.0f};
  const SoftShadowTruth truth = exact_soft_shadow_oracle(h.c, h.samples);
  ASSERT_EQ(truth.compared[sample], 1);
  EXPECT_EQ(truth.visible_fraction[sample], 0.0);
  EXPECT_EQ(truth.band_sensitivity[sample], 1.0);
  EXPECT_EQ(truth.robust[sample], 0);
}

// distance_to_triangle is a lower bound on the distance to every point of the triangle, for
// needles and slivers at scales 2^-40 to 2^40 with the point near an edge, a vertex, over the
// triangle or in its plane; and it is tight where the triangle is well shaped.
TEST(BandSensitivity, TheDistanceToATriangleIsALowerBoundForNeedlesAndSlivers) {
  std::mt19937_64 random(408);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const auto point = [&](double s) {
    return glm::vec3(float(s * unit(random)), float(s * unit(random)), float(s * unit(random)));
  };
  int checked = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double s = std::ldexp(1.0, int(random() % 81) - 40);
    const glm::vec3 a = point(s), b = point(s);
    // The third vertex a relative 2^-k off the edge (needle, k large) or off a vertex (sliver).
    const double off = std::ldexp(s, -int(random() % 30));
    const float t = float((unit(random) + 1.0) / 2.0);
    const glm::vec3 base = random() % 2 == 0 ? a + t * (b - a) : b;
    const glm::vec3 c = base + point(off);
    const std::array<glm::dvec3, 3> v{glm::dvec3(a), glm::dvec3(b), glm::dvec3(c)};
    // Points of the triangle: a barycentric grid, edges included (long double).
    const auto at = [&](long double u, long double w, int k) {
      return static_cast<long double>(v[0][k]) + u * (static_cast<long double>(v[1][k]) - v[0][k]) +
             w * (static_cast<long double>(v[2][k]) - v[0][k]);
    };
    // The query near an edge point, a vertex, or anywhere around.
    const float u0 = float((unit(random) + 1.0) / 2.0);
    const glm::vec3 near = random() % 3 == 0 ? a : a + u0 * (b - a);
    const glm::vec3 p = near + point(std::ldexp(off, int(random() % 8) - 4));
    const double bound = distance_to_triangle(glm::dvec3(p), v);
    long double nearest = HUGE_VALL;
    constexpr int n = 48;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        long double d2 = 0;
        for (int k = 0; k < 3; ++k) {
          const long double e = static_cast<long double>(p[k]) - at(i / 48.0L, j / 48.0L, k);
          d2 += e * e;
        }
        nearest = std::min(nearest, std::sqrt(d2));
      }
    // Also the point of edge ab nearest p (long double), where most queries lie.
    {
      long double ab2 = 0, dot = 0;
      for (int k = 0; k < 3; ++k) {
        const long double e = static_cast<long double>(v[1][k]) - v[0][k];
        ab2 += e * e;
        dot += (static_cast<long double>(p[k]) - v[0][k]) * e;
      }
      const long double t_ab = ab2 > 0 ? std::clamp(dot / ab2, 0.0L, 1.0L) : 0.0L;
      long double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const long double e = static_cast<long double>(p[k]) - at(t_ab, 0.0L, k);
        d2 += e * e;
      }
      nearest = std::min(nearest, std::sqrt(d2));
    }
    ASSERT_LE(bound, double(nearest) * (1.0 + 1e-15) + 1e-15 * s)
        << "trial " << trial << ": p (" << p.x << ", " << p.y << ", " << p.z << ")";
    ++checked;
  }
  EXPECT_EQ(checked, 4000);
  // Well shaped: the unit right triangle in z = 0; over it, beside an edge, beyond a vertex.
  const std::array<glm::dvec3, 3> v{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
  const struct {
    glm::dvec3 p;
    double distance;
  } known[] = {
      {{0.25, 0.25, 0.5}, 0.5}, {{0.25, 0.25, -2.0}, 2.0},          {{0.5, -0.75, 0.0}, 0.75},
      {{-3.0, -4.0, 0.0}, 5.0}, {{0.5, -0.5, 0.5}, std::sqrt(0.5)}, {{0.25, 0.25, 0.0}, 0.0},
      {{2.0, 0.0, 0.0}, 1.0}};
  for (const auto& k : known) {
    const double bound = distance_to_triangle(k.p, v);
    EXPECT_LE(bound, k.distance);
    EXPECT_GE(bound, k.distance * (1.0 - 1e-9) - 1e-9);
  }
}

// The band's other bound: a caster is skipped when its angle from the sun direction exceeds the
// disk's radius by more than a move can turn it, so an angle too large would call a sample robust
// beside a caster that a move brings into the disk.
TEST(BandSensitivity, TheAngleToATriangleIsALowerBoundForNeedlesAndSlivers) {
  std::mt19937_64 random(2026);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<long double> fraction(0.0L, 1.0L);
  const auto point = [&](double s) {
    return glm::vec3(float(s * unit(random)), float(s * unit(random)), float(s * unit(random)));
  };
  using Point = std::array<long double, 3>;
  const auto angle = [](const glm::dvec3& d, const Point& q) {  // between d and q (long double)
    const long double x[3] = {d.x, d.y, d.z};
    long double dot = 0, cross2 = 0;
    for (int k = 0; k < 3; ++k) {
      dot += x[k] * q[k];
      const long double c = x[(k + 1) % 3] * q[(k + 2) % 3] - x[(k + 2) % 3] * q[(k + 1) % 3];
      cross2 += c * c;
    }
    return std::atan2(std::sqrt(cross2), dot);
  };
  for (int trial = 0; trial < 4000; ++trial) {
    const double s = std::ldexp(1.0, int(random() % 81) - 40);
    const glm::vec3 a = point(s), b = point(s);
    const double off = std::ldexp(s, -int(random() % 30));
    const float t = float((unit(random) + 1.0) / 2.0);
    const glm::vec3 c = (random() % 2 == 0 ? a + t * (b - a) : b) + point(off);
    // p at the triangle's size or far from it (the triangle then a few degrees or less wide).
    const glm::vec3 p = a + point(std::ldexp(s, int(random() % 12) - 2));
    const std::array<glm::dvec3, 3> w{glm::dvec3(a) - glm::dvec3(p), glm::dvec3(b) - glm::dvec3(p),
                                      glm::dvec3(c) - glm::dvec3(p)};
    // Relative to p, in long double: the triangle's points q(u, v) = w0 + u (w1 - w0) + v (w2 -
    // w0).
    const auto at = [&](long double u, long double v) {
      Point q;
      for (int k = 0; k < 3; ++k)
        q[k] = static_cast<long double>(w[0][k]) +
               u * (static_cast<long double>(w[1][k]) - w[0][k]) +
               v * (static_cast<long double>(w[2][k]) - w[0][k]);
      return q;
    };
    // d towards a point of the triangle (inside, or on an edge), then turned by up to 2^-k rad.
    long double u = fraction(random), v = fraction(random);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    if (random() % 4 == 0) v = 0;
    const Point target = at(u, v);
    glm::dvec3 d =
        glm::normalize(glm::dvec3(double(target[0]), double(target[1]), double(target[2])));
    if (random() % 2 == 0) {
      const glm::dvec3 turn(unit(random), unit(random), unit(random));
      d = glm::normalize(d + std::ldexp(1.0, -int(random() % 40)) * turn);
    }
    const double bound = angle_to_triangle(d, w);
    long double nearest = angle(d, target);
    constexpr int n = 32;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        nearest = std::min(nearest, angle(d, at(i / 32.0L, j / 32.0L)));
    // d rounded to double is within about 1e-16 rad of its target.
    ASSERT_LE(bound, double(nearest) + 1e-14)
        << "trial " << trial << ": p (" << p.x << ", " << p.y << ", " << p.z << ")";
  }
}

}  // namespace
}  // namespace shadowcts
