// The band's cube tests: ExactCubeQuery on configurations whose answer is known exactly (dyadic
// coordinates), and the exact oracle's band against brute force on random cases: a sample robust
// at a length has the same exact answer everywhere in the cube of that half-width, robustness is
// monotone in the length, and no move of the 14 changes the answer of a robust sample.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "oracles/ambiguity_band.h"
#include "oracles/band_moves.h"
#include "oracles/caster_bvh.h"
#include "oracles/caster_closure.h"
#include "oracles/exact_segment_triangle.h"
#include "shadowcts/hard_shadow_inputs.h"
#include "shadowcts/hard_shadow_oracle.h"

namespace shadowcts {
namespace {

HardShadowLight point_at(const glm::dvec3& position) {
  HardShadowLight light;
  light.position = position;
  return light;
}

HardShadowLight directional(const glm::dvec3& direction) {
  HardShadowLight light;
  light.directional = true;
  light.direction = direction;
  return light;
}

// Shadow of the vertex (0, 2, 0) on y = 0 at the origin (light straight above it); near the
// vertex the triangle's shadow is a wedge between the directions (1, 0.25) and (1, 0.375) in xz.
const Triangle thin_wedge{{0, 2, 0}, {1, 2, 0.25f}, {1, 2, 0.375f}, 0};

TEST(ExactCubeQuery, NarrowVertexWedgeBetweenMoveDirectionsMeetsTheCube) {
  const glm::dvec3 p(-0x1p-30, 0, 0);
  for (const HardShadowLight& light : {point_at({0, 8, 0}), directional({0, 1, 0})}) {
    const ExactShadowPredicate predicate(light, 8.0);
    EXPECT_FALSE(predicate.blocks(thin_wedge, MovedPoint{p, 0.0, {0, 0, 0}}));
    for (const double h : {0x1p-20, 0x1p-10, 0.25}) {
      // None of the 14 moves enters the wedge ...
      for (const glm::ivec3& move : band_moves)
        EXPECT_FALSE(predicate.blocks(thin_wedge, MovedPoint{p, h, move})) << h;
      // ... but the cube holds points of it: the wedge behind the edges at the vertex, the ray
      // behind the vertex and so the shadow volume meet the cube, not the triangle itself.
      const ExactCubeQuery cube(predicate, p, h);
      EXPECT_TRUE(cube.shadow_volume_meets(thin_wedge)) << h;
      EXPECT_TRUE(cube.shadow_ray_meets(glm::dvec3(thin_wedge.v0))) << h;
      EXPECT_TRUE(cube.shadow_wedge_meets(glm::dvec3(thin_wedge.v0), glm::dvec3(thin_wedge.v1)));
      EXPECT_FALSE(cube.shadow_ray_meets(glm::dvec3(thin_wedge.v1))) << h;
      EXPECT_FALSE(cube.meets_triangle(thin_wedge)) << h;
    }
    // A cube that stays 2^-10 away on the lit side of the vertex misses it all.
    const ExactCubeQuery away(predicate, glm::dvec3(-0x1p-9, 0, 0), 0x1p-10);
    EXPECT_FALSE(away.shadow_volume_meets(thin_wedge));
    EXPECT_FALSE(away.shadow_ray_meets(glm::dvec3(thin_wedge.v0)));
  }
}

// The triangle (-1, 2, -1), (1, 2, -1), (0, 2, 1). Point light (0, 6, -1): the shadow of the edge
// z = -1 on y = 0 is x in [-1.5, 1.5] at z = -1, of the vertex (1, 2, -1) the point (1.5, 0, -1).
// Directional light straight up: the shadows are the vertical projections.
TEST(ExactCubeQuery, WedgesAndRaysMeetTheCubeExactlyWhenTheyTouchIt) {
  const Triangle t{{-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, 0};
  const glm::dvec3 a(t.v0), b(t.v1);
  const double h = 0x1p-12;
  struct Setup {
    HardShadowLight light;
    double vertex_image_x;  // x of the shadow of (1, 2, -1) on y = 0
  };
  for (const Setup& s : {Setup{point_at({0, 6, -1}), 1.5}, Setup{directional({0, 1, 0}), 1.0}}) {
    const ExactShadowPredicate predicate(s.light, 8.0);
    // Beside the edge's shadow (outside the triangle's shadow): touching it with a face is
    // meeting it (closed), one more h away is missing it.
    const ExactCubeQuery touching(predicate, {0, 0, -1 - h}, h);
    EXPECT_TRUE(touching.shadow_wedge_meets(a, b));
    EXPECT_TRUE(touching.shadow_volume_meets(t));
    const ExactCubeQuery clear(predicate, {0, 0, -1 - 2 * h}, h);
    EXPECT_FALSE(clear.shadow_wedge_meets(a, b));
    EXPECT_FALSE(clear.shadow_volume_meets(t));
    // Beyond the vertex's shadow along x, on the line z = -1.
    const ExactCubeQuery at_vertex(predicate, {s.vertex_image_x + h, 0, -1}, h);
    EXPECT_TRUE(at_vertex.shadow_ray_meets(b));
    EXPECT_FALSE(at_vertex.shadow_ray_meets(a));
    EXPECT_TRUE(at_vertex.shadow_volume_meets(t));
    const ExactCubeQuery past_vertex(predicate, {s.vertex_image_x + 2 * h, 0, -1}, h);
    EXPECT_FALSE(past_vertex.shadow_ray_meets(b));
    EXPECT_FALSE(past_vertex.shadow_wedge_meets(a, b));
    EXPECT_FALSE(past_vertex.shadow_volume_meets(t));
    // Inside the shadow, far from its boundary: the volume meets the cube, no wedge does.
    const ExactCubeQuery inside(predicate, {0, 0, 0}, h);
    EXPECT_TRUE(inside.shadow_volume_meets(t));
    EXPECT_FALSE(inside.shadow_wedge_meets(a, b));
    EXPECT_FALSE(inside.meets_triangle(t));
    // A cube around a point of the triangle meets the triangle itself.
    const ExactCubeQuery on(predicate, {0, 2 + h, 0}, h);
    EXPECT_TRUE(on.meets_triangle(t));
  }
}

TEST(ExactCubeQuery, CubeFarFromEverythingMeetsNothing) {
  const Triangle t{{-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, 0};
  for (const HardShadowLight& light : {point_at({0, 8, 0}), directional({0.25, 1, -0.375})}) {
    const ExactShadowPredicate predicate(light, 8.0);
    const ExactCubeQuery cube(predicate, {5, 0, 5}, 0x1p-10);
    EXPECT_FALSE(cube.meets_triangle(t));
    EXPECT_FALSE(cube.shadow_volume_meets(t));
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) EXPECT_FALSE(cube.shadow_ray_meets(v));
    EXPECT_FALSE(cube.shadow_wedge_meets(glm::dvec3(t.v0), glm::dvec3(t.v1)));
  }
}

// The light inside the cube: the hull is the cube itself.
TEST(ExactCubeQuery, PointLightInsideTheCube) {
  const Triangle t{{-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, 0};
  const ExactShadowPredicate predicate(point_at({0, 1, 0}), 8.0);
  const ExactCubeQuery around_light(predicate, {0, 1, 0}, 0.5);
  EXPECT_FALSE(around_light.shadow_volume_meets(t));  // the triangle lies above the cube
  const ExactCubeQuery reaching(predicate, {0, 1.5, 0}, 0.5);
  EXPECT_TRUE(reaching.shadow_volume_meets(t));  // touches the triangle's plane inside it
  EXPECT_TRUE(reaching.meets_triangle(t));
}

// A directional light whose swept corners are not doubles (2^-60 d_x below the corners' last
// bit): the query goes exact and still finds the thin wedge, and still misses where it should.
TEST(ExactCubeQuery, SweptCornersThatAreNotDoublesStayExact) {
  const ExactShadowPredicate predicate(directional({0x1p-60 * (1 + 0x1p-23), 1, 0}), 8.0);
  const glm::dvec3 p(-0x1p-30, 0, 0);
  const ExactCubeQuery cube(predicate, p, 0x1p-20);
  EXPECT_TRUE(cube.shadow_volume_meets(thin_wedge));
  EXPECT_TRUE(cube.shadow_ray_meets(glm::dvec3(thin_wedge.v0)));
  const ExactCubeQuery away(predicate, glm::dvec3(-0x1p-9, 0, 0), 0x1p-10);
  EXPECT_FALSE(away.shadow_volume_meets(thin_wedge));
}

TEST(ExactCubeQuery, LightPlaneSides) {
  const ExactShadowPredicate point(point_at({0, 8, 0}), 8.0);
  const glm::dvec3 a(0, 2, 0), b(1, 2, 0);
  // The plane through L, a and b is z = 0.
  EXPECT_EQ(point.light_plane_side(a, b, {0, 2, 1}), -point.light_plane_side(a, b, {0, 2, -1}));
  EXPECT_NE(point.light_plane_side(a, b, {0, 2, 1}), 0);
  EXPECT_EQ(point.light_plane_side(a, b, {5, 3, 0}), 0);
  EXPECT_EQ(point.light_plane_side({0, 4, 0}, {0, 6, 0}, {1, 1, 1}), 0);  // L on the line ab
  const ExactShadowPredicate up(directional({0, 1, 0}), 8.0);
  EXPECT_EQ(up.light_plane_side(a, b, {0, 5, 1}), -up.light_plane_side(a, b, {0, -5, -1}));
  EXPECT_NE(up.light_plane_side(a, b, {0, 5, 1}), 0);
  EXPECT_EQ(up.light_plane_side({0, 2, 0}, {0, 3, 0}, {1, 0, 1}), 0);  // ab parallel to d
}

// The open pieces and points behind one edge, as the closure reports them.
struct Exposed {
  std::vector<std::pair<glm::vec3, glm::vec3>> pieces;
  std::vector<glm::vec3> points;
};

Exposed exposed(const CasterClosure& closure, std::uint32_t t, int k, std::uint32_t receiver) {
  Exposed e;
  closure.any_exposed(
      t, k, receiver,
      [&](const glm::vec3& a, const glm::vec3& b) {
        e.pieces.push_back({a, b});
        return false;
      },
      [&](const glm::vec3& x) {
        e.points.push_back(x);
        return false;
      });
  return e;
}

// The pyramid fan (apex (0, 3, 0), rim (+-1, 2, +-1)) under a light above: the edges from the apex
// are shared with a triangle on the other side, the rim edges are not; the apex is surrounded.
TEST(CasterClosure, ClosedFanSharedEdgesAndTheReceiver) {
  for (const ShadowLight& light :
       {testing::point_light({0.25f, 8, 0.5f}), testing::directional_light({0, 1, 0})}) {
    auto h = testing::make_hand_built_case(light);
    testing::add_pyramid_fan(h);  // triangles 1 ... 4: (apex, rim[i], rim[i + 1])
    const CasterBvh bvh(h.c);
    const ExactShadowPredicate predicate(hard_shadow_light(h.c), h.c.scale());
    const CasterClosure closure(h.c, bvh, predicate);
    const glm::vec3 apex{0, 3, 0}, rim0{-1, 2, -1}, rim1{1, 2, -1};
    // Edge 0 of triangle 1 (apex to rim[0]): closed by triangle 4; only its rim end is open.
    Exposed e = exposed(closure, 1, 0, no_receiver);
    EXPECT_TRUE(e.pieces.empty());
    ASSERT_EQ(e.points.size(), 1u);
    EXPECT_EQ(e.points[0], rim0);
    EXPECT_TRUE(closure.may_expose(1, 0, no_receiver));
    // Edge 1 (rim[0] to rim[1]) is open.
    e = exposed(closure, 1, 1, no_receiver);
    ASSERT_EQ(e.pieces.size(), 1u);
    EXPECT_EQ(e.pieces[0].first, rim0);
    EXPECT_EQ(e.pieces[0].second, rim1);
    // For a sample on triangle 4, its edge does not close triangle 1's, nor the apex.
    e = exposed(closure, 1, 0, 4);
    EXPECT_EQ(e.pieces.size(), 1u);
    EXPECT_EQ(e.points.size(), 2u);
    EXPECT_EQ(e.points[0], apex);
  }
}

// The closure tells the sides of a shared edge from each caster's own orientation: neighbours
// wound either way round the shared edge, and an apex written as -0 in some of them (the same
// point), close the fan's edges; a fold (both third vertices on one side) leaves its edge open.
TEST(CasterClosure, SharedEdgesCloseWhateverTheWindingAndTheSignOfZero) {
  const glm::vec3 apex{0, 3, 0}, negative_zero_apex{-0.0f, 3, -0.0f};
  const glm::vec3 rim[4] = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};
  for (const ShadowLight& light :
       {testing::point_light({0.25f, 8, 0.5f}), testing::directional_light({0, 1, 0})})
    for (const bool flip : {false, true})
      for (const bool negative_zero : {false, true}) {
        SCOPED_TRACE(::testing::Message() << "flip " << flip << ", -0 " << negative_zero);
        auto h = testing::make_hand_built_case(light);
        for (int i = 0; i < 4; ++i) {
          const glm::vec3& a = negative_zero && i % 2 == 1 ? negative_zero_apex : apex;
          if (flip && i % 2 == 1)
            h.add_triangle(a, rim[(i + 1) % 4], rim[i]);  // 1 ... 4, edges 0 and 2 at the apex
          else
            h.add_triangle(a, rim[i], rim[(i + 1) % 4]);
        }
        const auto fan_closed = [&](const CasterClosure& closure, bool apex_closed) {
          for (std::uint32_t t = 1; t <= 4; ++t)
            for (const int k : {0, 2}) {
              const Exposed e = exposed(closure, t, k, no_receiver);
              EXPECT_TRUE(e.pieces.empty()) << "triangle " << t << " edge " << k;
              if (!apex_closed) continue;
              for (const glm::vec3& x : e.points) EXPECT_NE(x, apex) << "triangle " << t;
            }
        };
        {
          const CasterBvh bvh(h.c);
          const ExactShadowPredicate predicate(hard_shadow_light(h.c), h.c.scale());
          fan_closed(CasterClosure(h.c, bvh, predicate), true);
        }
        // The fold: a fifth caster on the edge from the apex to rim[1], its third vertex on the
        // same side as triangle 1's (rim[0]). The fan's edges stay closed; the apex is now open
        // (nothing crosses the fold's edge to (-1, 2, -0.5)).
        const std::uint32_t fold = h.add_triangle(apex, {-1, 2, -0.5f}, rim[1]);
        const CasterBvh bvh(h.c);
        const ExactShadowPredicate predicate(hard_shadow_light(h.c), h.c.scale());
        const CasterClosure closure(h.c, bvh, predicate);
        fan_closed(closure, false);
        // The fold's edge from rim[1] to the apex is closed by triangle 2 (the other side), not by
        // triangle 1 (its own side); its edge from the apex to (-1, 2, -0.5) is open.
        EXPECT_TRUE(exposed(closure, fold, 2, no_receiver).pieces.empty());
        EXPECT_EQ(exposed(closure, fold, 0, no_receiver).pieces.size(), 1u);
        // Without triangle 2 as a partner (a sample on it), triangle 1 and the fold, on one side,
        // leave that edge open.
        EXPECT_EQ(exposed(closure, fold, 2, 2).pieces.size(), 1u);
      }
  // A lone fold, searched from both ends of the shared edge: open on both casters.
  for (const ShadowLight& light :
       {testing::point_light({0.25f, 8, 0.5f}), testing::directional_light({0, 1, 0})})
    for (const bool flip : {false, true}) {
      auto h = testing::make_hand_built_case(light);
      const std::uint32_t first = h.add_triangle(apex, rim[0], rim[1]);  // edge 2: rim[1], apex
      const std::uint32_t fold = flip ? h.add_triangle(apex, rim[1], {-1, 2, -0.5f})   // edge 0
                                      : h.add_triangle(apex, {-1, 2, -0.5f}, rim[1]);  // edge 2
      const CasterBvh bvh(h.c);
      const ExactShadowPredicate predicate(hard_shadow_light(h.c), h.c.scale());
      const CasterClosure closure(h.c, bvh, predicate);
      EXPECT_EQ(exposed(closure, first, 2, no_receiver).pieces.size(), 1u) << "flip " << flip;
      EXPECT_EQ(exposed(closure, fold, flip ? 0 : 2, no_receiver).pieces.size(), 1u)
          << "flip " << flip;
    }
}

// The same fan with triangle 1 split at the midpoint m of its edge from rim[1] to the apex: the
// neighbour's edge from the apex to rim[1] gets a T-junction at m and stays closed in two pieces.
TEST(CasterClosure, TJunctionsCutEdgesIntoPieces) {
  auto h = testing::make_hand_built_case(testing::point_light({0.25f, 8, 0.5f}));
  const glm::vec3 apex{0, 3, 0};
  const glm::vec3 rim[4] = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};
  const glm::vec3 m{0.5f, 2.5f, -0.5f};
  h.add_triangle(apex, rim[0], m);                                       // 1
  h.add_triangle(m, rim[0], rim[1]);                                     // 2
  const std::uint32_t neighbour = h.add_triangle(apex, rim[1], rim[2]);  // 3
  h.add_triangle(apex, rim[2], rim[3]);
  h.add_triangle(apex, rim[3], rim[0]);
  const CasterBvh bvh(h.c);
  const ExactShadowPredicate predicate(hard_shadow_light(h.c), h.c.scale());
  const CasterClosure closure(h.c, bvh, predicate);
  // The neighbour's edge 0 (apex to rim[1]): pieces apex-m and m-rim[1] both closed, m closed.
  Exposed e = exposed(closure, neighbour, 0, no_receiver);
  EXPECT_TRUE(e.pieces.empty());
  ASSERT_EQ(e.points.size(), 1u);
  EXPECT_EQ(e.points[0], rim[1]);
  // Triangle 1's edge 2 (m to apex) is closed by a part of the neighbour's edge, and so is
  // triangle 2's edge 2 (rim[1] to m).
  e = exposed(closure, 1, 2, no_receiver);
  EXPECT_TRUE(e.pieces.empty());
  EXPECT_TRUE(e.points.empty());
  e = exposed(closure, 2, 2, no_receiver);
  EXPECT_TRUE(e.pieces.empty());
  ASSERT_EQ(e.points.size(), 1u);
  EXPECT_EQ(e.points[0], rim[1]);
}

// --- The oracle's band against brute force -------------------------------------------------

bool exact_answer(const testing::HandBuiltCase& h, const ExactShadowPredicate& predicate,
                  std::uint32_t receiver, const glm::dvec3& q) {
  // Under the receiver half-space rule, against the plane of p's receiver.
  const ReceiverPlane plane = predicate.receiver_plane(h.c.triangles[receiver]);
  for (std::size_t t = 0; t < h.c.triangles.size(); ++t) {
    if (t == receiver || !h.c.meshes[h.c.triangles[t].mesh].caster) continue;
    if (predicate.blocks(h.c.triangles[t], MovedPoint{q, 0.0, {0, 0, 0}}, plane)) return true;
  }
  return false;
}

// p + h u when exact in doubles (dyadic u: it is for these cases; checked).
bool exact_point(const glm::dvec3& p, double h, const glm::dvec3& u, glm::dvec3& q) {
  for (int i = 0; i < 3; ++i) {
    const double offset = h * u[i];
    q[i] = p[i] + offset;
    if (q[i] - p[i] != offset) return false;
  }
  return true;
}

class BandOnRandomCases : public ::testing::TestWithParam<int> {};

testing::HandBuiltCase random_case(int param) {
  const ShadowLight light = param % 2 == 0 ? testing::point_light({1.5f, 10.0f, 0.75f})
                                           : testing::directional_light({0.25f, 1.0f, -0.375f});
  // Few, large blockers and many samples at vertex and edge images: every kind of boundary.
  return testing::make_random_case(100 + std::uint64_t(param), 4, 40, 2.5f, 400, light);
}

TEST_P(BandOnRandomCases, RobustMeansConstantOnTheWholeCube) {
  const auto h = random_case(GetParam());
  const HardShadowTruth truth = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  const HardShadowLight light = hard_shadow_light(h.c);
  const ExactShadowPredicate predicate(light, h.c.scale());
  std::mt19937 random{std::uint32_t(GetParam())};
  std::uniform_int_distribution<int> coordinate(-64, 64);
  std::size_t checked_points = 0, robust_samples = 0;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    const ViewSample& s = h.samples.samples[i];
    const glm::dvec3 p(s.position);
    const bool answer = truth.shadowed[i] == 1;
    ASSERT_EQ(answer, exact_answer(h, predicate, s.receiver, p)) << "sample " << i;
    const int e = truth.robust_exponent[i];
    if (e < band_min_exponent) continue;
    ++robust_samples;
    const double length = std::ldexp(h.c.scale(), e);
    // The 14 moves at every level up to the robust one, and points all over its cube.
    for (int k = band_min_exponent; k <= e; ++k)
      for (const glm::ivec3& move : band_moves) {
        const MovedPoint moved{p, std::ldexp(h.c.scale(), k), move};
        const ReceiverPlane plane = predicate.receiver_plane(h.c.triangles[s.receiver]);
        bool moved_answer = false;
        for (std::size_t t = 0; t < h.c.triangles.size() && !moved_answer; ++t)
          moved_answer = t != s.receiver && h.c.meshes[h.c.triangles[t].mesh].caster &&
                         predicate.blocks(h.c.triangles[t], moved, plane);
        ASSERT_EQ(moved_answer, answer) << "sample " << i << " level " << k;
      }
    for (int n = 0; n < 24; ++n) {
      const glm::dvec3 u(coordinate(random) / 64.0, coordinate(random) / 64.0,
                         coordinate(random) / 64.0);
      glm::dvec3 q;
      if (!exact_point(p, length, u, q)) continue;
      ++checked_points;
      ASSERT_EQ(exact_answer(h, predicate, s.receiver, q), answer)
          << "sample " << i << " robust at 2^" << e << ", point p + " << length << " * (" << u.x
          << ", " << u.y << ", " << u.z << ")";
    }
  }
  EXPECT_GT(robust_samples, h.samples.samples.size() / 2);
  EXPECT_GT(checked_points, 1000u);
}

// classify_packet (the oracle's path) gives every sample of a packet the truth classify() gives
// it alone, at an eps_rel that is a power of two and at one that is not.
TEST_P(BandOnRandomCases, PacketsGiveEverySampleItsOwnTruth) {
  auto h = random_case(GetParam());
  for (const double eps_rel : {0x1p-16, 3e-5}) {
    h.c.parameters.eps_rel = eps_rel;
    const HardShadowLight light = hard_shadow_light(h.c);
    const CasterBvh casters(h.c);
    const ExactShadowPredicate predicate(light, h.c.scale());
    const ExactBandClassifier classifier(h.c, h.c.scale(), light, casters, predicate);
    std::vector<const ViewSample*> regular;
    for (const ViewSample& s : h.samples.samples)
      if (s.sample_class == SampleClass::regular) regular.push_back(&s);
    std::vector<BandCandidate> scratch, candidates[CasterBvh::packet_lanes];
    SampleTruth truths[CasterBvh::packet_lanes];
    std::size_t ambiguous = 0, shadowed = 0;
    for (std::size_t first = 0; first < regular.size(); first += CasterBvh::packet_lanes) {
      const int count = int(std::min<std::size_t>(CasterBvh::packet_lanes, regular.size() - first));
      classifier.classify_packet(&regular[first], count, candidates, truths);
      for (int l = 0; l < count; ++l) {
        const SampleTruth alone =
            classifier.classify(*regular[first + std::size_t(l)], scratch, false);
        ASSERT_EQ(truths[l].shadowed, alone.shadowed) << "sample " << first + std::size_t(l);
        ASSERT_EQ(truths[l].band, alone.band) << "sample " << first + std::size_t(l);
        ASSERT_EQ(truths[l].robust_exponent, alone.robust_exponent);
        ambiguous += alone.band == BandClass::ambiguous;
        shadowed += alone.shadowed;
      }
    }
    EXPECT_GT(ambiguous, 0u);
    EXPECT_GT(shadowed, 0u);
  }
}

// The class at eps_rel = 2^e is robust_exponent >= e, robust_exponent does not depend on eps_rel,
// and an eps_rel between two powers of two is decided by its own cube, between the two classes.
TEST_P(BandOnRandomCases, RobustnessIsMonotoneInTheLength) {
  auto h = random_case(GetParam());
  const HardShadowTruth base = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  std::vector<HardShadowTruth> at;  // at[e - band_min_exponent]: eps_rel = 2^e
  for (int e = band_min_exponent; e <= band_max_exponent; ++e) {
    h.c.parameters.eps_rel = std::ldexp(1.0, e);
    at.push_back(exact_hard_shadow_oracle_with_exponents(h.c, h.samples));
  }
  std::size_t between_checked = 0;
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    for (int e = band_min_exponent; e <= band_max_exponent; ++e) {
      const HardShadowTruth& t = at[std::size_t(e - band_min_exponent)];
      ASSERT_EQ(t.robust_exponent[i], base.robust_exponent[i]) << "sample " << i;
      ASSERT_EQ(t.band[i] != BandClass::ambiguous, base.robust_exponent[i] >= e)
          << "sample " << i << " at 2^" << e;
    }
  }
  // eps_rel = 1.5 * 2^-14: robust there implies robust at 2^-14, and robust at 2^-13 implies
  // robust there.
  h.c.parameters.eps_rel = 1.5 * 0x1p-14;
  const HardShadowTruth between = exact_hard_shadow_oracle_with_exponents(h.c, h.samples);
  for (std::size_t i = 0; i < h.samples.samples.size(); ++i) {
    const bool robust = between.band[i] != BandClass::ambiguous;
    if (robust) {
      EXPECT_GE(base.robust_exponent[i], -14) << "sample " << i;
    }
    if (base.robust_exponent[i] >= -13) {
      EXPECT_TRUE(robust) << "sample " << i;
    }
    between_checked += robust;
  }
  EXPECT_GT(between_checked, 0u);
}

INSTANTIATE_TEST_SUITE_P(PointAndDirectional, BandOnRandomCases, ::testing::Values(0, 1, 2, 3));

}  // namespace
}  // namespace shadowcts
