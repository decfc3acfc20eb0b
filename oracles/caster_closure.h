#pragma once
// Which parts of the casters' edges and vertices are closed towards the light: the pieces of the
// shadow boundary that the casters cover from both sides, so that they are no boundary at all.
//
// Seen from the light (centrally from a point light, along d for a directional one), a piece of
// an edge ab is closed when another caster has an edge on the same line that contains the piece,
// with its third vertex strictly on the other side of the plane through ab and the light than
// this caster's third vertex: then every point of the wedge behind the piece, except the rays
// behind the piece's end points, lies in the interior of the union of the two shadow volumes.
// An edge that no single edge covers is cut into pieces at the caster vertices inside it that
// collinear chains of edges lead to (T-junctions, as splitting a triangle at an edge point makes
// them), and each piece is closed on its own.
//
// A vertex v is closed when the casters through v that were found (those with v as a vertex, a
// sector at v's projection, and those with v inside an edge, a half plane), not seen edge-on and
// at least one, have every boundary ray of their sector at v crossed: another of them has an edge
// along that ray with its third vertex on the other side. Going round v's projection, every
// sector boundary then leads into a neighbouring sector, so the sectors cover a whole
// neighbourhood and the ray behind v lies in the interior of the union of the shadow volumes
// too. Casters through v that were not found (v inside their face, or inside an edge that no
// collinear chain of edges leads to) are not used, which is conservative.
//
// Points are equal when their float coordinates are; all tests are exact.
//
// A sample's receiver casts no shadow on it: a piece closed by the receiver alone, and a vertex the
// receiver passes through, count as open for its samples.
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "oracles/caster_bvh.h"
#include "oracles/exact_segment_triangle.h"
#include "shadowcts/case.h"

namespace shadowcts {

class CasterClosure {
 public:
  CasterClosure(const Case& c, const CasterBvh& casters, const ExactShadowPredicate& predicate);

  // Whether some part of the shadow boundary behind edge k (from vertex k to vertex k + 1 mod 3)
  // of caster t may be exposed for a sample on `receiver`: an open piece of the edge or an open
  // point of it (its end points and T-junctions).
  bool may_expose(std::uint32_t t, int k, std::uint32_t receiver) const;

  // Calls piece(a, b) for every open piece and point(x) for every open point of that edge, until
  // one returns true; returns whether one did.
  template <class Piece, class Point>
  bool any_exposed(std::uint32_t t, int k, std::uint32_t receiver, Piece&& piece,
                   Point&& point) const;

 private:
  static constexpr std::uint32_t no_partner = 0xffffffffu;
  static constexpr std::uint32_t several_partners = 0xfffffffeu;
  static constexpr std::uint32_t no_group = 0xffffffffu;

  struct Junction {  // a caster edge with a vertex position inside it
    std::uint32_t group;
    std::uint32_t triangle;
    int edge;
  };
  // An edge with T-junctions: the points inside it in order from its vertex k to vertex k + 1,
  // and the closing partner of each of the points.size() + 1 pieces between them.
  struct SplitEdge {
    std::vector<std::uint32_t> points;  // vertex groups
    std::vector<std::uint32_t> partner;
  };

  bool piece_closed(std::uint32_t partner, std::uint32_t receiver) const {
    return partner == several_partners || (partner != no_partner && partner != receiver);
  }
  bool point_closed(std::uint32_t group, std::uint32_t receiver) const;
  const glm::vec3& group_position(std::uint32_t group) const { return positions_[group]; }

  const Case& case_;
  // Per case triangle t and vertex k, [3 t + k]: the vertex group (equal positions) of casters.
  std::vector<std::uint32_t> vertex_group_;
  std::vector<glm::vec3> positions_;        // per group
  std::vector<std::uint8_t> group_closed_;  // per group
  // Per group, the casters with the position inside an edge: junctions_[junction_begin_[g] ...].
  std::vector<std::uint32_t> junction_begin_;
  std::vector<Junction> junctions_;
  // Per case triangle t and edge k, [3 t + k]: the closing partner of an edge without T-junctions
  // (no_partner also for triangles that cast no shadow); split edges are in split_edges_.
  std::vector<std::uint32_t> edge_partner_;
  std::unordered_map<std::uint32_t, SplitEdge> split_edges_;
};

template <class Piece, class Point>
bool CasterClosure::any_exposed(std::uint32_t t, int k, std::uint32_t receiver, Piece&& piece,
                                Point&& point) const {
  const std::size_t edge = 3 * std::size_t(t) + std::size_t(k);
  const std::size_t next = 3 * std::size_t(t) + std::size_t((k + 1) % 3);
  const std::uint32_t from = vertex_group_[edge], to = vertex_group_[next];
  const auto split = split_edges_.find(std::uint32_t(edge));
  if (split == split_edges_.end()) {
    if (!piece_closed(edge_partner_[edge], receiver) &&
        piece(group_position(from), group_position(to)))
      return true;
  } else {
    const SplitEdge& s = split->second;
    for (std::size_t i = 0; i <= s.points.size(); ++i) {
      const std::uint32_t a = i == 0 ? from : s.points[i - 1];
      const std::uint32_t b = i == s.points.size() ? to : s.points[i];
      if (!piece_closed(s.partner[i], receiver) && piece(group_position(a), group_position(b)))
        return true;
    }
    for (const std::uint32_t g : s.points)
      if (!point_closed(g, receiver) && point(group_position(g))) return true;
  }
  for (const std::uint32_t g : {from, to})
    if (!point_closed(g, receiver) && point(group_position(g))) return true;
  return false;
}

}  // namespace shadowcts
