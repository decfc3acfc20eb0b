// libFuzzer target: shared-edge watertightness. The bytes choose a surface with dyadic (exact)
// vertices — a closed fan around an apex, a closed bipyramid, a closed box whose faces are
// tessellated grids, or a T-junction (a vertex on another triangle's edge, not shared) — a point
// or directional light, and samples whose segment to the light passes exactly through a shared
// vertex or a point of a shared edge (or within a few ulps of one). Every registered algorithm
// must agree with the exact oracle on every sample the oracle calls robust: through a shared
// edge of a closed fan that is "shadowed" under every perturbation, so a leak there is a real
// failure; at T-junctions the exact answer decides (Embree, whose float test is watertight only
// inside edges shared vertex to vertex, is run but not compared on T-junction surfaces and on
// samples aimed at shared vertices: documented limits of the peer). Violations are shrunk and
// written as reproducers (support/conformance_check.h).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "support/conformance_check.h"
#include "support/fuzz_input.h"
#include "support/reproducer.h"

namespace shadowcts::fuzzing {
namespace {

// Points of the surface that shadow rays are aimed through.
struct Features {
  std::vector<glm::vec3> points;
  std::vector<bool> is_vertex;
  // Adds the edge's first end (a shared vertex) and dyadic points along it.
  void edge(const glm::vec3& a, const glm::vec3& b) {
    points.push_back(a);
    is_vertex.push_back(true);
    for (int k = 1; k < 8; ++k) {
      points.push_back(a + (float(k) / 8.0f) * (b - a));
      is_vertex.push_back(false);
    }
  }
};

class SurfaceBuilder {
 public:
  SurfaceBuilder(SampleCase& sample_case, const AxisSymmetry& symmetry, bool closed)
      : case_(sample_case), symmetry_(symmetry), closed_(closed) {
    const glm::vec3 x = symmetry({1, 0, 0}), y = symmetry({0, 1, 0}), z = symmetry({0, 0, 1});
    mirrors_ = glm::dot(glm::cross(x, y), z) < 0.0f;
  }
  // A mirroring symmetry would turn a closed mesh inside out: its triangles are flipped back.
  void triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    if (mirrors_ && closed_)
      case_.add_triangle(symmetry_(a), symmetry_(c), symmetry_(b));
    else
      case_.add_triangle(symmetry_(a), symmetry_(b), symmetry_(c));
  }
  glm::vec3 world(const glm::vec3& v) const { return symmetry_(v); }

 private:
  SampleCase& case_;
  AxisSymmetry symmetry_;
  bool closed_;
  bool mirrors_ = false;
};

// Rim of `n` points around `centre` in the local x-z plane, radius ~1 with dyadic jitter, and
// heights from the bytes: star-shaped around the centre, so fans over it usually cover it.
std::vector<glm::vec3> rim(FuzzedDataProvider& in, const glm::vec3& centre, int n) {
  std::vector<glm::vec3> points;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * 3.14159265358979323846 * i / n;
    const float radius = 1.0f + dyadic(in, 8, 4);
    // Cosine and sine rounded to multiples of 1/64: exact, and still going around.
    const float cx = std::round(float(std::cos(angle)) * 64.0f) / 64.0f;
    const float cz = std::round(float(std::sin(angle)) * 64.0f) / 64.0f;
    points.push_back(centre + glm::vec3(radius * cx, dyadic(in, 8, 4), radius * cz));
  }
  return points;
}

void closed_fan(FuzzedDataProvider& in, SurfaceBuilder& surface, Features& features,
                const glm::vec3& centre) {
  const int n = in.ConsumeIntegralInRange<int>(3, 12);
  const glm::vec3 apex = centre + glm::vec3(0.0f, 0.5f + dyadic(in, 8, 3), 0.0f);
  const std::vector<glm::vec3> ring = rim(in, centre, n);
  for (int i = 0; i < n; ++i) {
    surface.triangle(apex, ring[i], ring[(i + 1) % n]);
    features.edge(surface.world(apex), surface.world(ring[i]));
  }
}

void bipyramid(FuzzedDataProvider& in, SurfaceBuilder& surface, Features& features,
               const glm::vec3& centre) {
  const int n = in.ConsumeIntegralInRange<int>(3, 10);
  const glm::vec3 top = centre + glm::vec3(0.0f, 1.0f + dyadic(in, 8, 3), 0.0f);
  const glm::vec3 bottom = centre - glm::vec3(0.0f, 1.0f + dyadic(in, 8, 3), 0.0f);
  const std::vector<glm::vec3> ring = rim(in, centre, n);
  for (int i = 0; i < n; ++i) {
    const glm::vec3 &a = ring[i], &b = ring[(i + 1) % n];
    surface.triangle(top, b, a);  // outward: the rim runs counter-clockwise seen from below
    surface.triangle(bottom, a, b);
    features.edge(surface.world(top), surface.world(a));
    features.edge(surface.world(bottom), surface.world(a));
    features.edge(surface.world(a), surface.world(b));
  }
}

// Closed box, each face an n x n grid (n = 1, 2, 4) of cells with uniform or alternating diagonals.
void tessellated_box(FuzzedDataProvider& in, SurfaceBuilder& surface, Features& features,
                     const glm::vec3& centre) {
  // Powers of two only: the grid steps stay dyadic, so the faces meet bit for bit.
  const int n = 1 << in.ConsumeIntegralInRange<int>(0, 2);
  const bool alternating = in.ConsumeBool();
  const glm::vec3 half(0.5f + dyadic(in, 8, 4), 0.5f + dyadic(in, 8, 4), 0.5f + dyadic(in, 8, 4));
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.0f, 1.0f}) {
      // u, v span the face; u x v points along side * axis (outwards).
      const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
      glm::vec3 u(0.0f), v(0.0f), origin = centre;
      u[ua] = 2.0f * half[ua] / float(n);
      v[va] = 2.0f * half[va] / float(n);
      origin[axis] += side * half[axis];
      origin[ua] -= half[ua];
      origin[va] -= half[va];
      if (side < 0.0f) std::swap(u, v);
      const auto at = [&](int i, int j) { return origin + float(i) * u + float(j) * v; };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const glm::vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if (alternating && (i + j) % 2) {
            surface.triangle(a, b, d);
            surface.triangle(b, c, d);
            features.edge(surface.world(b), surface.world(d));
          } else {
            surface.triangle(a, b, c);
            surface.triangle(a, c, d);
            features.edge(surface.world(a), surface.world(c));
          }
          features.edge(surface.world(a), surface.world(b));
          features.edge(surface.world(a), surface.world(d));
        }
    }
}

// One triangle on one side of edge ab; on the other side two triangles meeting at m, a dyadic
// point of ab: m is a vertex of two triangles but lies inside the first one's edge.
void t_junction(FuzzedDataProvider& in, SurfaceBuilder& surface, Features& features,
                const glm::vec3& centre) {
  const glm::vec3 a = centre + glm::vec3(-1.0f, 0.0f, 0.0f) + 0.125f * dyadic_point(in, 4, 2);
  const glm::vec3 b = centre + glm::vec3(1.0f, 0.0f, 0.0f) + 0.125f * dyadic_point(in, 4, 2);
  const glm::vec3 c = centre + glm::vec3(0.0f, dyadic(in, 4, 2), -1.0f);
  const glm::vec3 d = centre + glm::vec3(0.0f, dyadic(in, 4, 2), 1.0f);
  const glm::vec3 m = a + (float(in.ConsumeIntegralInRange<int>(1, 7)) / 8.0f) * (b - a);
  surface.triangle(a, c, b);
  surface.triangle(a, m, d);
  surface.triangle(m, b, d);
  features.edge(surface.world(a), surface.world(b));
  features.edge(surface.world(m), surface.world(d));
}

}  // namespace
}  // namespace shadowcts::fuzzing

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shadowcts;
  using namespace shadowcts::fuzzing;
  FuzzedDataProvider in(data, size);
  SampleCase s;
  s.c.name = "fuzz.watertight";
  s.c.source = "fuzz_watertight";
  s.c.parameters.threads = 1;
  ShadowLight light;
  if (in.ConsumeIntegralInRange<int>(0, 3) != 0) {
    light.kind = ShadowLightKind::point;
    light.position = glm::vec3(dyadic(in, 32, 0), 8.0f + dyadic(in, 16, 0), dyadic(in, 32, 0));
  } else {
    light.kind = ShadowLightKind::directional;
    glm::vec3 d(dyadic(in, 2, 0), 1.0f + dyadic(in, 1, 0), dyadic(in, 2, 0));
    if (d == glm::vec3(0.0f)) d.y = 1.0f;
    light.direction = manifest_stable_direction(d);
  }
  const AxisSymmetry symmetry = AxisSymmetry::read(in);
  light.position = symmetry(light.position);
  if (light.kind == ShadowLightKind::directional)
    light.direction = manifest_stable_direction(symmetry(light.direction));
  s.c.light = light;

  // The receiver of every sample: a triangle that casts nothing, so it never hides anything.
  s.begin_mesh("receiver", false, false);
  const std::uint32_t receiver = s.add_triangle({-1, -8, -1}, {1, -8, -1}, {0, -8, 1});

  Features features;
  bool has_t_junction = false;
  const int surfaces = in.ConsumeIntegralInRange<int>(1, 3);
  for (int k = 0; k < surfaces; ++k) {
    const int kind = in.ConsumeIntegralInRange<int>(0, 3);
    const glm::vec3 centre = dyadic_point(in, 64, 3);
    const bool closed = kind == 1 || kind == 2;
    s.begin_mesh("surface" + std::to_string(k), closed);
    SurfaceBuilder surface(s, symmetry, closed);
    switch (kind) {
      case 0:
        closed_fan(in, surface, features, centre);
        break;
      case 1:
        bipyramid(in, surface, features, centre);
        break;
      case 2:
        tessellated_box(in, surface, features, centre);
        break;
      default:
        t_junction(in, surface, features, centre);
        has_t_junction = true;
        break;
    }
  }

  const int sample_count = in.ConsumeIntegralInRange<int>(1, 48);
  std::vector<std::size_t> through_vertices;
  for (int k = 0; k < sample_count; ++k) {
    const std::size_t f = in.ConsumeIntegralInRange<std::size_t>(0, features.points.size() - 1);
    const glm::vec3 feature = features.points[f];
    if (features.is_vertex[f]) through_vertices.push_back(std::size_t(k));
    // Beyond the feature, seen from the light: the segment from the sample to the light passes
    // through the feature (exactly for point lights: all values are dyadic with few bits).
    const float beyond = float(in.ConsumeIntegralInRange<int>(1, 16)) / 4.0f;
    glm::vec3 p =
        light.kind == ShadowLightKind::point
            ? feature + beyond * (feature - light.position)
            : glm::vec3(glm::dvec3(feature) - double(beyond) * glm::dvec3(light.direction));
    if (in.ConsumeIntegralInRange<int>(0, 3) == 0) p = ulp_jitter(in, p, 4);
    s.add_sample(p, receiver);
  }
  s.finish();
  // Embree's watertightness covers the inside of edges shared vertex to vertex; at a T-junction
  // its float test can let a ray through the crack between the rounded triangles, and a ray
  // through (or within rounding of) a vertex that several triangles share meets only rounded
  // edge functions, which can all exclude it (docs/specification.md). The runner reports both as
  // a Fail; here they are known limits of the peer, not findings.
  std::vector<KnownLimit> known_limits;
  if (has_t_junction)
    known_limits.push_back({"embree", "a float ray can slip through a T-junction's crack"});
  else if (!through_vertices.empty())
    known_limits.push_back({"embree",
                            "a float ray through a shared vertex can miss every triangle around it",
                            through_vertices});
  check_every_algorithm(s, "fuzz_watertight", known_limits);
  return 0;
}
