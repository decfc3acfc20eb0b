#include "reference/stencil/silhouette.h"

#include <algorithm>
#include <array>
#include <tuple>

#include <glm/common.hpp>

#include "reference/stencil/robust_orientation.h"
#include "shadowcts/closed_surface.h"

namespace shadowcts::stencil {
namespace {

using Position = std::array<float, 3>;

Position key(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}

// A directed edge keyed by the exact positions of its ends, stored with the smaller end first
// and the direction as a sign.
struct EdgeUse {
  Position lo, hi;
  int direction;  // +1: lo -> hi, -1: hi -> lo
  bool operator<(const EdgeUse& o) const { return std::tie(lo, hi) < std::tie(o.lo, o.hi); }
};

EdgeUse edge_use(const glm::vec3& a, const glm::vec3& b) {
  const Position pa = key(a), pb = key(b);
  return pa < pb ? EdgeUse{pa, pb, +1} : EdgeUse{pb, pa, -1};
}

// Net uses of each undirected edge, after sorting: equal keys are adjacent.
template <class Visit>
void for_each_net_edge(std::vector<EdgeUse>& uses, Visit visit) {
  std::sort(uses.begin(), uses.end());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int net = 0;
    for (; j < uses.size() && !(uses[i] < uses[j]); ++j) net += uses[j].direction;
    visit(uses[i], net);
    i = j;
  }
}

bool light_outside_box(const Case& c, const std::vector<std::uint32_t>& triangles,
                       const HardShadowLight& light) {
  if (light.directional) return true;
  glm::dvec3 lo(c.triangles[triangles[0]].v0), hi = lo;
  for (std::uint32_t i : triangles)
    for (const glm::vec3& v : {c.triangles[i].v0, c.triangles[i].v1, c.triangles[i].v2}) {
      lo = glm::min(lo, glm::dvec3(v));
      hi = glm::max(hi, glm::dvec3(v));
    }
  for (int k = 0; k < 3; ++k)
    if (light.position[k] < lo[k] || light.position[k] > hi[k]) return true;
  return false;
}

}  // namespace

int facing_sign(const Triangle& t, const HardShadowLight& light) {
  const glm::dvec3 a(t.v0), b(t.v1), d(t.v2);
  if (light.directional) return sign_of_determinant(b, a, d, a, light.direction, glm::dvec3(0.0));
  return orientation(a, b, d, light.position);
}

Occluders find_occluders(const Case& c, const HardShadowLight& light,
                         const std::vector<std::uint32_t>& excluded) {
  std::vector<std::vector<std::uint32_t>> by_mesh(c.meshes.size());
  for (std::size_t i = 0; i < c.triangles.size(); ++i)
    if (c.meshes.at(c.triangles[i].mesh).caster &&
        !std::binary_search(excluded.begin(), excluded.end(), std::uint32_t(i)))
      by_mesh[c.triangles[i].mesh].push_back(std::uint32_t(i));

  Occluders out;
  for (const std::vector<std::uint32_t>& triangles : by_mesh) {
    if (triangles.empty()) continue;
    const bool front_faces_only =
        is_closed_surface(c.triangles, triangles) && light_outside_box(c, triangles, light);
    out.closed_meshes += front_faces_only;
    std::vector<EdgeUse> uses;
    for (std::uint32_t i : triangles) {
      const Triangle& t = c.triangles[i];
      const int facing = facing_sign(t, light);
      if (facing == 0 || (front_faces_only && facing < 0)) continue;
      LightCap cap;
      cap.triangle = i;
      cap.v[0] = glm::dvec3(t.v0);
      cap.v[1] = glm::dvec3(facing > 0 ? t.v1 : t.v2);
      cap.v[2] = glm::dvec3(facing > 0 ? t.v2 : t.v1);
      out.caps.push_back(cap);
      const glm::vec3 v[3] = {t.v0, facing > 0 ? t.v1 : t.v2, facing > 0 ? t.v2 : t.v1};
      for (int k = 0; k < 3; ++k) uses.push_back(edge_use(v[k], v[(k + 1) % 3]));
    }
    for_each_net_edge(uses, [&](const EdgeUse& e, int net) {
      const glm::dvec3 lo(e.lo[0], e.lo[1], e.lo[2]), hi(e.hi[0], e.hi[1], e.hi[2]);
      for (int m = 0; m < std::abs(net); ++m)
        out.silhouette.push_back(net > 0 ? SilhouetteEdge{lo, hi} : SilhouetteEdge{hi, lo});
    });
  }
  return out;
}

}  // namespace shadowcts::stencil
