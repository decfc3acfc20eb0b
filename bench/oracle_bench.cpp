// Both hard-shadow oracles, band included, on a synthetic case: a caster ground grid with random
// blocker triangles above it, 1920 x 1080 view samples cast onto the ground analytically (the
// samples ignore the blockers in front of the ground: they are shadow queries, not a render).
// The goal: the exact oracle costs at most 3x the Embree oracle.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <random>

#include <glm/geometric.hpp>

#include <tbb/parallel_for.h>

#include "oracles/embree_shadow_rays.h"
#include "shadowcts/case.h"
#include "shadowcts/hard_shadow_oracle.h"
#include "shadowcts/view_samples.h"

namespace shadowcts {
namespace {

constexpr int grid_cells = 100;  // per side: 2 x 100 x 100 ground triangles on [-50, 50]^2
constexpr float ground_half = 50.0f;

struct BenchCase {
  Case c;
  ViewSamples samples;
};

BenchCase make_bench_case(std::size_t triangle_count, float blocker_size) {
  BenchCase b;
  Case& c = b.c;
  c.name = "bench.ground_blockers." + std::to_string(triangle_count);
  c.source = "oracle_bench.cpp";
  c.meshes = {Mesh{"ground", false, true}, Mesh{"blockers", false, true}};
  ShadowLight light;
  light.position = {10.0f, 100.0f, 5.0f};
  c.light = light;
  // Looking steeply down: every pixel's ray hits the ground grid.
  c.camera.position = {0.0f, 60.0f, 8.0f};
  c.camera.target = {0.0f, 0.0f, 0.0f};
  c.camera.width = 1920;
  c.camera.height = 1080;
  c.camera.vertical_fov_degrees = 40.0f;

  const float cell = 2.0f * ground_half / grid_cells;
  for (int i = 0; i < grid_cells; ++i)
    for (int k = 0; k < grid_cells; ++k) {
      const float x0 = -ground_half + cell * float(i), z0 = -ground_half + cell * float(k);
      const glm::vec3 a{x0, 0, z0}, p{x0 + cell, 0, z0}, q{x0 + cell, 0, z0 + cell},
          d{x0, 0, z0 + cell};
      c.triangles.push_back({a, p, q, 0});
      c.triangles.push_back({a, q, d, 0});
    }
  std::mt19937_64 random(triangle_count);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  while (c.triangles.size() < triangle_count) {
    const glm::vec3 centre{-45.0f + 90.0f * unit(random), 1.0f + 19.0f * unit(random),
                           -45.0f + 90.0f * unit(random)};
    auto corner = [&] {
      return centre + blocker_size *
                          glm::vec3(unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f);
    };
    c.triangles.push_back({corner(), corner(), corner(), 1});
  }

  // Pinhole camera, rays through pixel centres, hit points on y = 0.
  const Camera& cam = c.camera;
  const glm::dvec3 eye(cam.position);
  const glm::dvec3 forward = glm::normalize(glm::dvec3(cam.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(cam.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double half_height = std::tan(0.5 * double(cam.vertical_fov_degrees) * M_PI / 180.0);
  const double half_width = half_height * double(cam.width) / double(cam.height);
  b.samples.width = cam.width;
  b.samples.height = cam.height;
  b.samples.samples.resize(std::size_t(cam.width) * cam.height);
  for (std::uint32_t y = 0; y < cam.height; ++y)
    for (std::uint32_t x = 0; x < cam.width; ++x) {
      ViewSample& s = b.samples.samples[std::size_t(y) * cam.width + x];
      s.pixel_x = x;
      s.pixel_y = y;
      const double u = (2.0 * (x + 0.5) / cam.width - 1.0) * half_width;
      const double v = (1.0 - 2.0 * (y + 0.5) / cam.height) * half_height;
      const glm::dvec3 direction = forward + u * right + v * up;
      if (!(direction.y < 0.0)) continue;  // sky
      const glm::dvec3 hit = eye - (eye.y / direction.y) * direction;
      const glm::vec3 p(float(hit.x), 0.0f, float(hit.z));
      if (std::fabs(p.x) >= ground_half || std::fabs(p.z) >= ground_half) continue;  // sky
      const int i = std::min(grid_cells - 1, int((p.x + ground_half) / cell));
      const int k = std::min(grid_cells - 1, int((p.z + ground_half) / cell));
      const float fx = p.x - (-ground_half + cell * float(i));
      const float fz = p.z - (-ground_half + cell * float(k));
      s.position = p;
      s.normal = {0.0f, 1.0f, 0.0f};
      s.receiver = std::uint32_t(2 * (i * grid_cells + k) + (fx >= fz ? 0 : 1));
      s.sample_class = SampleClass::regular;
    }
  return b;
}

const BenchCase& bench_case(std::size_t triangles) {
  static std::map<std::size_t, BenchCase> cases;
  auto it = cases.find(triangles);
  if (it == cases.end()) {
    // Blocker sizes keep roughly half of the ground in shadow at both sizes.
    const float size = triangles <= 100'000 ? 0.6f : 0.18f;
    it = cases.emplace(triangles, make_bench_case(triangles, size)).first;
  }
  return it->second;
}

void report(benchmark::State& state, const BenchCase& b, const HardShadowTruth& truth) {
  std::size_t regular = 0, shadowed = 0, ambiguous = 0;
  for (std::size_t i = 0; i < truth.band.size(); ++i) {
    if (truth.band[i] == BandClass::not_compared) continue;
    ++regular;
    shadowed += truth.shadowed[i];
    ambiguous += truth.band[i] == BandClass::ambiguous;
  }
  state.counters["triangles"] = double(b.c.triangles.size());
  state.counters["samples"] = double(regular);
  state.counters["shadowed"] = double(shadowed) / double(regular);
  state.counters["ambiguous"] = double(ambiguous) / double(regular);
}

void BM_ExactHardShadowOracle(benchmark::State& state) {
  const BenchCase& b = bench_case(std::size_t(state.range(0)));
  HardShadowTruth truth;
  for (auto _ : state) truth = exact_hard_shadow_oracle(b.c, b.samples);
  report(state, b, truth);
}

void BM_EmbreeHardShadowOracle(benchmark::State& state) {
  const BenchCase& b = bench_case(std::size_t(state.range(0)));
  HardShadowTruth truth;
  for (auto _ : state) truth = embree_hard_shadow_oracle(b.c, b.samples);
  report(state, b, truth);
}

void trace_one_ray_per_sample(const EmbreeShadowRays& rays, const BenchCase& b,
                              std::vector<std::uint8_t>& shadowed) {
  tbb::parallel_for(std::size_t(0), shadowed.size(), [&](std::size_t i) {
    const ViewSample& s = b.samples.samples[i];
    shadowed[i] = rays.occluded(s.position, s.receiver);
  });
}

// One Embree occlusion ray per sample, no band: the plain answer a user's renderer would trace.
// The oracles above do much more (the band's moves), so this is the floor they are measured
// against, not a peer.
void BM_EmbreeSingleRayPerSample(benchmark::State& state) {
  const BenchCase& b = bench_case(std::size_t(state.range(0)));
  const EmbreeShadowRays rays(b.c);
  std::vector<std::uint8_t> shadowed(b.samples.samples.size());
  for (auto _ : state) {
    trace_one_ray_per_sample(rays, b, shadowed);
    benchmark::DoNotOptimize(shadowed.data());
  }
  state.counters["triangles"] = double(b.c.triangles.size());
}

// The same rays with the scene built inside the timed loop: build + query, what the exact oracle's
// time (its own tree and closure included) is measured against.
void BM_EmbreeBuildAndSingleRayPerSample(benchmark::State& state) {
  const BenchCase& b = bench_case(std::size_t(state.range(0)));
  std::vector<std::uint8_t> shadowed(b.samples.samples.size());
  for (auto _ : state) {
    const EmbreeShadowRays rays(b.c);
    trace_one_ray_per_sample(rays, b, shadowed);
    benchmark::DoNotOptimize(shadowed.data());
  }
  state.counters["triangles"] = double(b.c.triangles.size());
}

BENCHMARK(BM_ExactHardShadowOracle)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_EmbreeHardShadowOracle)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

BENCHMARK(BM_EmbreeSingleRayPerSample)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

BENCHMARK(BM_EmbreeBuildAndSingleRayPerSample)
    ->Arg(100'000)
    ->Arg(1'000'000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
}  // namespace shadowcts

BENCHMARK_MAIN();
