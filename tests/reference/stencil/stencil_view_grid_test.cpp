// The stencil baseline's view grid (view_grid.h, with crossing_reach.h's depth bounds) must list,
// for every sample, every face whose crossing count is non-zero: the count over its candidates is
// then the count over all faces. Checked against brute force (count_crossings over every face) on
// random scenes on a coarse coordinate grid (exact ties: samples on caster vertices and edges, so
// on side-quad planes; the eye in cap planes; casters straddling the eye's plane and next to the
// eye; a T-junction), and on small fixtures.
#include "reference/stencil/view_grid.h"

#include <array>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "reference/light_on_caster.h"
#include "reference/stencil/crossing_reach.h"
#include "reference/stencil/shadow_volume.h"
#include "reference/stencil/silhouette.h"
#include "reference/stencil/volume_counting.h"
#include "shadowcts/fixtures.h"
#include "shadowcts/hard_shadow_inputs.h"

namespace shadowcts {
namespace {

using namespace stencil;

struct Coverage {
  std::uint64_t counted = 0;     // (sample, face) pairs with a non-zero count
  std::uint64_t missed = 0;      // of those, not among the grid's candidates
  std::uint64_t candidates = 0;  // candidates listed, over all samples
  std::uint64_t pairs = 0;       // samples x faces
  std::string first_miss;
};

Coverage grid_coverage(const Case& c, const ViewSamples& samples, CountingMode mode) {
  const HardShadowLight light = hard_shadow_light(c);
  const glm::dvec3 eye(c.camera.position);
  const Occluders occluders = find_occluders(c, light, casters_containing_light(c));
  const ShadowVolumes volumes = build_shadow_volumes(occluders, light, eye, samples);
  std::vector<VolumeFace> faces;
  for (const VolumeFace& f : volumes.faces)
    if (mode == CountingMode::z_fail || f.kind != FaceKind::dark_cap) faces.push_back(f);
  std::vector<FaceEyeSides> sides;
  std::vector<CrossingReach> reaches;
  const double reach = sample_reach(eye, samples);
  for (const VolumeFace& f : faces) {
    sides.push_back(eye_sides(f, eye, light));
    reaches.push_back(crossing_reach(f, sides.back(), mode, volumes.extrusion, light, eye, reach));
  }
  // Each dark cap's light-cap vertices (count_crossings' dark_base), once per face.
  std::vector<std::array<glm::dvec3, 3>> bases(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (faces[f].kind == FaceKind::dark_cap)
      for (const LightCap& cap : occluders.caps)
        if (cap.triangle == faces[f].triangle) bases[f] = dark_cap_base(cap);
  const ViewGrid grid(c.camera, samples, faces, reaches, mode);
  Coverage coverage;
  std::vector<char> listed(faces.size());
  for (std::size_t i = 0; i < samples.samples.size(); ++i) {
    const ViewSample& s = samples.samples[i];
    if (s.sample_class != SampleClass::regular) continue;
    const glm::dvec3 p(s.position);
    std::fill(listed.begin(), listed.end(), 0);
    grid.for_each_candidate(p, [&](std::uint32_t f) {
      listed[f] = 1;
      ++coverage.candidates;
    });
    coverage.pairs += faces.size();
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const std::array<glm::dvec3, 3>* base =
          faces[f].kind == FaceKind::dark_cap ? &bases[f] : nullptr;
      if (count_crossings(faces[f], sides[f], mode, eye, p, light, volumes.extrusion, base) == 0)
        continue;
      ++coverage.counted;
      if (listed[f]) continue;
      if (coverage.missed++ == 0)
        coverage.first_miss = "sample " + std::to_string(i) + " face " + std::to_string(f) +
                              " kind " + std::to_string(int(faces[f].kind));
    }
  }
  return coverage;
}

void expect_covered(const Case& c, const ViewSamples& samples, const std::string& what,
                    Coverage* total = nullptr) {
  for (const CountingMode mode : {CountingMode::z_fail, CountingMode::z_pass}) {
    const Coverage coverage = grid_coverage(c, samples, mode);
    const char* name = mode == CountingMode::z_fail ? "zfail" : "zpass";
    EXPECT_EQ(coverage.missed, 0u) << what << " " << name << ": " << coverage.first_miss;
    if (total) {
      total->counted += coverage.counted;
      total->candidates += coverage.candidates;
      total->pairs += coverage.pairs;
    }
  }
}

ViewSample regular_sample(const glm::vec3& position) {
  ViewSample s;
  s.position = position;
  s.normal = {0.0f, 1.0f, 0.0f};
  s.sample_class = SampleClass::regular;
  return s;
}

// Coordinates on a grid of quarters: ties between faces, lines and points are frequent.
float on_grid(std::mt19937& rng, int lo, int hi) {
  return float(std::uniform_int_distribution<int>(4 * lo, 4 * hi)(rng)) / 4.0f;
}

glm::vec3 grid_point(std::mt19937& rng, int lo, int hi) {
  return {on_grid(rng, lo, hi), on_grid(rng, lo, hi), on_grid(rng, lo, hi)};
}

Case random_case(std::uint32_t seed, bool directional) {
  std::mt19937 rng(seed);
  Case c;
  c.name = "view_grid_random_" + std::to_string(seed);
  ShadowLight light;
  if (directional) {
    light.kind = ShadowLightKind::directional;
    light.direction = {on_grid(rng, -1, 1), 1.0f + on_grid(rng, 0, 1), on_grid(rng, -1, 1)};
  } else {
    light.kind = ShadowLightKind::point;
    light.position = {on_grid(rng, -3, 3), on_grid(rng, 5, 8), on_grid(rng, -3, 3)};
  }
  c.light = light;
  c.camera.position = grid_point(rng, -4, 4);
  c.camera.target = grid_point(rng, -2, 2);
  if (c.camera.target == c.camera.position) c.camera.target.x += 1.0f;
  // Open triangles, some in the eye's horizontal plane (caps whose plane holds the eye), some
  // around it (straddling its view plane, next to it).
  c.meshes.push_back(Mesh{"open", false, true});
  for (int k = 0; k < 10; ++k) {
    Triangle t{grid_point(rng, -4, 4), grid_point(rng, -4, 4), grid_point(rng, -4, 4), 0};
    if (k < 2) t.v0.y = t.v1.y = t.v2.y = c.camera.position.y;
    if (k == 2) t.v0 = c.camera.position + glm::vec3(0.25f, 0.0f, 0.0f);
    c.triangles.push_back(t);
  }
  // A T-junction: a vertex of one triangle in the middle of the other's edge.
  const glm::vec3 a = grid_point(rng, -3, 3), b = a + glm::vec3(2.0f, 0.0f, 0.5f);
  const glm::vec3 mid = 0.5f * (a + b), apex = a + glm::vec3(0.5f, 0.75f, 1.0f);
  c.triangles.push_back({a, b, apex, 0});
  c.triangles.push_back(
      {mid, a - glm::vec3(0.0f, 0.5f, 1.0f), a + glm::vec3(1.5f, -0.5f, -1.0f), 0});
  // A closed box.
  c.meshes.push_back(Mesh{"box", true, true});
  const glm::vec3 lo = grid_point(rng, -3, 1), hi = lo + glm::vec3(1.0f, 0.5f, 1.5f);
  const glm::vec3 centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  for (int axis = 0; axis < 3; ++axis)
    for (const float sign : {1.0f, -1.0f}) {
      glm::vec3 u(0.0f), v(0.0f), n(0.0f);
      n[axis] = sign * half[axis];
      u[(axis + 1) % 3] = half[(axis + 1) % 3];
      v[(axis + 2) % 3] = half[(axis + 2) % 3];
      if (sign < 0) std::swap(u, v);
      const glm::vec3 p00 = centre + n - u - v, p10 = centre + n + u - v, p11 = centre + n + u + v,
                      p01 = centre + n - u + v;
      c.triangles.push_back({p00, p10, p11, 1});
      c.triangles.push_back({p00, p11, p01, 1});
    }
  return c;
}

ViewSamples random_samples(const Case& c, std::uint32_t seed) {
  std::mt19937 rng(seed ^ 0x5EEDu);
  ViewSamples samples;
  // Caster vertices and edge midpoints (on side-quad planes), then grid points anywhere.
  for (const Triangle& t : c.triangles) {
    for (const glm::vec3& v : {t.v0, t.v1, t.v2}) samples.samples.push_back(regular_sample(v));
    samples.samples.push_back(regular_sample(0.5f * (t.v0 + t.v1)));
  }
  for (int k = 0; k < 150; ++k) samples.samples.push_back(regular_sample(grid_point(rng, -6, 6)));
  samples.width = std::uint32_t(samples.samples.size());
  samples.height = 1;
  for (std::size_t i = 0; i < samples.samples.size(); ++i)
    samples.samples[i].pixel_x = std::uint32_t(i);
  return samples;
}

TEST(StencilViewGrid, ListsEveryCountedFaceOnRandomScenesWithTies) {
  Coverage total;
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    for (const bool directional : {false, true}) {
      const Case c = random_case(seed, directional);
      const ViewSamples samples = random_samples(c, seed);
      expect_covered(c, samples, c.name + (directional ? " directional" : " point"), &total);
    }
  }
  // The check means something: faces were counted, and the grid left most pairs out.
  EXPECT_GT(total.counted, 1000u);
  EXPECT_LT(total.candidates, total.pairs);
}

// The fuzz reproducer of a T-junction (stencil_test.cpp): a sample exactly on the exact plane of
// two side quads whose rounded triangles it lies on different sides of.
TEST(StencilViewGrid, ListsTheSideQuadsOfASampleOnTheirExactPlane) {
  Case c;
  ShadowLight light;
  light.kind = ShadowLightKind::point;
  light.position = {24.0f, -24.0f, -15.0f};
  c.light = light;
  c.camera.position = {10.23654556274414f, -10.883883476257324f, -5.7293500900268555f};
  c.camera.target = {-62.20115661621094f, 58.1468505859375f, 43.0625114440918f};
  c.meshes = {Mesh{"part0", false, false}, Mesh{"part1", false, true}};
  c.triangles = {{{-1, 128, -1}, {1, 128, -1}, {0, 128, 1}, 0},
                 {{-0x1.3p-1f, 0x1.cp+2f, 0x1.c8p+1f},
                  {0x1p-1f, 0x1.fp+2f, 0x1.5p+1f},
                  {-0x1.4p-1f, 0x1.c4p+2f, 0x1.ap+0f},
                  1},
                 {{-0x1.32p-1f, 0x1.c08p+2f, 0x1.a9p+1f},
                  {-0x1.4p-1f, 0x1.c4p+2f, 0x1.ap+0f},
                  {-0x1.8p+0f, 0x1.dp+2f, 0x1.5p+1f},
                  1}};
  ViewSamples samples;
  samples.samples = {regular_sample({-0x1.9dap+3f, 0x1.692p+4f, 0x1.554p+3f}),
                     regular_sample({-0x1.f1cp+6f, 0x1.57f8p+6f, 0x1.5398p+6f})};
  samples.width = 2;
  samples.height = 1;
  expect_covered(c, samples, "t_junction");
}

TEST(StencilViewGrid, ListsEveryCountedFaceOnSmallFixtures) {
  for (const char* name : {"gate_house.2k", "ground_blockers.2k", "closed_shapes.2k", "foliage.2k",
                           "shared_edges.2k"}) {
    Case c = hard_shadow_view(make_fixture(name));
    if (!c.light) continue;
    c.camera.width = 64;
    c.camera.height = 40;
    expect_covered(c, generate_view_samples(c), std::string(name));
  }
}

}  // namespace
}  // namespace shadowcts
