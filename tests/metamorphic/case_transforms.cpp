#include "case_transforms.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

namespace shadowcts::metamorphic {
namespace {

glm::vec3 scaled(const glm::vec3& v, int k) {
  return {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
}

template <class PointMap, class DirectionMap>
CaseWithSamples map_geometry(const CaseWithSamples& in, PointMap point, DirectionMap direction) {
  CaseWithSamples out = in;
  for (Triangle& t : out.c.triangles) t = {point(t.v0), point(t.v1), point(t.v2), t.mesh};
  for (ViewSample& s : out.samples.samples) {
    s.position = point(s.position);
    s.normal = direction(s.normal);
  }
  Camera& cam = out.c.camera;
  cam.position = point(cam.position);
  cam.target = point(cam.target);
  cam.up = direction(cam.up);
  if (out.c.light) {
    out.c.light->position = point(out.c.light->position);
    out.c.light->direction = direction(out.c.light->direction);
  }
  for (RangedLight& l : out.c.ranged_lights) {
    l.centre = point(l.centre);
    l.direction = direction(l.direction);
  }
  return out;
}

// Exact (double) point a + t (b - a) when it is a float, for t in {1/2, 1/4, 3/4}.
std::optional<glm::vec3> representable_edge_point(const glm::vec3& a, const glm::vec3& b) {
  for (const double t : {0.5, 0.25, 0.75}) {
    const glm::dvec3 p = glm::dvec3(a) + t * (glm::dvec3(b) - glm::dvec3(a));
    const glm::vec3 f(p);
    // The double value is exact (float inputs, dyadic t); keep it only if float holds it.
    if (glm::dvec3(f) == p && f != a && f != b) return f;
  }
  return std::nullopt;
}

}  // namespace

CaseWithSamples scale_by_power_of_two(const CaseWithSamples& in, int k) {
  CaseWithSamples out = map_geometry(
      in, [k](const glm::vec3& v) { return scaled(v, k); }, [](const glm::vec3& d) { return d; });
  out.c.camera.near_plane = std::ldexp(out.c.camera.near_plane, k);
  out.c.camera.far_plane = std::ldexp(out.c.camera.far_plane, k);
  for (RangedLight& l : out.c.ranged_lights) l.range = std::ldexp(l.range, k);
  return out;
}

CaseWithSamples permute_axes(const CaseWithSamples& in, const int axis[3], const float sign[3]) {
  const auto map = [axis, sign](const glm::vec3& v) {
    return glm::vec3(sign[0] * v[axis[0]], sign[1] * v[axis[1]], sign[2] * v[axis[2]]);
  };
  CaseWithSamples out = map_geometry(in, map, map);
  const float det = glm::dot(glm::cross(map({1, 0, 0}), map({0, 1, 0})), map({0, 0, 1}));
  if (det < 0.0f)
    for (Triangle& t : out.c.triangles) std::swap(t.v1, t.v2);
  return out;
}

CaseWithSamples turn_image_over(const CaseWithSamples& in, std::vector<std::size_t>& new_index) {
  CaseWithSamples out = in;
  const std::uint32_t width = in.samples.width;
  new_index.assign(in.samples.samples.size(), 0);
  for (std::size_t i = 0; i < in.samples.samples.size(); ++i) {
    ViewSample s = in.samples.samples[i];
    s.pixel_x = width - 1 - s.pixel_x;
    new_index[i] = std::size_t(s.pixel_y) * width + s.pixel_x;
    out.samples.samples[new_index[i]] = s;
  }
  return out;
}

CaseWithSamples rotate_vertex_order(const CaseWithSamples& in) {
  CaseWithSamples out = in;
  for (Triangle& t : out.c.triangles) t = {t.v1, t.v2, t.v0, t.mesh};
  return out;
}

CaseWithSamples open_meshes(const CaseWithSamples& in) {
  CaseWithSamples out = in;
  for (Mesh& m : out.c.meshes) m.closed = false;
  return out;
}

CaseWithSamples flip_winding(const CaseWithSamples& in) {
  CaseWithSamples out = open_meshes(in);
  for (Triangle& t : out.c.triangles) std::swap(t.v1, t.v2);
  return out;
}

namespace {

// order[new] = old, a pseudo-random permutation of n: Fisher-Yates with our own index draw
// (std::shuffle's sequence is implementation-defined).
std::vector<std::uint32_t> random_order(std::size_t n, std::uint64_t seed) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 random(seed);
  for (std::size_t i = n; i > 1; --i) std::swap(order[i - 1], order[random() % i]);
  return order;
}

}  // namespace

CaseWithSamples shuffle_lights(const CaseWithSamples& in, std::uint64_t seed,
                               std::vector<std::uint32_t>& old_index) {
  old_index = random_order(in.c.ranged_lights.size(), seed);
  CaseWithSamples out = in;
  for (std::size_t k = 0; k < old_index.size(); ++k)
    out.c.ranged_lights[k] = in.c.ranged_lights[old_index[k]];
  return out;
}

CaseWithSamples shuffle_triangles(const CaseWithSamples& in, std::uint64_t seed) {
  const std::size_t n = in.c.triangles.size();
  const std::vector<std::uint32_t> order = random_order(n, seed);  // order[new] = old
  std::vector<std::uint32_t> new_index(n);
  CaseWithSamples out = in;
  for (std::size_t k = 0; k < n; ++k) {
    out.c.triangles[k] = in.c.triangles[order[k]];
    new_index[order[k]] = std::uint32_t(k);
  }
  for (ViewSample& s : out.samples.samples)
    if (s.receiver != no_receiver) s.receiver = new_index[s.receiver];
  return out;
}

CaseWithSamples split_triangles(const CaseWithSamples& in, std::size_t& split_count) {
  std::vector<bool> receives(in.c.triangles.size(), false);
  for (const ViewSample& s : in.samples.samples)
    if (s.receiver != no_receiver) receives[s.receiver] = true;
  CaseWithSamples out = in;
  out.c.triangles.clear();
  std::vector<std::uint32_t> new_index(in.c.triangles.size());
  split_count = 0;
  for (std::size_t i = 0; i < in.c.triangles.size(); ++i) {
    const Triangle& t = in.c.triangles[i];
    new_index[i] = std::uint32_t(out.c.triangles.size());
    std::optional<glm::vec3> point;
    int edge = 0;  // the edge from vertex `edge` to vertex `edge + 1`
    if (!receives[i]) {
      const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
      // Longest edge first: the split then makes the least slender halves.
      int order[3] = {0, 1, 2};
      std::sort(order, order + 3, [&](int a, int b) {
        return glm::length(glm::dvec3(v[(a + 1) % 3]) - glm::dvec3(v[a])) >
               glm::length(glm::dvec3(v[(b + 1) % 3]) - glm::dvec3(v[b]));
      });
      for (const int e : order)
        if ((point = representable_edge_point(v[e], v[(e + 1) % 3]))) {
          edge = e;
          break;
        }
    }
    if (!point) {
      out.c.triangles.push_back(t);
      continue;
    }
    const glm::vec3 v[3] = {t.v0, t.v1, t.v2};
    const glm::vec3 &a = v[edge], &b = v[(edge + 1) % 3], &c = v[(edge + 2) % 3];
    // a m c and m b c: both keep the orientation of a b c.
    out.c.triangles.push_back({a, *point, c, t.mesh});
    out.c.triangles.push_back({*point, b, c, t.mesh});
    ++split_count;
  }
  for (ViewSample& s : out.samples.samples)
    if (s.receiver != no_receiver) s.receiver = new_index[s.receiver];
  return out;
}

}  // namespace shadowcts::metamorphic
