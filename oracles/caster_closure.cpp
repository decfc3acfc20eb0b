#include "oracles/caster_closure.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <tuple>

#include <hwy/contrib/sort/vqsort.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "oracles/ordered_float_bits.h"
#include "shadowcts/distinct_key_sort.h"

namespace shadowcts {
namespace {

const glm::vec3& corner(const Triangle& t, int k) {
  return k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
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

  // Every (caster, vertex) use, as caster * 4 + k, grouped by the vertex position. Each use is a
  // 128-bit key: its position's 96 bits (the coordinates' order-preserving bits) rearranged, then
  // the use. Equal positions have equal first 96 bits, so sorting the keys puts them next to each
  // other in use order; the first 63 bits interleave the top 21 bits of the three coordinates (a
  // Morton order), so that groups near each other in space get near numbers and near places in
  // `keys`, which keeps the searches below in the cache. Neither the sort nor the grouping reads
  // the triangles. Keys are unique, so the sorted order does not depend on how it is reached.
  const std::size_t use_count = 3 * ids.size();
  const auto spread = [](std::uint64_t v) {  // bit i of a 21-bit v to bit 3 i
    v &= 0x1fffffu;
    v = (v | v << 32) & 0x001f00000000ffffULL;
    v = (v | v << 16) & 0x001f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    return (v | v << 2) & 0x1249249249249249ULL;
  };
  std::unique_ptr<hwy::uint128_t[]> keys(new hwy::uint128_t[use_count]);
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const glm::vec3& p = corner(c.triangles[ids[i]], int(k));
      const std::uint64_t x = ordered_float_bits(p.x), y = ordered_float_bits(p.y),
                          z = ordered_float_bits(p.z);
      hwy::uint128_t& key = keys[3 * i + k];
      key.hi =
          (spread(x >> 11) << 3 | spread(y >> 11) << 2 | spread(z >> 11) << 1) | (x >> 10 & 1u);
      key.lo = ((x & 0x3ffu) << 22 | (y & 0x7ffu) << 11 | (z & 0x7ffu)) << 32 | (ids[i] * 4 + k);
    }
  });
  {
    std::unique_ptr<hwy::uint128_t[]> sorted(new hwy::uint128_t[use_count]);
    sort_distinct_keys(keys.get(), use_count, sorted.get(),
                       [](const hwy::uint128_t& u, const hwy::uint128_t& v) {
                         return u.hi != v.hi ? u.hi < v.hi : u.lo < v.lo;
                       });
    keys = std::move(sorted);
  }
  const auto key_use = [&](std::size_t i) { return std::uint32_t(keys[i].lo); };
  const auto same_position = [&](std::size_t i, std::size_t j) {
    return keys[i].hi == keys[j].hi && keys[i].lo >> 32 == keys[j].lo >> 32;
  };
  // Groups numbered in key order, counted in pieces fixed by the input alone.
  constexpr std::size_t piece = std::size_t(1) << 16;
  const std::size_t pieces = (use_count + piece - 1) / piece;
  std::vector<std::uint32_t> piece_groups(pieces + 1, 0);  // groups starting before each piece
  tbb::parallel_for(std::size_t(0), pieces, [&](std::size_t p) {
    std::uint32_t starts = 0;
    for (std::size_t i = p * piece; i < std::min(use_count, (p + 1) * piece); ++i)
      starts += i == 0 || !same_position(i - 1, i);
    piece_groups[p + 1] = starts;
  });
  for (std::size_t p = 0; p < pieces; ++p) piece_groups[p + 1] += piece_groups[p];
  const std::size_t groups = piece_groups[pieces];
  // uses at keys[group_begin[g] ...] have the position of group g
  std::vector<std::size_t> group_begin(groups + 1, use_count);
  positions_.resize(groups);
  tbb::parallel_for(std::size_t(0), pieces, [&](std::size_t p) {
    std::uint32_t g = piece_groups[p];  // groups started so far: the number of the next one
    for (std::size_t i = p * piece; i < std::min(use_count, (p + 1) * piece); ++i) {
      const std::uint32_t use = key_use(i);
      if (i == 0 || !same_position(i - 1, i)) {
        group_begin[g] = i;
        positions_[g++] = corner(c.triangles[use / 4], int(use % 4));
      }
      vertex_group_[3 * std::size_t(use / 4) + use % 4] = g - 1;
    }
  });
  junction_begin_.assign(groups + 1, 0);  // no junctions known yet
  const auto group_of = [&](std::uint32_t t, int k) {
    return vertex_group_[3 * std::size_t(t) + std::size_t(k)];
  };
  // Per use in group order: the use, and the groups of its caster's next and previous vertices.
  // The searches below walk a group's uses and read these, one run of memory per group, instead
  // of every caster's vertex groups and corners.
  struct UseAround {
    std::uint32_t use, next, previous;
  };
  std::vector<UseAround> around(use_count);
  tbb::parallel_for(std::size_t(0), use_count, [&](std::size_t i) {
    const std::uint32_t use = key_use(i), t = use / 4;
    const int k = int(use % 4);
    around[i] = {use, group_of(t, (k + 1) % 3), group_of(t, (k + 2) % 3)};
  });
  keys.reset();

  // Each caster's side: light_plane_side(v0, v1, v2). The side of the third vertex against the
  // plane through an edge and the light is the same for every edge (the orientation of (L, a, b,
  // x), or det(b - a, d, x - a), is unchanged by a cyclic shift of a, b, x), and the side of a
  // caster's third vertex against an edge it shares with another caster is that caster's side,
  // negated when it runs along the edge the other way: one exact test per caster instead of one
  // per edge and candidate partner. Casters seen edge-on (0: the light in their plane, or d
  // parallel to it) cover nothing.
  std::vector<std::int8_t> side_of(n, 0);
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
    const Triangle& t = c.triangles[ids[i]];
    side_of[ids[i]] = std::int8_t(
        predicate.light_plane_side(glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)));
  });
  const auto edge_on = [&](std::uint32_t t) { return side_of[t] == 0; };

  // The closing partner of the piece between groups `from` and `to` of edge k of caster t (on
  // its line): a caster through one end of the piece with an edge on the line that reaches the
  // other end, its third vertex on the other side. Its edge either has that end as a vertex or
  // passes through it (a junction).
  // Casters are read through their vertex groups (12 bytes each, positions_ in Morton order),
  // not their triangles, which keeps this search in the cache.
  // group_a and group_b: the groups of the edge's end points.
  const auto closing_partner = [&](std::uint32_t t, int side, std::uint32_t group_a,
                                   std::uint32_t group_b, std::uint32_t from, std::uint32_t to) {
    const glm::vec3& a = positions_[group_a];
    const glm::vec3& b = positions_[group_b];
    const int axis = line_axis(a, b);
    std::uint32_t partner = no_partner;
    for (const auto& ends : {std::pair{from, to}, std::pair{to, from}}) {
      const std::uint32_t at = ends.first, target = ends.second;
      const glm::vec3& q = positions_[target];
      const bool increasing = q[axis] > positions_[at][axis];
      // The other caster's edge from its point at `at` to the vertex of group x, its third vertex
      // of group `third`; `forward`: it runs from `at` to x in the caster's order.
      const auto consider = [&](std::uint32_t other, std::uint32_t x_group,
                                std::uint32_t third_group, bool forward) {
        if (other == t || partner == several_partners) return;
        int third_side = 0;
        if (x_group == target) {  // the edge from a to b, or from b to a
          third_side = forward == (at == from) ? side_of[other] : -side_of[other];
        } else {
          const glm::vec3& x = positions_[x_group];
          if (increasing ? x[axis] < q[axis] : x[axis] > q[axis]) return;  // does not reach q
          if (x_group != group_a && x_group != group_b && !collinear(a, b, x)) return;
          third_side = predicate.light_plane_side(glm::dvec3(a), glm::dvec3(b),
                                                  glm::dvec3(positions_[third_group]));
        }
        if (third_side != -side) return;
        if (partner == no_partner)
          partner = other;
        else if (partner != other)
          partner = several_partners;
      };
      for (std::size_t i = group_begin[at]; i < group_begin[at + 1]; ++i) {
        const UseAround& u = around[i];
        consider(u.use / 4, u.next, u.previous, true);
        consider(u.use / 4, u.previous, u.next, false);
      }
      for (std::uint32_t i = junction_begin_[at]; i < junction_begin_[at + 1]; ++i) {
        const Junction& j = junctions_[i];
        const std::uint32_t third = group_of(j.triangle, (j.edge + 2) % 3);
        consider(j.triangle, group_of(j.triangle, j.edge), third, false);
        consider(j.triangle, group_of(j.triangle, (j.edge + 1) % 3), third, true);
      }
      if (partner != no_partner) break;
    }
    return partner;
  };

  // Every edge as a whole first: most are closed by an edge with the same end points. Edges are
  // taken from the group of their first end point, in group order (near in space, so the
  // searches stay in the cache); each edge is written once.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, groups, 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t g = range.begin(); g != range.end(); ++g)
                        for (std::size_t i = group_begin[g]; i < group_begin[g + 1]; ++i) {
                          const UseAround& u = around[i];
                          const std::uint32_t t = u.use / 4;
                          const int side = side_of[t];
                          // no plane through an edge and the light, or seen edge-on
                          if (side == 0) continue;
                          edge_partner_[3 * std::size_t(t) + u.use % 4] = closing_partner(
                              t, side, std::uint32_t(g), u.next, std::uint32_t(g), u.next);
                        }
                    });

  // T-junctions: caster vertices strictly inside another caster's edge. Found along collinear
  // edges, as meshes make them (splitting a triangle at an edge point): two casters at a vertex a
  // with edges a-x and a-y on one line, y strictly between a and x, put y inside the edge a-x;
  // then, from each junction y found inside an edge, an edge on the same line that starts at y
  // and ends inside that edge gives the next one. A vertex that touches an edge in no such chain
  // is not found, which only leaves pieces open (conservative).
  const auto strictly_inside = [](const glm::vec3& a, const glm::vec3& x, const glm::vec3& y) {
    const int axis = line_axis(a, x);
    return std::min(a[axis], x[axis]) < y[axis] && y[axis] < std::max(a[axis], x[axis]);
  };
  // Edges from group g (the casters at its position) that end strictly inside the edge (t, k),
  // on its line: their far ends are junctions of (t, k).
  const auto junctions_from = [&](std::size_t g, std::uint32_t t, int k,
                                  std::vector<Junction>& out) {
    const glm::vec3& a = positions_[group_of(t, k)];
    const glm::vec3& b = positions_[group_of(t, (k + 1) % 3)];
    for (std::size_t i = group_begin[g]; i < group_begin[g + 1]; ++i) {
      const UseAround& u = around[i];
      if (u.use / 4 == t) continue;
      // The far ends of the use's two edges: its next and its previous vertex.
      for (const std::uint32_t y_group : {u.next, u.previous}) {
        const glm::vec3& y = positions_[y_group];
        if (y == a || y == b || !strictly_inside(a, b, y) || !collinear(a, b, y)) continue;
        out.push_back({y_group, t, k});
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
      if (side_of[t] == 0 || edge_partner_[edge] != no_partner) continue;
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
    const int side = side_of[t];
    SplitEdge& s = splits[i]->second;
    if (side == 0) return;
    const std::uint32_t from = group_of(t, k), to = group_of(t, (k + 1) % 3);
    for (std::size_t p = 0; p <= s.points.size(); ++p)
      s.partner[p] = closing_partner(t, side, from, to, p == 0 ? from : s.points[p - 1],
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
      const UseAround& u = around[i];
      if (u.use / 4 == self) continue;
      const glm::vec3 &x1 = positions_[u.next], &x2 = positions_[u.previous];
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
      const UseAround& u = around[i];
      const std::uint32_t t = u.use / 4;
      const int k = int(u.use % 4);
      if (edge_on(t)) continue;
      any = true;
      const glm::vec3 &next = positions_[u.next], &previous = positions_[u.previous];
      if (!crossed(t, k, next, previous) || !crossed(t, (k + 2) % 3, previous, next)) return;
    }
    for (std::uint32_t i = junction_begin_[g]; i < junction_begin_[g + 1]; ++i) {
      const Junction& j = junctions_[i];
      if (edge_on(j.triangle)) continue;
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
