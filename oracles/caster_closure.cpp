#include "oracles/caster_closure.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <tuple>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace shadowcts {
namespace {

const glm::vec3& corner(const Triangle& t, int k) {
  return k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
}

// A float's bits, mapped so that their unsigned order is the numeric order (-0 taken as +0).
std::uint32_t ordered_bits(float v) {
  v += 0.0f;  // -0 becomes +0
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  return (bits & 0x80000000u) != 0 ? ~bits : bits | 0x80000000u;
}

// The coordinate along which the points of the line through a != b are ordered (the largest
// |b - a|), and the direction of b from a along it.
int line_axis(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 d = b - a;  // only compared: rounding cannot change which one is largest by 0
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(d[k]) > std::fabs(d[axis])) axis = k;
  // A float difference rounds to 0 only when it is 0, so the axis has a[axis] != b[axis].
  return axis;
}

bool collinear(const glm::vec3& a, const glm::vec3& b, const glm::vec3& x) {
  // A cheap certificate first: a component of (b - a) x (x - a), evaluated in doubles, whose
  // magnitude exceeds its rounding bound (each difference and product rounds once, relative
  // 2^-53, so the error stays below 5 * 2^-53 of the two products' magnitudes) is not zero.
  const glm::dvec3 u = glm::dvec3(b) - glm::dvec3(a), w = glm::dvec3(x) - glm::dvec3(a);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double p = u[i] * w[j], q = u[j] * w[i];
    if (std::fabs(p - q) > 0x1p-50 * (std::fabs(p) + std::fabs(q))) return false;
  }
  return is_zero_area(Triangle{a, b, x, 0});
}

}  // namespace

CasterClosure::CasterClosure(const Case& c, const CasterBvh& casters,
                             const ExactShadowPredicate& predicate)
    : case_(c) {
  const std::size_t n = c.triangles.size();
  vertex_group_.assign(3 * n, no_group);
  edge_partner_.assign(3 * n, no_partner);
  junction_begin_.assign(1, 0);
  const std::vector<std::uint32_t>& ids = casters.triangles();
  if (ids.empty() || n > (std::size_t(1) << 30)) return;  // too many: everything stays open

  // Every (caster, vertex) use, as caster * 4 + k, grouped by the vertex position: sorted by the
  // position's coordinates as integer keys (x, y, z, then the use), so that neither the sort nor
  // the grouping reads the triangles.
  struct Use {
    std::uint64_t xy;  // ordered_bits(x) << 32 | ordered_bits(y)
    std::uint32_t z;   // ordered_bits(z)
    std::uint32_t use;
  };
  const auto use_position = [&](const Use& x) -> const glm::vec3& {
    return corner(c.triangles[x.use / 4], int(x.use % 4));
  };
  std::vector<Use> uses(3 * ids.size());
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const glm::vec3& x = corner(c.triangles[ids[i]], int(k));
      uses[3 * i + k] = {std::uint64_t(ordered_bits(x.x)) << 32 | ordered_bits(x.y),
                         ordered_bits(x.z), ids[i] * 4 + k};
    }
  });
  tbb::parallel_sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    if (x.xy != y.xy) return x.xy < y.xy;
    if (x.z != y.z) return x.z < y.z;
    return x.use < y.use;
  });
  std::vector<std::size_t> group_begin;  // uses[group_begin[g] ...] have the position of group g
  for (std::size_t i = 0; i < uses.size(); ++i) {
    if (i == 0 || uses[i - 1].xy != uses[i].xy || uses[i - 1].z != uses[i].z) {
      group_begin.push_back(i);
      positions_.push_back(use_position(uses[i]));
    }
    vertex_group_[3 * std::size_t(uses[i].use / 4) + uses[i].use % 4] =
        std::uint32_t(group_begin.size() - 1);
  }
  const std::size_t groups = group_begin.size();
  group_begin.push_back(uses.size());
  junction_begin_.assign(groups + 1, 0);  // no junctions known yet
  const auto group_of = [&](std::uint32_t t, int k) {
    return vertex_group_[3 * std::size_t(t) + std::size_t(k)];
  };

  // Casters seen edge-on (the light in their plane, or d parallel to it) cover nothing.
  std::vector<std::uint8_t> edge_on(n, 0);
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    const Triangle& t = c.triangles[ids[i]];
    edge_on[ids[i]] =
        predicate.light_plane_side(glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)) == 0;
  });

  // The closing partner of the piece between groups `from` and `to` of edge k of caster t (on
  // its line): a caster through one end of the piece with an edge on the line that reaches the
  // other end, its third vertex on the other side. Its edge either has that end as a vertex or
  // passes through it (a junction).
  const auto closing_partner = [&](std::uint32_t t, int k, int side, std::uint32_t from,
                                   std::uint32_t to) {
    const Triangle& tri = c.triangles[t];
    const glm::vec3& a = corner(tri, k);
    const glm::vec3& b = corner(tri, (k + 1) % 3);
    const int axis = line_axis(a, b);
    std::uint32_t partner = no_partner;
    for (const auto& [at, target] : {std::pair{from, to}, std::pair{to, from}}) {
      const glm::vec3& q = positions_[target];
      const bool increasing = q[axis] > positions_[at][axis];
      const auto consider = [&](std::uint32_t other, const glm::vec3& x, const glm::vec3& third) {
        if (other == t || partner == several_partners) return;
        if (increasing ? x[axis] < q[axis] : x[axis] > q[axis]) return;  // does not reach q
        if (x != a && x != b && !collinear(a, b, x)) return;
        if (predicate.light_plane_side(glm::dvec3(a), glm::dvec3(b), glm::dvec3(third)) != -side)
          return;
        if (partner == no_partner)
          partner = other;
        else if (partner != other)
          partner = several_partners;
      };
      for (std::size_t i = group_begin[at]; i < group_begin[at + 1]; ++i) {
        const std::uint32_t other = uses[i].use / 4;
        const int kv = int(uses[i].use % 4);
        const Triangle& o = c.triangles[other];
        consider(other, corner(o, (kv + 1) % 3), corner(o, (kv + 2) % 3));
        consider(other, corner(o, (kv + 2) % 3), corner(o, (kv + 1) % 3));
      }
      for (std::uint32_t i = junction_begin_[at]; i < junction_begin_[at + 1]; ++i) {
        const Junction& j = junctions_[i];
        const Triangle& o = c.triangles[j.triangle];
        const glm::vec3& third = corner(o, (j.edge + 2) % 3);
        consider(j.triangle, corner(o, j.edge), third);
        consider(j.triangle, corner(o, (j.edge + 1) % 3), third);
      }
      if (partner != no_partner) break;
    }
    return partner;
  };

  // Every edge as a whole first: most are closed by an edge with the same end points.
  std::vector<std::int8_t> side_of_third(3 * n, 0);  // the third vertex's side of each edge
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    const std::uint32_t t = ids[i];
    const Triangle& tri = c.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int side = predicate.light_plane_side(glm::dvec3(corner(tri, k)),
                                                  glm::dvec3(corner(tri, (k + 1) % 3)),
                                                  glm::dvec3(corner(tri, (k + 2) % 3)));
      side_of_third[3 * std::size_t(t) + std::size_t(k)] = std::int8_t(side);
      if (side == 0) continue;  // no plane through the edge and the light, or seen edge-on
      edge_partner_[3 * std::size_t(t) + std::size_t(k)] =
          closing_partner(t, k, side, group_of(t, k), group_of(t, (k + 1) % 3));
    }
  });

  // T-junctions: caster vertices strictly inside another caster's edge. Found along collinear
  // edges, as meshes make them (splitting a triangle at an edge point): two casters at a vertex a
  // with edges a-x and a-y on one line, y strictly between a and x, put y inside the edge a-x;
  // then, from each junction y found inside an edge, an edge on the same line that starts at y
  // and ends inside that edge gives the next one. A vertex that touches an edge in no such chain
  // is not found, which only leaves pieces open (conservative).
  struct EdgeEnd {  // an edge of a caster seen from one of its end points
    std::uint32_t triangle;
    int edge;   // from vertex `edge` to vertex `edge + 1`
    int other;  // the vertex index of the other end point
  };
  const auto edges_at = [&](std::uint32_t t, int k, EdgeEnd out[2]) {
    out[0] = {t, k, (k + 1) % 3};            // from vertex k
    out[1] = {t, (k + 2) % 3, (k + 2) % 3};  // to vertex k
  };
  const auto strictly_inside = [](const glm::vec3& a, const glm::vec3& x, const glm::vec3& y) {
    const int axis = line_axis(a, x);
    return std::min(a[axis], x[axis]) < y[axis] && y[axis] < std::max(a[axis], x[axis]);
  };
  // Edges from group g (the casters at its position) that end strictly inside the edge (t, k),
  // on its line: their far ends are junctions of (t, k).
  const auto junctions_from = [&](std::size_t g, std::uint32_t t, int k,
                                  std::vector<Junction>& out) {
    const Triangle& tri = c.triangles[t];
    const glm::vec3& a = corner(tri, k);
    const glm::vec3& b = corner(tri, (k + 1) % 3);
    for (std::size_t i = group_begin[g]; i < group_begin[g + 1]; ++i) {
      const std::uint32_t other = uses[i].use / 4;
      if (other == t) continue;
      EdgeEnd ends[2];
      edges_at(other, int(uses[i].use % 4), ends);
      for (const EdgeEnd& e : ends) {
        const glm::vec3& y = corner(c.triangles[other], e.other);
        if (y == a || y == b || !strictly_inside(a, b, y) || !collinear(a, b, y)) continue;
        out.push_back({group_of(other, e.other), t, k});
      }
    }
  };
  // Only edges that no single edge closes need cutting (a junction inside a closed edge would
  // only add a member around the junction vertex; leaving it out is conservative).
  std::vector<std::vector<Junction>> found(ids.size());
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    const std::uint32_t t = ids[i];
    for (int k = 0; k < 3; ++k) {
      const std::size_t edge = 3 * std::size_t(t) + std::size_t(k);
      if (side_of_third[edge] == 0 || edge_partner_[edge] != no_partner) continue;
      junctions_from(group_of(t, k), t, k, found[i]);
      junctions_from(group_of(t, (k + 1) % 3), t, k, found[i]);
    }
  });
  std::vector<Junction> all;
  std::set<std::tuple<std::uint32_t, int, std::uint32_t>> seen;
  const auto add = [&](const Junction& j) {
    if (seen.insert({j.triangle, j.edge, j.group}).second) all.push_back(j);
  };
  for (const std::vector<Junction>& f : found)
    for (const Junction& j : f) add(j);
  found.clear();
  for (std::size_t next = 0; next < all.size(); ++next) {  // along the chains
    std::vector<Junction> more;
    const Junction j = all[next];
    junctions_from(j.group, j.triangle, j.edge, more);
    for (const Junction& m : more) add(m);
  }
  std::sort(all.begin(), all.end(), [](const Junction& x, const Junction& y) {
    if (x.group != y.group) return x.group < y.group;
    if (x.triangle != y.triangle) return x.triangle < y.triangle;
    return x.edge < y.edge;
  });
  junctions_ = std::move(all);
  for (std::size_t g = 0, i = 0; g < groups; ++g) {
    while (i < junctions_.size() && junctions_[i].group == g) ++i;
    junction_begin_[g + 1] = std::uint32_t(i);
  }

  // Split edges: their T-junctions in order along the edge.
  for (const Junction& j : junctions_)
    split_edges_[3 * j.triangle + std::uint32_t(j.edge)].points.push_back(j.group);
  for (auto& [edge, split] : split_edges_) {
    const Triangle& t = c.triangles[edge / 3];
    const glm::vec3& a = corner(t, int(edge % 3));
    const glm::vec3& b = corner(t, int(edge % 3 + 1) % 3);
    const int axis = line_axis(a, b);
    const bool increasing = b[axis] > a[axis];
    std::sort(split.points.begin(), split.points.end(), [&](std::uint32_t x, std::uint32_t y) {
      return increasing ? positions_[x][axis] < positions_[y][axis]
                        : positions_[x][axis] > positions_[y][axis];
    });
    split.partner.assign(split.points.size() + 1, no_partner);
  }

  // The pieces of the split edges. Each edge is one task, writing only its own entries.
  std::vector<std::pair<const std::uint32_t, SplitEdge>*> splits;
  for (auto& entry : split_edges_) splits.push_back(&entry);
  tbb::parallel_for(std::size_t(0), splits.size(), [&](std::size_t i) {
    const std::uint32_t t = splits[i]->first / 3;
    const int k = int(splits[i]->first % 3);
    const int side = side_of_third[splits[i]->first];
    SplitEdge& s = splits[i]->second;
    if (side == 0) return;
    const std::uint32_t from = group_of(t, k), to = group_of(t, (k + 1) % 3);
    for (std::size_t p = 0; p <= s.points.size(); ++p)
      s.partner[p] = closing_partner(t, k, side, p == 0 ? from : s.points[p - 1],
                                     p == s.points.size() ? to : s.points[p]);
  });

  // Vertices. The covering argument (caster_closure.h) needs every boundary ray of a member's
  // sector at v crossed by a member on the other side, and that member must itself be one of
  // those checked: a caster with v as a vertex, or one with v inside an edge found above.
  const auto dv = [](const glm::vec3& x) { return glm::dvec3(x); };
  const auto member = [&](std::uint32_t t, std::size_t g) {
    for (int k = 0; k < 3; ++k)
      if (group_of(t, k) == g) return true;
    for (std::uint32_t i = junction_begin_[g]; i < junction_begin_[g + 1]; ++i)
      if (junctions_[i].triangle == t) return true;
    return false;
  };
  // The closing partner of the piece of edge k of caster t next to group g.
  const auto piece_partner = [&](std::uint32_t t, int k, std::size_t g) {
    const std::size_t edge = 3 * std::size_t(t) + std::size_t(k);
    const auto split = split_edges_.find(std::uint32_t(edge));
    if (split == split_edges_.end()) return edge_partner_[edge];
    const SplitEdge& s = split->second;
    if (g == group_of(t, k)) return s.partner.front();
    if (g == group_of(t, (k + 1) % 3)) return s.partner.back();
    return no_partner;  // not reached for the pieces asked for
  };
  // Whether a member at g other than `self` has an edge along the ray from v through w, with its
  // third vertex strictly on the other side of the plane through v, w and the light than `third`.
  const auto ray_crossed = [&](std::size_t g, std::uint32_t self, const glm::vec3& w,
                               const glm::vec3& third) {
    const glm::vec3& v = positions_[g];
    const int side = predicate.light_plane_side(dv(v), dv(w), dv(third));
    if (side == 0) return false;
    const int axis = line_axis(v, w);
    const bool increasing = w[axis] > v[axis];
    const auto along = [&](const glm::vec3& x) {
      if (increasing ? x[axis] <= v[axis] : x[axis] >= v[axis]) return false;
      return x == w || collinear(v, w, x);
    };
    const auto opposite = [&](const glm::vec3& x) {
      return predicate.light_plane_side(dv(v), dv(w), dv(x)) == -side;
    };
    for (std::size_t i = group_begin[g]; i < group_begin[g + 1]; ++i) {
      const std::uint32_t other = uses[i].use / 4;
      if (other == self) continue;
      const int kv = int(uses[i].use % 4);
      const Triangle& o = c.triangles[other];
      const glm::vec3 &x1 = corner(o, (kv + 1) % 3), &x2 = corner(o, (kv + 2) % 3);
      if ((along(x1) && opposite(x2)) || (along(x2) && opposite(x1))) return true;
    }
    for (std::uint32_t i = junction_begin_[g]; i < junction_begin_[g + 1]; ++i) {
      const Junction& j = junctions_[i];
      if (j.triangle == self) continue;
      const Triangle& o = c.triangles[j.triangle];
      if ((along(corner(o, j.edge)) || along(corner(o, (j.edge + 1) % 3))) &&
          opposite(corner(o, (j.edge + 2) % 3)))
        return true;
    }
    return false;
  };
  group_closed_.assign(groups, 0);
  tbb::parallel_for(std::size_t(0), groups, [&](std::size_t g) {
    bool any = false;
    // The ray along the piece of edge k of t next to v towards w: crossed by the piece's
    // partner when that is a member, else by a search among the members.
    const auto crossed = [&](std::uint32_t t, int k, const glm::vec3& w, const glm::vec3& third) {
      const std::uint32_t partner = piece_partner(t, k, g);
      if (partner != no_partner && partner != several_partners && member(partner, g)) return true;
      return ray_crossed(g, t, w, third);
    };
    for (std::size_t i = group_begin[g]; i < group_begin[g + 1]; ++i) {
      const std::uint32_t t = uses[i].use / 4;
      const int k = int(uses[i].use % 4);
      if (edge_on[t]) continue;
      any = true;
      const Triangle& tri = c.triangles[t];
      const glm::vec3 &next = corner(tri, (k + 1) % 3), &previous = corner(tri, (k + 2) % 3);
      if (!crossed(t, k, next, previous) || !crossed(t, (k + 2) % 3, previous, next)) return;
    }
    for (std::uint32_t i = junction_begin_[g]; i < junction_begin_[g + 1]; ++i) {
      const Junction& j = junctions_[i];
      if (edge_on[j.triangle]) continue;
      any = true;
      const Triangle& tri = c.triangles[j.triangle];
      const glm::vec3& third = corner(tri, (j.edge + 2) % 3);
      if (!ray_crossed(g, j.triangle, corner(tri, j.edge), third) ||
          !ray_crossed(g, j.triangle, corner(tri, (j.edge + 1) % 3), third))
        return;
    }
    group_closed_[g] = any ? 1 : 0;
  });
}

bool CasterClosure::point_closed(std::uint32_t group, std::uint32_t receiver) const {
  if (!group_closed_[group]) return false;
  if (receiver >= case_.triangles.size()) return true;
  // The receiver is one of the casters through the point: without it the cover may break.
  for (int k = 0; k < 3; ++k)
    if (vertex_group_[3 * std::size_t(receiver) + std::size_t(k)] == group) return false;
  for (std::uint32_t i = junction_begin_[group]; i < junction_begin_[group + 1]; ++i)
    if (junctions_[i].triangle == receiver) return false;
  return true;
}

bool CasterClosure::may_expose(std::uint32_t t, int k, std::uint32_t receiver) const {
  return any_exposed(
      t, k, receiver, [](const glm::vec3&, const glm::vec3&) { return true; },
      [](const glm::vec3&) { return true; });
}

}  // namespace shadowcts
