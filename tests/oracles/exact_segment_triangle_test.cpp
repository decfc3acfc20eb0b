// The exact predicate on configurations whose answer is known exactly (dyadic coordinates).
#include "oracles/exact_segment_triangle.h"

#include <gtest/gtest.h>

namespace shadowcts {
namespace {

const Triangle unit_triangle{{-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, 0};  // in the plane y = 2

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

MovedPoint at(const glm::dvec3& p) {
  return MovedPoint{p, 0.0, {0, 0, 0}};
}

TEST(ExactSegmentTriangle, SegmentThroughTheInteriorBlocks) {
  const ExactShadowPredicate predicate(point_at({0, 8, 0}), 8.0);
  EXPECT_TRUE(predicate.blocks(unit_triangle, at({0, 0, 0})));
  EXPECT_FALSE(predicate.blocks(unit_triangle, at({3, 0, 0})));
}

TEST(ExactSegmentTriangle, SegmentEndingBeforeTheTriangleDoesNotBlock) {
  // The light lies below the triangle: the closed segment stops short of it.
  const ExactShadowPredicate predicate(point_at({0, 1.5, 0}), 8.0);
  EXPECT_FALSE(predicate.blocks(unit_triangle, at({0, 0, 0})));
}

TEST(ExactSegmentTriangle, EdgesAndVerticesAreClosed) {
  const ExactShadowPredicate predicate(point_at({0, 8, -1}), 8.0);
  EXPECT_TRUE(predicate.blocks(unit_triangle, at({0, 0, -1})));  // through the edge z = -1
  const ExactShadowPredicate to_vertex(point_at({0, 8, 1}), 8.0);
  EXPECT_TRUE(to_vertex.blocks(unit_triangle, at({0, 0, 1})));  // through the vertex (0, 2, 1)
  // Oblique, through the edge point (0.5, 2, 0) of the edge (1, 2, -1) - (0, 2, 1), and just
  // beside it (1/1024 further out).
  const ExactShadowPredicate oblique(point_at({1, 4, 0}), 8.0);
  EXPECT_TRUE(oblique.blocks(unit_triangle, at({0, 0, 0})));
  EXPECT_FALSE(oblique.blocks(unit_triangle, at({0.0009765625 * 2, 0, 0})));
}

TEST(ExactSegmentTriangle, SegmentInTheTrianglePlane) {
  const Triangle vertical{{0, 1, -1}, {0, 1, 1}, {0, 3, 0}, 0};  // in the plane x = 0
  const ExactShadowPredicate predicate(point_at({0, 8, 0}), 8.0);
  EXPECT_TRUE(predicate.blocks(vertical, at({0, 0, 0})));  // coplanar, through the triangle
  const ExactShadowPredicate beside(point_at({0, 8, 2}), 8.0);
  EXPECT_FALSE(beside.blocks(vertical, at({0, 0, 2})));  // coplanar, beside it
  // Grazing: the segment touches the plane only at its end point, outside the triangle.
  EXPECT_FALSE(predicate.blocks(vertical, at({1, 0, 0})));
}

TEST(ExactSegmentTriangle, LightInTheTrianglePlane) {
  const Triangle beside_light{{1, 8, -1}, {3, 8, -1}, {2, 8, 1}, 0};
  const ExactShadowPredicate predicate(point_at({0, 8, 0}), 8.0);
  EXPECT_FALSE(predicate.blocks(beside_light, at({0, 0, 0})));
  const Triangle around_light{{-1, 8, -1}, {1, 8, -1}, {0, 8, 1}, 0};
  EXPECT_TRUE(predicate.blocks(around_light, at({0, 0, 0})));  // the light lies on the caster
}

TEST(ExactSegmentTriangle, ZeroAreaTrianglesNeverBlock) {
  const Triangle collinear{{-1, 2, 0}, {1, 2, 0}, {0, 2, 0}, 0};
  const Triangle repeated_vertex{{-1, 2, 0}, {-1, 2, 0}, {1, 2, 0}, 0};
  const Triangle point{{0, 2, 0}, {0, 2, 0}, {0, 2, 0}, 0};
  EXPECT_TRUE(is_zero_area(collinear));
  EXPECT_TRUE(is_zero_area(repeated_vertex));
  EXPECT_FALSE(is_zero_area(unit_triangle));
  const ExactShadowPredicate predicate(point_at({0, 8, 0}), 8.0);
  EXPECT_FALSE(predicate.blocks(collinear, at({0, 0, 0})));
  EXPECT_FALSE(predicate.blocks(repeated_vertex, at({0, 0, 0})));
  EXPECT_FALSE(predicate.blocks(point, at({0, 0, 0})));
}

TEST(ExactSegmentTriangle, SampleAtTheLight) {
  const ExactShadowPredicate predicate(point_at({0, 2, 0}), 8.0);
  EXPECT_TRUE(predicate.blocks(unit_triangle, at({0, 2, 0})));  // the single point lies on it
  const ExactShadowPredicate off(point_at({0, 3, 0}), 8.0);
  EXPECT_FALSE(off.blocks(unit_triangle, at({0, 3, 0})));
}

TEST(ExactSegmentTriangle, DirectionalRayIsUnboundedAndOneSided) {
  const Triangle high{{-1, 1000, -1}, {1, 1000, -1}, {0, 1000, 1}, 0};
  const ExactShadowPredicate up(directional({0, 1, 0}), 1000.0);
  EXPECT_TRUE(up.blocks(high, at({0, 0, 0})));
  EXPECT_TRUE(up.blocks(unit_triangle, at({0, 0, -1})));  // through an edge
  EXPECT_FALSE(up.blocks(unit_triangle, at({0, 3, 0})));  // the triangle lies behind the ray
  EXPECT_TRUE(up.blocks(unit_triangle, at({0, 2, 0})));   // the ray starts on it (closed)
  const ExactShadowPredicate oblique(directional({1, 4, 0}), 8.0);
  EXPECT_TRUE(oblique.blocks(unit_triangle, at({0, 0, 0})));  // through the edge point (0.5, 2, 0)
}

// The far point x + s d of the directional ray is not a double here (p.x = 1 + 2^-23 and
// s d.x = 2^-56 need 57 bits): the predicate must go exact instead of rounding it to p.x, which
// would make the ray vertical and hit both triangles on their common edge x = p.x.
TEST(ExactSegmentTriangle, DirectionalFarPointThatIsNotADoubleStaysExact) {
  const double px = 1.0 + 0x1p-23;
  const ExactShadowPredicate predicate(directional({0x1p-60, 1, 0}), 4.0);
  const Triangle left{{float(px), 2, -1}, {float(px), 2, 1}, {float(px - 1), 2, 0}, 0};
  const Triangle right{{float(px), 2, -1}, {float(px), 2, 1}, {float(px + 1), 2, 0}, 0};
  EXPECT_FALSE(predicate.blocks(left, at({px, 0, 0})));
  EXPECT_TRUE(predicate.blocks(right, at({px, 0, 0})));
}

// A moved point that is not a double: 2^-100 + 2^-3. At y = 2 the segment to the light
// (2^-3, 4, 0) passes x = 2^-3 + 2^-101, right of the common edge x = 2^-3.
TEST(ExactSegmentTriangle, MovedPointThatIsNotADoubleStaysExact) {
  const ExactShadowPredicate predicate(point_at({0x1p-3, 4, 0}), 4.0);
  const Triangle left{{0x1p-3f, 2, -1}, {0x1p-3f, 2, 1}, {-1, 2, 0}, 0};
  const Triangle right{{0x1p-3f, 2, -1}, {0x1p-3f, 2, 1}, {1, 2, 0}, 0};
  const MovedPoint moved{{0x1p-100, 0, 0}, 0x1p-3, {1, 0, 0}};
  EXPECT_FALSE(predicate.blocks(left, moved));
  EXPECT_TRUE(predicate.blocks(right, moved));
  // The same point reached by a move that is a double: 2^-3 + 2^-4 (x = 3/16 at y = 2: right).
  const MovedPoint exact_move{{0x1p-4, 0, 0}, 0x1p-3, {1, 0, 0}};
  EXPECT_FALSE(predicate.blocks(left, exact_move));
  EXPECT_TRUE(predicate.blocks(right, exact_move));
}

TEST(ExactSegmentTriangle, MovesFollowTheirDirection) {
  // Straight under the edge z = -1; moving by +z enters the shadow volume, -z leaves it.
  const ExactShadowPredicate predicate(point_at({0, 8, -1}), 8.0);
  EXPECT_TRUE(predicate.blocks(unit_triangle, MovedPoint{{0, 0, -1}, 0x1p-20, {0, 0, 1}}));
  EXPECT_FALSE(predicate.blocks(unit_triangle, MovedPoint{{0, 0, -1}, 0x1p-20, {0, 0, -1}}));
  EXPECT_FALSE(predicate.blocks(unit_triangle, MovedPoint{{0, 0, -1}, 0x1p-20, {1, 1, -1}}));
}

}  // namespace
}  // namespace shadowcts
