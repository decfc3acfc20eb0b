// The one definition of closedness (shadowcts/closed_surface.h) that the loaders' Mesh::closed and
// the stencil baseline's front-face rule share: exact positions, every directed edge once and its
// reverse once, triangles with a repeated corner ignored.
#include "shadowcts/closed_surface.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace shadowcts {
namespace {

const glm::vec3 p0{0, 0, 0}, p1{1, 0, 0}, p2{0, 1, 0}, p3{0, 0, 1};

// Outward-facing (counter-clockwise seen from outside).
std::vector<Triangle> tetrahedron(const glm::vec3& offset = glm::vec3(0.0f)) {
  return {{p0 + offset, p2 + offset, p1 + offset},
          {p0 + offset, p1 + offset, p3 + offset},
          {p0 + offset, p3 + offset, p2 + offset},
          {p1 + offset, p2 + offset, p3 + offset}};
}

TEST(ClosedSurface, TetrahedronIsClosedAndEveryFaceRemovedOpensIt) {
  EXPECT_TRUE(is_closed_surface(tetrahedron()));
  for (std::size_t drop = 0; drop < 4; ++drop) {
    std::vector<Triangle> open = tetrahedron();
    open.erase(open.begin() + static_cast<std::ptrdiff_t>(drop));
    EXPECT_FALSE(is_closed_surface(open)) << drop;
  }
  EXPECT_FALSE(is_closed_surface({}));
}

TEST(ClosedSurface, OneFlippedFaceIsNotClosed) {
  std::vector<Triangle> flipped = tetrahedron();
  std::swap(flipped[3].v1, flipped[3].v2);
  EXPECT_FALSE(is_closed_surface(flipped));
}

TEST(ClosedSurface, DuplicatedFacesInEitherOrientationAreNotClosed) {
  std::vector<Triangle> same = tetrahedron();
  same.push_back(same[0]);
  EXPECT_FALSE(is_closed_surface(same));
  std::vector<Triangle> opposite = tetrahedron();
  opposite.push_back({opposite[0].v0, opposite[0].v2, opposite[0].v1, 0});
  EXPECT_FALSE(is_closed_surface(opposite));
  // A face and its reverse alone: a closed (flat, two-sided) surface.
  EXPECT_TRUE(is_closed_surface(std::vector<Triangle>{{p0, p1, p2, 0}, {p0, p2, p1, 0}}));
}

TEST(ClosedSurface, NonManifoldEdgeIsNotClosedButSurfacesTouchingAtAVertexAre) {
  // Two tetrahedra sharing the edge p0-p3 (four faces on it): not closed even though every edge
  // is used as often in one direction as in the other.
  std::vector<Triangle> book = tetrahedron();
  const glm::vec3 q1{-1, 0, 0}, q2{0, -1, 0};
  for (const Triangle& t :
       std::vector<Triangle>{{p0, q1, q2, 0}, {p0, p3, q1, 0}, {p0, q2, p3, 0}, {q1, p3, q2, 0}})
    book.push_back(t);
  EXPECT_FALSE(is_closed_surface(book));
  // Two tetrahedra touching only at p1 (the second one's p0): closed.
  std::vector<Triangle> touching = tetrahedron();
  for (const Triangle& t : tetrahedron(p1)) touching.push_back(t);
  EXPECT_TRUE(is_closed_surface(touching));
}

TEST(ClosedSurface, RepeatedCornerTrianglesAreIgnoredAndSignedZerosAreOnePoint) {
  std::vector<Triangle> with_sliver = tetrahedron();
  with_sliver.push_back({p1, p1, p2, 0});
  EXPECT_TRUE(is_closed_surface(with_sliver));
  EXPECT_FALSE(is_closed_surface(std::vector<Triangle>{{p1, p1, p2, 0}, {p0, p0, p0, 0}}));
  std::vector<Triangle> signed_zeros = tetrahedron();
  signed_zeros[0].v0 = glm::vec3(-0.0f, 0.0f, -0.0f);
  EXPECT_TRUE(is_closed_surface(signed_zeros));
  // A different position, however close, is a different point: the surface opens there.
  signed_zeros[0].v0 = glm::vec3(0.0f, 0.0f, 1e-45f);
  EXPECT_FALSE(is_closed_surface(signed_zeros));
}

TEST(ClosedSurface, SubsetIsJudgedOnItsOwn) {
  std::vector<Triangle> all = tetrahedron();
  all.push_back({p0, p1, glm::vec3(5, 5, 5), 1});  // an open fin, another mesh
  EXPECT_FALSE(is_closed_surface(all));
  const std::vector<std::uint32_t> tetra{0, 1, 2, 3}, three{0, 1, 2}, fin{4};
  EXPECT_TRUE(is_closed_surface(all, tetra));
  EXPECT_FALSE(is_closed_surface(all, three));
  EXPECT_FALSE(is_closed_surface(all, fin));
}

}  // namespace
}  // namespace shadowcts
