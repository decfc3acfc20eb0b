#pragma once
// Hard-shadow cases built by hand for the oracle and algorithm tests. Hand-picked coordinates are
// dyadic (exact in float), so "on an edge" means exactly on it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "shadowcts/case.h"
#include "shadowcts/view_samples.h"

namespace shadowcts::testing {

inline constexpr std::uint32_t ground_mesh = 0;         // receives, never casts
inline constexpr std::uint32_t blocker_mesh = 1;        // casts
inline constexpr std::uint32_t caster_ground_mesh = 2;  // a ground that also casts

struct HandBuiltCase {
  Case c;
  ViewSamples samples;
  std::uint32_t ground = 0;  // a non-caster ground triangle, receiver of samples on y = 0

  std::uint32_t add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& d,
                             std::uint32_t mesh = blocker_mesh) {
    c.triangles.push_back(Triangle{a, b, d, mesh});
    return std::uint32_t(c.triangles.size() - 1);
  }
  // A regular sample; returns its index.
  std::size_t add_sample(const glm::vec3& p, std::uint32_t receiver) {
    ViewSample s;
    s.position = p;
    s.normal = {0.0f, 1.0f, 0.0f};
    s.receiver = receiver;
    s.pixel_x = std::uint32_t(samples.samples.size());
    s.sample_class = SampleClass::regular;
    samples.samples.push_back(s);
    samples.width = std::uint32_t(samples.samples.size());
    samples.height = 1;
    return samples.samples.size() - 1;
  }
  std::size_t add_ground_sample(const glm::vec3& p) { return add_sample(p, ground); }
};

inline ShadowLight point_light(const glm::vec3& position) {
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = position;
  return light;
}

inline ShadowLight directional_light(const glm::vec3& direction) {
  ShadowLight light;
  light.kind = ShadowLightKind::directional;
  light.direction = direction;
  return light;
}

// Meshes: ground (non-caster), blockers, caster ground. One ground triangle spanning [-8, 8]^2 in
// y = 0, so the case scale is 8 unless the light is farther out. Small camera, eps_rel 2^-16.
inline HandBuiltCase make_hand_built_case(const ShadowLight& light) {
  HandBuiltCase h;
  h.c.name = "hand_built";
  h.c.source = "hand_built_case.h";
  h.c.meshes = {Mesh{"ground", false, false}, Mesh{"blockers", false, true},
                Mesh{"caster_ground", false, true}};
  h.c.light = light;
  h.c.camera.position = {0.0f, 0.5f, 0.5f};
  h.c.camera.target = {0.0f, 0.0f, 0.0f};
  h.ground = h.add_triangle({-8, 0, -8}, {8, 0, -8}, {0, 0, 8}, ground_mesh);
  return h;
}

// A pyramid without base: four triangles around the apex (0, 3, 0), rim (+-1, 2, +-1). Every
// edge from the apex is shared by two of them: a closed fan around the apex.
inline void add_pyramid_fan(HandBuiltCase& h) {
  const glm::vec3 apex{0, 3, 0};
  const glm::vec3 rim[4] = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};
  for (int i = 0; i < 4; ++i) h.add_triangle(apex, rim[i], rim[(i + 1) % 4]);
}

// fuzz_watertight-531e78eca2acc5e5: a T-junction (a vertex of one caster in the middle of
// another's edge) with a shadow segment exactly through the covered edge piece, so the sample is
// robustly shadowed. A watertight test that rounds each vertex on its own opens a crack there:
// the float test misses both triangles. The sample has no receiver (the fuzz case named a ground
// far below, whose plane would put both casters off the light's side): the receiver half-space
// rule is void.
struct CrackCase {
  HandBuiltCase h;
  std::size_t sample = 0;
};
inline CrackCase t_junction_crack() {
  CrackCase crack{make_hand_built_case(point_light({24.0f, -24.0f, -15.0f}))};
  HandBuiltCase& h = crack.h;
  h.c.triangles.clear();
  h.ground = h.add_triangle({-1, -8, -1}, {1, -8, -1}, {0, -8, 1}, ground_mesh);
  const glm::vec3 a(-0x1.3p-1f, 0x1.cp+2f, 0x1.c8p+1f), b(0x1p-1f, 0x1.fp+2f, 0x1.5p+1f),
      c(-0x1.4p-1f, 0x1.c4p+2f, 0x1.ap+0f), on_ac(-0x1.32p-1f, 0x1.c08p+2f, 0x1.a9p+1f),
      e(-0x1.8p+0f, 0x1.dp+2f, 0x1.5p+1f);
  h.add_triangle(a, b, c);
  h.add_triangle(on_ac, c, e);
  h.c.camera.position = {0x1.6745fp+3f, -0x1.374eacp+3f, -0x1.81776cp+2f};
  crack.sample = h.add_sample({-0x1.5d3cp+5f, 0x1.ea58p+5f, 0x1.15b8p+5f}, no_receiver);
  h.samples.samples[crack.sample].normal = {0, -1, 0};
  return crack;
}

// The case with every position (triangles, a point light, camera, samples) multiplied by 2^k:
// exact in float away from denormals and overflow. Directions stay.
inline HandBuiltCase scaled_by_power_of_two(HandBuiltCase h, int k) {
  const auto scale = [k](glm::vec3& v) {
    v = {std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
  };
  for (Triangle& t : h.c.triangles) {
    scale(t.v0);
    scale(t.v1);
    scale(t.v2);
  }
  if (h.c.light && h.c.light->kind == ShadowLightKind::point) scale(h.c.light->position);
  scale(h.c.camera.position);
  scale(h.c.camera.target);
  for (ViewSample& s : h.samples.samples) scale(s.position);
  return h;
}

// A random scene: a caster ground of 2 x grid x grid triangles on [-8, 8]^2 (y = 0), `blockers`
// random triangles of size ~`size` above it, and `sample_count` samples: half on the ground
// (receiver: the ground triangle under them), a quarter on blockers (receiver: that blocker,
// position rounded to float), a quarter at the shadow-boundary images of blocker edge midpoints
// and, with vertex_images, vertices on the ground (where the band matters).
inline HandBuiltCase make_random_case(std::uint64_t seed, int grid, int blockers, float size,
                                      int sample_count, const ShadowLight& light,
                                      bool vertex_images = true) {
  HandBuiltCase h = make_hand_built_case(light);
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float cell = 16.0f / float(grid);
  const std::uint32_t first_ground = std::uint32_t(h.c.triangles.size());
  for (int i = 0; i < grid; ++i)
    for (int k = 0; k < grid; ++k) {
      const float x0 = -8.0f + cell * float(i), z0 = -8.0f + cell * float(k);
      const glm::vec3 a{x0, 0, z0}, b{x0 + cell, 0, z0}, d{x0 + cell, 0, z0 + cell},
          e{x0, 0, z0 + cell};
      h.add_triangle(a, b, d, caster_ground_mesh);
      h.add_triangle(a, d, e, caster_ground_mesh);
    }
  const std::uint32_t first_blocker = std::uint32_t(h.c.triangles.size());
  for (int i = 0; i < blockers; ++i) {
    const glm::vec3 centre{-6.0f + 12.0f * unit(random), 0.5f + 3.5f * unit(random),
                           -6.0f + 12.0f * unit(random)};
    auto corner = [&] {
      return centre +
             size * glm::vec3(unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f);
    };
    h.add_triangle(corner(), corner(), corner());
  }
  auto ground_receiver = [&](float x, float z) {
    const int i = std::min(grid - 1, int((x + 8.0f) / cell));
    const int k = std::min(grid - 1, int((z + 8.0f) / cell));
    const float fx = x - (-8.0f + cell * float(i)), fz = z - (-8.0f + cell * float(k));
    return first_ground + std::uint32_t(2 * (i * grid + k) + (fx >= fz ? 0 : 1));
  };
  auto light_direction_at = [&](const glm::vec3& p) {
    return light.kind == ShadowLightKind::point ? light.position - p : light.direction;
  };
  for (int s = 0; s < sample_count; ++s) {
    const int kind = s % 4;
    if (kind <= 1) {
      const float x = -7.0f + 14.0f * unit(random), z = -7.0f + 14.0f * unit(random);
      h.add_sample({x, 0, z}, ground_receiver(x, z));
    } else if (kind == 2) {
      const std::uint32_t t = first_blocker + std::uint32_t(random() % std::uint64_t(blockers));
      const Triangle& tri = h.c.triangles[t];
      float u = unit(random), v = unit(random);
      if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
      h.add_sample(tri.v0 + u * (tri.v1 - tri.v0) + v * (tri.v2 - tri.v0), t);
    } else {
      // Project a blocker vertex or edge midpoint along the light onto the ground.
      const Triangle& tri =
          h.c.triangles[first_blocker + std::uint32_t(random() % std::uint64_t(blockers))];
      const bool vertex = (random() % 2) && vertex_images;
      const glm::vec3 feature = vertex ? tri.v0 : 0.5f * (tri.v1 + tri.v2);
      const glm::vec3 towards = light_direction_at(feature);
      if (!(towards.y > 0.0f)) continue;
      const glm::vec3 p = feature - (feature.y / towards.y) * towards;
      if (std::fabs(p.x) > 7.5f || std::fabs(p.z) > 7.5f) continue;
      h.add_sample({p.x, 0.0f, p.z}, ground_receiver(p.x, p.z));
    }
  }
  return h;
}

}  // namespace shadowcts::testing
