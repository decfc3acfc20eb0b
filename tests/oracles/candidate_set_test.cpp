// The candidate set of the exact oracle can never miss a triangle that blocks the sample or any
// sample moved by the band: checked against the exact predicate over every caster.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hand_built_case.h"
#include "oracles/band_moves.h"
#include "oracles/caster_bvh.h"
#include "oracles/exact_segment_triangle.h"
#include "oracles/shadow_segment.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

// For samples of `h`, for move lengths 2^k S (k = -24 ... -10, plus 0 and the larger 2^-6 S)
// and all 14 moves: every caster that blocks the moved sample (exact predicate, brute force over
// all casters) is visited by the BVH query inflated by the length, and its separation bound does
// not exceed the length. Returns the number of blocking (sample, move, triangle) triples seen,
// so the caller can make sure the check was not vacuous.
std::size_t check_conservative(const testing::HandBuiltCase& h, std::size_t sample_stride) {
  const Case& c = h.c;
  const HardShadowLight light = hard_shadow_light(c);
  const double scale = c.scale();
  const CasterBvh bvh(c);
  const ExactShadowPredicate predicate(light, scale);
  std::vector<double> lengths = {0.0};
  for (int k = -24; k <= -10; k += 2) lengths.push_back(std::ldexp(scale, k));
  lengths.push_back(std::ldexp(scale, -6));

  std::size_t blocking = 0;
  std::vector<std::uint8_t> visited(c.triangles.size());
  for (std::size_t i = 0; i < h.samples.samples.size(); i += sample_stride) {
    const ViewSample& sample = h.samples.samples[i];
    const glm::dvec3 p(sample.position);
    const ShadowSegment segment = make_shadow_segment(p, light, scale);
    for (const double delta : lengths) {
      std::fill(visited.begin(), visited.end(), 0);
      bvh.visit(segment, delta, [&](std::uint32_t t) {
        visited[t] = 1;
        return false;
      });
      for (std::size_t m = 0; m < (delta == 0.0 ? 1 : band_moves.size()); ++m) {
        const MovedPoint moved{p, delta, delta == 0.0 ? glm::ivec3(0) : band_moves[m]};
        for (const std::uint32_t t : bvh.triangles()) {
          if (t == sample.receiver || !predicate.blocks(c.triangles[t], moved)) continue;
          ++blocking;
          if (!visited[t]) {
            ADD_FAILURE() << "sample " << i << " length " << delta << " move " << m << ": triangle "
                          << t << " blocks but was not visited";
            return blocking;
          }
          const Triangle& tri = c.triangles[t];
          const double separation = separation_inflation(
              segment, glm::dvec3(tri.v0), glm::dvec3(tri.v1), glm::dvec3(tri.v2), 1e300);
          if (separation > delta) {
            ADD_FAILURE() << "sample " << i << " length " << delta << " move " << m << ": triangle "
                          << t << " blocks but its separation is " << separation;
            return blocking;
          }
        }
      }
    }
  }
  return blocking;
}

TEST(CandidateSet, NeverMissesABlockerOfAMovedSamplePointLight) {
  const auto h =
      testing::make_random_case(7, 4, 300, 0.75f, 240, testing::point_light({1.5f, 10.0f, 0.75f}));
  EXPECT_GT(check_conservative(h, 1), 1000u);
}

TEST(CandidateSet, NeverMissesABlockerOfAMovedSampleDirectionalLight) {
  const auto h = testing::make_random_case(8, 4, 300, 0.75f, 240,
                                           testing::directional_light({0.25f, 1.0f, -0.375f}));
  EXPECT_GT(check_conservative(h, 1), 1000u);
}

// Large coordinates far from the origin make the float/double rounding margins matter.
TEST(CandidateSet, NeverMissesABlockerFarFromTheOrigin) {
  auto h =
      testing::make_random_case(9, 4, 200, 0.75f, 160, testing::point_light({1.5f, 10.0f, 0.75f}));
  const glm::vec3 offset{40000.0f, 1000.0f, -30000.0f};
  for (Triangle& t : h.c.triangles) t.v0 += offset, t.v1 += offset, t.v2 += offset;
  for (ViewSample& s : h.samples.samples) s.position += offset;
  h.c.light->position += offset;
  EXPECT_GT(check_conservative(h, 1), 500u);
}

// Samples exactly on edges and vertices of a closed fan: the moves fall on both sides.
TEST(CandidateSet, NeverMissesABlockerAroundSharedEdges) {
  auto h = testing::make_hand_built_case(testing::point_light({0.5f, 8.0f, 0.5f}));
  testing::add_pyramid_fan(h);
  h.add_ground_sample({0.5f, 0.0f, 0.5f});
  h.add_ground_sample({1.0f, 0.0f, 1.0f});
  h.add_ground_sample({0.5f, 0.0f, -1.0f});
  EXPECT_GT(check_conservative(h, 1), 50u);
}

// visit_packet visits, for every lane, exactly what visit() visits for that lane's query alone,
// in the same order, also when lanes stop early and when a packet is not full; and only lanes'
// own triangles.
void check_packet_visits(const testing::HandBuiltCase& h) {
  const Case& c = h.c;
  const HardShadowLight light = hard_shadow_light(c);
  const double scale = c.scale();
  const CasterBvh bvh(c);
  std::vector<ShadowSegment> segments;
  for (const ViewSample& sample : h.samples.samples)
    segments.push_back(make_shadow_segment(glm::dvec3(sample.position), light, scale));
  std::size_t visits = 0;
  for (const double inflation : {0.0, std::ldexp(scale, -16), std::ldexp(scale, -10)})
    for (const std::size_t stop_after : {std::size_t(0), std::size_t(1), std::size_t(3)})
      for (std::size_t first = 0; first < segments.size(); first += CasterBvh::packet_lanes - 3) {
        // Packets of 13 (not full), from every 13th sample.
        const int lanes =
            int(std::min<std::size_t>(CasterBvh::packet_lanes - 3, segments.size() - first));
        const std::size_t n = std::size_t(lanes);
        std::vector<std::vector<std::uint32_t>> alone(n), packed(n);
        for (int l = 0; l < lanes; ++l)
          bvh.visit(segments[first + std::size_t(l)], inflation, [&](std::uint32_t t) {
            alone[std::size_t(l)].push_back(t);
            return stop_after != 0 && alone[std::size_t(l)].size() == stop_after;
          });
        bvh.visit_packet(&segments[first], lanes, inflation, [&](int l, std::uint32_t t) {
          EXPECT_TRUE(l >= 0 && l < lanes);
          packed[std::size_t(l)].push_back(t);
          return stop_after != 0 && packed[std::size_t(l)].size() == stop_after;
        });
        for (int l = 0; l < lanes; ++l) {
          ASSERT_EQ(alone[std::size_t(l)], packed[std::size_t(l)])
              << "sample " << first + std::size_t(l) << ", inflation " << inflation;
          visits += alone[std::size_t(l)].size();
        }
      }
  EXPECT_GT(visits, 1000u);
}

TEST(CandidateSet, PacketVisitsWhatEachQueryVisitsAloneInTheSameOrder) {
  check_packet_visits(
      testing::make_random_case(7, 4, 300, 0.75f, 240, testing::point_light({1.5f, 10.0f, 0.75f})));
  check_packet_visits(testing::make_random_case(
      8, 4, 300, 0.75f, 240, testing::directional_light({0.25f, 1.0f, -0.375f})));
  // Axis-aligned light directions: zero direction components in every lane.
  check_packet_visits(testing::make_random_case(10, 4, 300, 0.75f, 240,
                                                testing::directional_light({0.0f, 1.0f, 0.0f})));
}

// The box test alone, at boxes that touch the query in exactly one point: the segment's exact
// midpoint m (dyadic coordinates) is the lower corner of the box, shifted by +delta in every
// coordinate and then inflated by delta (so the inflated box touches m). Any rounding the
// margin failed to cover would lose some of these.
TEST(CandidateSet, BoxTestReportsBoxesTouchingTheQueryAtOnePoint) {
  std::mt19937 random(3);
  std::uniform_int_distribution<int> coordinate(-512, 512);
  auto dyadic = [&] { return double(coordinate(random)) / 64.0; };
  for (int i = 0; i < 20000; ++i) {
    HardShadowLight light;
    light.position = {dyadic(), dyadic(), dyadic()};
    const glm::dvec3 p(dyadic(), dyadic(), dyadic());
    const ShadowSegment segment = make_shadow_segment(p, light, 8.0);
    const glm::dvec3 m = 0.5 * (p + light.position);  // exact
    const double delta = (i % 2) ? 0x1p-20 : 0.0;
    // Forward of m along axis 0 (where the segment goes for t > 1/2), behind it along axes 1
    // and 2: the segment touches the box only at m (where no direction component is 0).
    float lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const bool above = (k == 0) == (segment.direction[k] >= 0.0);
      if (above) {
        lo[k] = float(m[k] + delta), hi[k] = lo[k] + 1.0f;
      } else {
        hi[k] = float(m[k] - delta), lo[k] = hi[k] - 1.0f;
      }
    }
    ASSERT_TRUE(box_may_meet(segment, lo, hi, box_padding(segment, delta)))
        << "segment " << p.x << "," << p.y << "," << p.z << " delta " << delta;
    // Moved 1/16 further away along axis 1 the box is clear of the query (axis 0 excludes the
    // segment before m, axis 1 after it), and the test (whose margins are ~2^-37 here) says so:
    // it does filter.
    if (segment.direction[0] == 0.0 || segment.direction[1] == 0.0) continue;
    const float away = segment.direction[1] > 0.0 ? -0.0625f : 0.0625f;
    lo[1] += away, hi[1] += away;
    EXPECT_FALSE(box_may_meet(segment, lo, hi, box_padding(segment, delta)));
  }
}

}  // namespace
}  // namespace shadowcts
