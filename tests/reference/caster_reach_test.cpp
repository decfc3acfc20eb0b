// CasterReach drops a triangle only when it meets no sample's segment: checked against the exact
// predicate of the oracles on every (triangle, sample) pair, with triangles that touch segments
// exactly (a vertex or an edge through a point of the segment), lights of every kind and place,
// and coordinates near the largest floats.
#include "reference/caster_reach.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "oracles/exact_segment_triangle.h"

namespace shadowcts {
namespace {

struct Scene {
  HardShadowLight light;
  std::vector<glm::vec3> samples;
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> receivers = {};  // per sample; none: no_receiver for every sample
};

CasterReach reach_of(const Scene& s) {
  std::vector<float> x, y, z;
  for (const glm::vec3& p : s.samples) {
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
  }
  return CasterReach(s.light, x, y, z);
}

double bound_of(const Scene& s) {
  double b = 1.0;
  const auto add = [&](const glm::dvec3& p) {
    b = std::max({b, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  };
  for (const glm::vec3& p : s.samples) add(p);
  for (const Triangle& t : s.triangles)
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) add(v);
  if (!s.light.directional) add(s.light.position);
  return b;
}

// Checks every dropped triangle against every sample exactly; returns how many were dropped.
std::size_t expect_drops_are_exact(const Scene& s) {
  const CasterReach reach = reach_of(s);
  const ExactShadowPredicate exact(s.light, bound_of(s));
  std::size_t dropped = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Triangle& tri = s.triangles[t];
    if (reach.may_reach(tri.v0, tri.v1, tri.v2)) continue;
    ++dropped;
    for (std::size_t i = 0; i < s.samples.size(); ++i)
      if (exact.blocks(tri, MovedPoint{glm::dvec3(s.samples[i]), 0.0, {0, 0, 0}})) {
        ADD_FAILURE() << "triangle " << t << " dropped but meets the segment of sample " << i;
        return dropped;
      }
  }
  return dropped;
}

HardShadowLight point_light(glm::vec3 p) {
  HardShadowLight l;
  l.position = glm::dvec3(p);
  return l;
}

HardShadowLight directional_light(glm::vec3 d) {
  HardShadowLight l;
  l.directional = true;
  l.direction = glm::dvec3(d);
  return l;
}

// Dyadic coordinates (multiples of 1/64 in [-16, 16]), so that points on segments and edges
// through them are exact floats.
float coarse(std::mt19937& random) {
  return float(std::uniform_int_distribution<int>(-1024, 1024)(random)) / 64.0f;
}
glm::vec3 coarse_point(std::mt19937& random) {
  return {coarse(random), coarse(random), coarse(random)};
}

// Samples in a box, triangles of every size anywhere, and triangles that touch a sample's
// segment exactly: at a vertex, or with an edge through a point of it.
Scene random_scene(std::uint32_t seed, HardShadowLight light, glm::vec3 sample_box_centre,
                   float sample_box_size) {
  std::mt19937 random(seed);
  Scene s;
  s.light = light;
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 60; ++i)
    s.samples.push_back(sample_box_centre +
                        sample_box_size * glm::vec3(unit(random), unit(random), unit(random)));
  for (int i = 0; i < 20; ++i) s.samples.push_back(coarse_point(random));
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 a = 16.0f * glm::vec3(unit(random), unit(random), unit(random));
    const float size = std::pow(2.0f, float(std::uniform_int_distribution<int>(-12, 3)(random)));
    s.triangles.push_back({a, a + size * glm::vec3(unit(random), unit(random), unit(random)),
                           a + size * glm::vec3(unit(random), unit(random), unit(random)), 0});
  }
  // Exact points of the coarse samples' segments: p + k/8 (L - p), or p + 2^j d.
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 p = s.samples[60 + std::size_t(i % 20)];
    glm::vec3 x;
    if (light.directional)
      x = p + std::ldexp(1.0f, std::uniform_int_distribution<int>(-6, 2)(random)) *
                  glm::vec3(light.direction);
    else
      x = p + float(std::uniform_int_distribution<int>(0, 8)(random)) / 8.0f *
                  (glm::vec3(light.position) - p);
    const glm::vec3 w = coarse_point(random) / 8.0f, far = coarse_point(random);
    if (i % 2 == 0)
      s.triangles.push_back({x, far, far + w, 0});  // a vertex on the segment
    else
      s.triangles.push_back({x + w, x - w, far, 0});  // an edge through it
  }
  return s;
}

TEST(CasterReach, DropsOnlyTrianglesThatMeetNoSegment) {
  // Lights with dyadic coordinates (exact segment points), on every side and inside the samples.
  const std::vector<HardShadowLight> lights = {directional_light({0, 1, 0}),
                                               directional_light({1, 1, 1}),
                                               directional_light({-0.5f, 0.25f, 1}),
                                               directional_light({0.75f, -1, -0.125f}),
                                               point_light({0, 20, 0}),
                                               point_light({0, 0, 0}),
                                               point_light({3.5f, -2, 1.25f}),
                                               point_light({-40, 8, 30})};
  std::size_t dropped = 0, triangles = 0;
  std::uint32_t seed = 1;
  for (const HardShadowLight& light : lights)
    for (const float size : {0.5f, 4.0f, 16.0f}) {
      const Scene s = random_scene(seed++, light, {2, -3, 1}, size);
      dropped += expect_drops_are_exact(s);
      triangles += s.triangles.size();
    }
  // Not vacuous: most triangles of these scenes reach no sample.
  EXPECT_GT(dropped, triangles / 4);
}

// Checks every sample marked unreached against every caster exactly; returns how many were.
// `casters`: per triangle, whether it casts (default: all).
std::size_t expect_unreached_samples_are_lit(Scene s, std::vector<std::uint8_t> casters = {}) {
  s.receivers.resize(s.samples.size(), no_receiver);
  casters.resize(s.triangles.size(), 1);
  const CasterReach reach = reach_of(s);
  std::vector<float> x, y, z;
  for (const glm::vec3& p : s.samples) {
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
  }
  std::vector<std::uint32_t> listed;  // in a shuffled order: the answer must not depend on it
  for (std::uint32_t t = 0; t < casters.size(); ++t)
    if (casters[t]) listed.push_back(t);
  std::shuffle(listed.begin(), listed.end(), std::mt19937(9));
  const std::vector<std::uint8_t> reached =
      reach.samples_reached(s.triangles, listed, x, y, z, s.receivers);
  EXPECT_EQ(reached.size(), s.samples.size());
  const ExactShadowPredicate exact(s.light, bound_of(s));
  std::size_t unreached = 0;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    if (reached[i]) continue;
    ++unreached;
    // The receiver half-space rule, as the oracle applies it.
    const std::uint32_t r = s.receivers[i];
    ReceiverPlane plane;
    if (r != no_receiver) plane = exact.receiver_plane(s.triangles[r]);
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
      if (casters[t] && t != r &&
          exact.blocks(s.triangles[t], MovedPoint{glm::dvec3(s.samples[i]), 0.0, {0, 0, 0}},
                       plane)) {
        ADD_FAILURE() << "sample " << i << " marked unreached but triangle " << t
                      << " meets its segment";
        return unreached;
      }
  }
  return unreached;
}

TEST(CasterReach, SamplesMarkedUnreachedMeetNoCaster) {
  std::size_t unreached = 0, samples = 0;
  std::uint32_t seed = 100;
  for (const HardShadowLight& light :
       {directional_light({0, 1, 0}), directional_light({-0.5f, 0.25f, 1}), point_light({0, 20, 0}),
        point_light({3.5f, -2, 1.25f}), point_light({-40, 8, 30})})
    for (const float size : {0.5f, 4.0f, 16.0f}) {
      Scene s = random_scene(seed++, light, {2, -3, 1}, size);
      // Fewer casters, so that some samples are out of their reach.
      s.triangles.resize(s.triangles.size() / 8);
      unreached += expect_unreached_samples_are_lit(s);
      samples += s.samples.size();
    }
  EXPECT_GT(unreached, samples / 8);  // not vacuous
}

// A tessellated floor (y = 0, a caster) with samples on it, a plate above part of it, a coplanar
// plate and a plate below: only the samples under the raised plate can be shadowed. The floor's
// own triangles and the coplanar plate never shadow a floor sample (the receiver half-space
// rule), so those samples need no query; a sample whose receiver is tilted gets no such pass.
TEST(CasterReach, LevelCastersDoNotReachSamplesOnTheirOwnLevel) {
  for (const HardShadowLight& light :
       {point_light({0.5f, 10, 0.25f}), directional_light({0.25f, 1, 0.5f})}) {
    Scene s;
    s.light = light;
    for (int i = -4; i < 4; ++i)
      for (int k = -4; k < 4; ++k) {
        const float x = float(i), z = float(k);
        s.triangles.push_back({{x, 0, z}, {x + 1, 0, z}, {x, 0, z + 1}, 0});
        s.triangles.push_back({{x + 1, 0, z}, {x + 1, 0, z + 1}, {x, 0, z + 1}, 0});
      }
    std::mt19937 random(3);
    std::uniform_real_distribution<float> coordinate(-3.9f, 3.9f);
    for (int i = 0; i < 400; ++i) {
      const glm::vec3 p(coordinate(random), 0.0f, coordinate(random));
      const int qi = int(std::floor(p.x)) + 4, qk = int(std::floor(p.z)) + 4;
      const bool upper = (p.x - std::floor(p.x)) + (p.z - std::floor(p.z)) > 1.0f;
      s.samples.push_back(p);
      s.receivers.push_back(std::uint32_t(2 * (qi * 8 + qk) + (upper ? 1 : 0)));
    }
    const std::uint32_t floor_triangles = std::uint32_t(s.triangles.size());
    s.triangles.push_back({{1, 2, 1}, {2, 2, 1}, {1, 2, 2}, 0});        // raised plate
    s.triangles.push_back({{-3, 0, -3}, {-1, 0, -3}, {-3, 0, -1}, 0});  // coplanar plate
    s.triangles.push_back({{-3, -1, 1}, {0, -1, 1}, {-3, -1, 3}, 0});   // below the floor
    const std::size_t unreached = expect_unreached_samples_are_lit(s);
    // Most floor samples are out of reach of everything here.
    EXPECT_GT(unreached, s.samples.size() / 2);
    EXPECT_LT(unreached, s.samples.size());
    // The floor only receives: the raised plate is the one level caster over its cells.
    std::vector<std::uint8_t> casters(s.triangles.size(), 1);
    std::fill(casters.begin(), casters.begin() + floor_triangles, 0);
    EXPECT_EQ(expect_unreached_samples_are_lit(s, casters), unreached);
    // A tilted receiver: its samples are reached (the floor's triangles may shadow them).
    s.triangles.push_back({{-4, 0, -4}, {-3, 0.5f, -4}, {-4, 0, -3}, 0});
    for (std::uint32_t& r : s.receivers) r = floor_triangles + 3;
    EXPECT_EQ(expect_unreached_samples_are_lit(s), 0u);
    // A level receiver of zero area has no plane: the rule is void, the floor shadows.
    s.triangles.push_back({{-4, 0, -4}, {-3, 0, -4}, {-2, 0, -4}, 0});
    for (std::uint32_t& r : s.receivers) r = floor_triangles + 4;
    EXPECT_EQ(expect_unreached_samples_are_lit(s), 0u);
  }
}

TEST(CasterReach, KeepsTrianglesOnTheSegmentAndDropsThoseBeyondIt) {
  Scene s;
  s.samples = {{0, 0, 0}};
  const Triangle above{{-1, 5, -1}, {1, 5, -1}, {0, 5, 1}, 0};
  const Triangle below{{-1, -5, -1}, {1, -5, -1}, {0, -5, 1}, 0};
  const Triangle touching{{0, 0, 0}, {4, -1, 0}, {4, -1, 1}, 0};  // the sample is its vertex
  const Triangle beside{{2, 5, -1}, {3, 5, -1}, {2.5f, 5, 1}, 0};
  for (const HardShadowLight& light : {directional_light({0, 1, 0}), point_light({0, 10, 0})}) {
    s.light = light;
    const CasterReach reach = reach_of(s);
    EXPECT_TRUE(reach.may_reach(above.v0, above.v1, above.v2));
    EXPECT_FALSE(reach.may_reach(below.v0, below.v1, below.v2));
    EXPECT_TRUE(reach.may_reach(touching.v0, touching.v1, touching.v2));
    EXPECT_FALSE(reach.may_reach(beside.v0, beside.v1, beside.v2));
  }
  // Beyond the point light: its segment ends there.
  s.light = point_light({0, 10, 0});
  EXPECT_FALSE(reach_of(s).may_reach({-1, 12, -1}, {1, 12, -1}, {0, 12, 1}));
  // The light on the triangle: kept (its vertices are not all in front of the face).
  EXPECT_TRUE(reach_of(s).may_reach({-1, 10, -1}, {1, 10, -1}, {0, 10, 1}));
}

TEST(CasterReach, TrianglesTouchingARayAtACornerOfTheirProjection) {
  // A directional light whose ratios d_i / d_z round: the sample and a point of its ray, exact
  // floats, project a few ulps apart. The touching triangle's projected box starts at that point,
  // and a single sample makes the grid's box that one projection: only the proven margin keeps it.
  std::mt19937 random(5);
  for (const glm::vec3 d : {glm::vec3(1, 3, 5), {-7, 3, -11}, {5, 13, 3}}) {
    const HardShadowLight light = directional_light(d);
    for (int i = 0; i < 200; ++i) {
      const glm::vec3 p = coarse_point(random);
      const glm::vec3 x =
          p + std::ldexp(1.0f, std::uniform_int_distribution<int>(-3, 3)(random)) * d;
      // Offsets perpendicular to the dominant axis: the projection moves by them exactly.
      const int axis = std::fabs(d.z) >= std::max(std::fabs(d.x), std::fabs(d.y))
                           ? 2
                           : (std::fabs(d.y) >= std::fabs(d.x) ? 1 : 0);
      glm::vec3 e1(0.0f), e2(0.0f);
      e1[(axis + 1) % 3] = 1.0f;
      e2[(axis + 2) % 3] = 1.0f;
      const float sign = (i % 2 == 0) ? 1.0f : -1.0f;
      const Scene s{light, {p}, {{x, x + sign * (e1 + e2), x + sign * (e1 + 2.0f * e2), 0}}};
      const Triangle& t = s.triangles.front();
      ASSERT_TRUE(ExactShadowPredicate(light, bound_of(s))
                      .blocks(t, MovedPoint{glm::dvec3(p), 0.0, {0, 0, 0}}));
      EXPECT_TRUE(reach_of(s).may_reach(t.v0, t.v1, t.v2))
          << "d " << d.x << " " << d.y << " " << d.z << ", draw " << i;
    }
  }
}

TEST(CasterReach, SamplesOnEveryCubeFaceOfAPointLight) {
  Scene s;
  s.light = point_light({0, 0, 0});
  for (const glm::vec3 d :
       {glm::vec3(8, 1, 1), {-8, 1, 1}, {1, 8, 1}, {1, -8, 1}, {1, 1, 8}, {1, 1, -8}}) {
    s.samples.push_back(d);
    // Halfway to the light: kept; twice as far: dropped.
    s.triangles.push_back({0.5f * d + glm::vec3(0.25f, 0, 0), 0.5f * d - glm::vec3(0, 0.25f, 0),
                           0.5f * d + glm::vec3(0, 0, 0.25f), 0});
    s.triangles.push_back({2.0f * d + glm::vec3(0.25f, 0, 0), 2.0f * d - glm::vec3(0, 0.25f, 0),
                           2.0f * d + glm::vec3(0, 0, 0.25f), 0});
  }
  const CasterReach reach = reach_of(s);
  EXPECT_EQ(reach.planes(), 6u);
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    EXPECT_EQ(reach.may_reach(s.triangles[t].v0, s.triangles[t].v1, s.triangles[t].v2), t % 2 == 0)
        << t;
  EXPECT_EQ(expect_drops_are_exact(s), 6u);
}

TEST(CasterReach, DegenerateSampleSets) {
  const Triangle t{{-1, 5, -1}, {1, 5, -1}, {0, 5, 1}, 0};
  // No samples: nothing to reach. Default: keeps everything.
  EXPECT_FALSE(reach_of(Scene{directional_light({0, 1, 0}), {}, {}}).may_reach(t.v0, t.v1, t.v2));
  EXPECT_FALSE(reach_of(Scene{point_light({0, 9, 0}), {}, {}}).may_reach(t.v0, t.v1, t.v2));
  EXPECT_TRUE(CasterReach().may_reach(t.v0, t.v1, t.v2));
  // A sample at the point light: its segment is the light itself, no projection holds it.
  EXPECT_TRUE(
      reach_of(Scene{point_light({0, -9, 0}), {{0, -9, 0}}, {}}).may_reach(t.v0, t.v1, t.v2));
  // Every sample at one point (a grid of one cell), under both lights.
  for (const HardShadowLight& light : {directional_light({0.5f, 1, 0}), point_light({1, 9, 2})}) {
    Scene s = random_scene(7, light, {1, 1, 1}, 0.0f);
    s.samples.resize(60);
    EXPECT_GT(expect_drops_are_exact(s), 0u);
  }
}

TEST(CasterReach, CoordinatesNearTheLargestFloats) {
  // Projections and margins stay finite and sound where differences of coordinates overflow a
  // float: samples and triangles spread over +-2^127.
  for (const HardShadowLight& light :
       {directional_light({0.25f, 1, -0.5f}), point_light({0x1p126f, 0, -0x1p126f})}) {
    std::mt19937 random(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    Scene s;
    s.light = light;
    const float huge = 0x1.fffffep127f;
    for (int i = 0; i < 40; ++i)
      s.samples.push_back(huge * glm::vec3(unit(random), unit(random), unit(random)));
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 a = huge * glm::vec3(unit(random), unit(random), unit(random));
      const glm::vec3 b = s.samples[std::size_t(i) % s.samples.size()];
      s.triangles.push_back({a, 0.5f * a + 0.5f * b, huge * glm::vec3(unit(random), 0, 1), 0});
    }
    expect_drops_are_exact(s);
  }
}

}  // namespace
}  // namespace shadowcts
