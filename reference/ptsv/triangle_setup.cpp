#include "reference/ptsv/triangle_setup.h"

#include "reference/closed_mesh_culling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "shadowcts/errors.h"
#include "shadowcts/geometry/camera_frame.h"
#include "shadowcts/geometry/exact_orientation.h"
#include "shadowcts/geometry/triangle_area.h"

namespace shadowcts::ptsv {
namespace {

bool lexicographically_less(const glm::vec3& a, const glm::vec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

struct LightGeometry {
  bool directional = false;
  glm::vec3 position{0.0f};   // point light
  glm::vec3 direction{0.0f};  // directional: towards the light
  // The light "direction" of the plane through points a, b: L - a, or d.
  glm::dvec3 towards_light(const glm::dvec3& a) const {
    return directional ? glm::dvec3(direction) : glm::dvec3(position) - a;
  }
};

LightGeometry light_geometry(const Case& c) {
  if (!c.light || c.light->kind == ShadowLightKind::sun_disk)
    throw InputError(c.source, "light", "ptsv needs a point or directional light");
  LightGeometry g;
  g.directional = c.light->kind == ShadowLightKind::directional;
  g.position = c.light->position;
  g.direction = c.light->direction;
  if (g.directional && g.direction == glm::vec3(0.0f))
    throw InputError(c.source, "light.direction", "has zero length");
  return g;
}

// Unit plane through anchor with normal direction n, oriented so that `outside_sign` * n points
// outwards; false when n has no usable length.
bool make_plane(const glm::dvec3& n, const glm::dvec3& anchor, int outside_sign, Plane& plane) {
  const double length = glm::length(n);
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  plane.normal = (double(outside_sign) / length) * n;
  plane.anchor = anchor;
  plane.shift = 0.0;
  return true;
}

// Moves a culling plane outwards until it has the whole volume inside: the triangle's vertices
// and, up to the scene bound, the rays leaving them away from the light. Every point of the
// truncated volume is Y + t dir(Y) with Y in the triangle and dir(Y) a convex combination of the
// vertices' ray directions, so the plane's value there is at most max value at a vertex plus
// t_max times the largest positive slope along a ray. False when that bound is not finite.
bool contain_volume(Plane& plane, const std::array<glm::dvec3, 3>& vertices,
                    const std::array<glm::dvec3, 3>& ray_directions, double t_max) {
  double highest = -std::numeric_limits<double>::infinity(), slope = 0.0;
  for (int i = 0; i < 3; ++i) {
    highest = std::max(highest, plane.at(vertices[std::size_t(i)]));
    slope = std::max(slope, glm::dot(plane.normal, ray_directions[std::size_t(i)]));
  }
  const double reach = highest + (slope > 0.0 ? slope * t_max : 0.0);
  if (!std::isfinite(reach)) return false;
  plane.shift -= reach;
  return true;
}

}  // namespace

double trivial_accept_bias(double scene_bound) {
  return scene_bound * 0x1p-20;
}

std::vector<bool> front_face_culling_meshes(const Case& c, const ViewSamples& samples,
                                            const std::vector<double>& sample_reach) {
  const std::uint32_t width = samples.width, height = samples.height;
  const std::vector<bool> safe = meshes_safe_for_face_culling(c, samples);
  std::vector<bool> culled(c.meshes.size(), false);
  const double tan_half_fov = camera_frame(c.camera).tan_half_fov;
  const double aspect = double(width) / double(height);
  // Radius of a ball around the eye holding the near rectangle (primary rays start there).
  const double reach = double(c.camera.near_plane) *
                       std::sqrt(1.0 + tan_half_fov * tan_half_fov * (1.0 + aspect * aspect)) *
                       (1.0 + 0x1p-20);
  const glm::dvec3 eye(c.camera.position);
  std::vector<glm::dvec3> lo(c.meshes.size(), glm::dvec3(std::numeric_limits<double>::infinity()));
  std::vector<glm::dvec3> hi(c.meshes.size(), -lo.front());
  for (const Triangle& t : c.triangles) {
    if (t.mesh >= c.meshes.size()) continue;  // reported by the setup
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) {
      lo[t.mesh] = glm::min(lo[t.mesh], glm::dvec3(v));
      hi[t.mesh] = glm::max(hi[t.mesh], glm::dvec3(v));
    }
  }
  for (std::size_t m = 0; m < c.meshes.size(); ++m) {
    if (!safe[m]) continue;  // a sample or the light may be inside the solid
    bool clear = false;
    for (int k = 0; k < 3; ++k)
      clear = clear || eye[k] + reach < lo[m][k] || eye[k] - reach > hi[m][k];
    culled[m] = clear;
  }
  // A sample further than its reach from the box along one axis is further from every point of
  // the mesh: each face hit on its segment counts, and the crossing argument holds as without the
  // rule. Float coordinates are exact in double; the differences round by 2^-53 of themselves,
  // far below the reach's own margin.
  if (sample_reach.size() != samples.samples.size())
    throw std::logic_error("ptsv: one reject reach per sample expected");
  std::vector<std::size_t> candidates;
  for (std::size_t m = 0; m < c.meshes.size(); ++m)
    if (culled[m]) candidates.push_back(m);
  for (std::size_t i = 0; i < samples.samples.size() && !candidates.empty(); ++i) {
    const ViewSample& s = samples.samples[i];
    const double r = sample_reach[i];
    if (s.sample_class != SampleClass::regular || !(r > 0.0)) continue;
    const glm::dvec3 p(s.position);
    std::erase_if(candidates, [&](std::size_t m) {
      bool far = false;
      for (int k = 0; k < 3; ++k) far = far || lo[m][k] - p[k] > r || p[k] - hi[m][k] > r;
      if (!far) culled[m] = false;
      return !far;
    });
  }
  return culled;
}

std::optional<CanonicalCaster> canonical_caster(const Case& c, std::size_t i,
                                                const std::vector<bool>& culled_meshes,
                                                bool directional, const glm::vec3& light,
                                                SetupCounts& counts) {
  const Triangle& t = c.triangles[i];
  if (t.mesh >= c.meshes.size())
    throw InputError(c.source, "triangles[" + std::to_string(i) + "].mesh",
                     "mesh id " + std::to_string(t.mesh) + " out of range");
  if (!c.meshes[t.mesh].caster) return std::nullopt;
  ++counts.casters;
  if (triangle_has_zero_area(t.v0, t.v1, t.v2)) {
    ++counts.zero_area;
    return std::nullopt;
  }
  const int winding = directional
                          ? geometry::orientation_towards(glm::dvec3(t.v0), glm::dvec3(t.v1),
                                                          glm::dvec3(t.v2), glm::dvec3(light))
                          : geometry::orientation(glm::dvec3(t.v0), glm::dvec3(t.v1),
                                                  glm::dvec3(t.v2), glm::dvec3(light));
  if (winding == 0) {
    ++counts.edge_on;
    return std::nullopt;
  }
  if (culled_meshes[t.mesh] && winding > 0) {
    ++counts.front_faces_culled;
    return std::nullopt;
  }
  // Canonical vertex order p < q < r; each swap flips the orientation.
  CanonicalCaster caster{{t.v0, t.v1, t.v2}, winding};
  std::array<glm::vec3, 3>& v = caster.vertices;
  for (int pass = 0; pass < 2; ++pass)
    for (int k = 0; k < 2 - pass; ++k)
      if (lexicographically_less(v[std::size_t(k) + 1], v[std::size_t(k)])) {
        std::swap(v[std::size_t(k)], v[std::size_t(k) + 1]);
        caster.orientation = -caster.orientation;
      }
  return caster;
}

bool set_up_shadow_volume(const Case& c, std::size_t i, const std::vector<bool>& culled_meshes,
                          const SetupOptions& options, double scene_bound, SetupCounts& counts,
                          ShadowVolume& volume) {
  const LightGeometry light = light_geometry(c);
  const glm::dvec3 eye(c.camera.position);
  // Any two points within the scene bound are at most this far apart.
  const double diameter = 2.0 * std::sqrt(3.0) * scene_bound;
  {
    const std::optional<CanonicalCaster> caster =
        canonical_caster(c, i, culled_meshes, light.directional,
                         light.directional ? light.direction : light.position, counts);
    if (!caster) return false;
    const std::array<glm::vec3, 3>& v = caster->vertices;
    const int orientation = caster->orientation;
    const std::array<glm::dvec3, 3> d = {glm::dvec3(v[0]), glm::dvec3(v[1]), glm::dvec3(v[2])};

    volume = ShadowVolume{};
    volume.triangle = std::uint32_t(i);
    // Edges (p, q), (q, r), (p, r) with opposite vertices r, p, q. det[b - a, L - a, c - a] is
    // -orientation(a, b, c): -o for the even permutations (p, q, r) and (q, r, p), +o for the
    // odd (p, r, q). The opposite vertex must come out negative (inside).
    static constexpr int edge_first[3] = {0, 1, 0}, edge_second[3] = {1, 2, 2};
    static constexpr int edge_parity[3] = {1, 1, -1};
    bool usable = true;
    const auto condition = [](const glm::dvec3& x, const glm::dvec3& y) {
      return glm::length(x) * glm::length(y) / glm::length(glm::cross(x, y));
    };
    for (int e = 0; e < 3; ++e) {
      const glm::dvec3& a = d[std::size_t(edge_first[e])];
      const glm::dvec3& b = d[std::size_t(edge_second[e])];
      const int opposite_side = -edge_parity[e] * orientation;
      usable = usable && make_plane(glm::cross(b - a, light.towards_light(a)), a, -opposite_side,
                                    volume.edges[std::size_t(e)]);
      volume.exact.edge_outside[std::size_t(e)] = std::int8_t(-opposite_side);
      volume.exact.condition[std::size_t(e)] = condition(b - a, light.towards_light(a));
    }
    // Triangle plane: det[q - p, r - p, L - p] = o, and the light's side is outside.
    usable = usable && make_plane(glm::cross(d[1] - d[0], d[2] - d[0]), d[0], orientation,
                                  volume.triangle_plane);
    volume.exact.vertices = v;
    volume.exact.triangle_outside = std::int8_t(orientation);
    volume.exact.directional = light.directional;
    volume.exact.light = light.directional ? light.direction : light.position;
    volume.exact.condition[3] = condition(d[1] - d[0], d[2] - d[0]);
    if (!usable) {
      ++counts.edge_on;  // a cross product underflowed: as good as edge-on
      return false;
    }

    // Ray directions of the volume's edges, and how far along them a sample can lie.
    std::array<glm::dvec3, 3> rays;
    for (int k = 0; k < 3; ++k)
      rays[std::size_t(k)] = light.directional ? -glm::dvec3(light.direction)
                                               : d[std::size_t(k)] - glm::dvec3(light.position);
    double t_max;
    if (light.directional) {
      t_max = diameter / glm::length(glm::dvec3(light.direction));
    } else {
      // |Y - L| >= the light's distance to the triangle's plane for every Y in the triangle.
      const double light_height = volume.triangle_plane.at(glm::dvec3(light.position));
      t_max =
          light_height > 0.0 ? diameter / light_height : std::numeric_limits<double>::infinity();
    }

    if (options.extra_planes) {
      // Vertex k's two edges: p: (p,q), (p,r); q: (p,q), (q,r); r: (q,r), (p,r).
      static constexpr int vertex_edges[3][2] = {{0, 2}, {0, 1}, {1, 2}};
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 to_light = glm::normalize(light.towards_light(d[std::size_t(k)]));
        // Unstable where the triangle is seen almost edge-on from the light (the paper skips).
        if (std::fabs(glm::dot(volume.triangle_plane.normal, to_light)) < 1e-3) continue;
        glm::dvec3 half = volume.edges[std::size_t(vertex_edges[k][0])].normal +
                          volume.edges[std::size_t(vertex_edges[k][1])].normal;
        half -= glm::dot(half, to_light) * to_light;
        if (!(glm::length(half) > 1e-2)) continue;  // the two planes nearly opposite: no wedge
        Plane plane;
        if (!make_plane(half, d[std::size_t(k)], 1, plane)) continue;
        if (!contain_volume(plane, d, rays, t_max)) continue;
        volume.extra[std::size_t(volume.extra_count++)] = plane;
      }
      counts.extra_planes += std::uint64_t(volume.extra_count);
    }

    if (options.silhouette_planes) {
      for (int k = 0; k < 3; ++k) {
        const glm::dvec3 from_eye = d[std::size_t(k)] - eye;
        const glm::dvec3 light_from_eye =
            light.directional ? glm::dvec3(light.direction) : glm::dvec3(light.position) - eye;
        const glm::dvec3 n = glm::cross(light_from_eye, from_eye);
        if (!(glm::length(n) > 1e-12 * glm::length(light_from_eye) * glm::length(from_eye)))
          continue;  // eye, light and vertex in a line
        Plane plane;
        if (!make_plane(n, eye, 1, plane)) continue;
        const double first = plane.at(d[std::size_t((k + 1) % 3)]);
        const double second = plane.at(d[std::size_t((k + 2) % 3)]);
        if (first <= 0.0 && second <= 0.0) {
          // the other two vertices inside: a silhouette edge as it is
        } else if (first >= 0.0 && second >= 0.0) {
          plane.normal = -plane.normal;
        } else {
          continue;  // the projected volume lies on both sides of this line
        }
        if (!contain_volume(plane, d, rays, t_max)) continue;
        volume.silhouette[std::size_t(volume.silhouette_count++)] = plane;
      }
      counts.silhouette_planes += std::uint64_t(volume.silhouette_count);
    }
    ++counts.volumes;
  }
  return true;
}

std::vector<ShadowVolume> set_up_shadow_volumes(const Case& c,
                                                const std::vector<bool>& culled_meshes,
                                                const SetupOptions& options, double scene_bound,
                                                SetupCounts& counts) {
  light_geometry(c);  // throws without a point or directional light, even without triangles
  // A slot per triangle up front: growing by doubling held the old and the new array at once
  // (1.5 times the final size at 900k volumes); slots never written are never touched.
  std::vector<ShadowVolume> volumes;
  volumes.reserve(c.triangles.size());
  ShadowVolume volume;
  for (std::size_t i = 0; i < c.triangles.size(); ++i)
    if (set_up_shadow_volume(c, i, culled_meshes, options, scene_bound, counts, volume))
      volumes.push_back(volume);
  return volumes;
}

}  // namespace shadowcts::ptsv
