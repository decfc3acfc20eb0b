#include "reference/softtile/softtile_tile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/geometric.hpp>

#include "shadowcts/geometry/disk_reach.h"

namespace shadowcts::softtile {
namespace {

// The bound of a tile's relevant samples. The samples lie in the tile's slice of the view frustum
// between its min and max depth; seen from the eye along the tile's mean direction c, a sample at
// distance t along c lies within k t of the axis (k the largest ratio over the tile). A tapered
// capsule from t_min to t_max with radii k t_min, k t_max contains them all; when the depth range
// is short against the radius, one sphere around them is tighter and is used instead.
TileBound tile_bound(const glm::dvec3& eye, const std::vector<glm::dvec3>& positions) {
  glm::dvec3 direction(0.0), lo(positions[0]), hi(positions[0]);
  for (const glm::dvec3& p : positions) {
    direction += glm::normalize(p - eye);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double scale = glm::length(eye) + std::max(glm::length(lo), glm::length(hi));
  const double margin = 1e-6 * scale;
  TileBound sphere;
  sphere.a = 0.5 * (lo + hi);
  for (const glm::dvec3& p : positions)
    sphere.radius_a = std::max(sphere.radius_a, glm::length(p - sphere.a));
  sphere.radius_a = sphere.radius_a * (1.0 + 1e-9) + margin;
  if (positions.size() == 1 || !(glm::length(direction) > 0.0)) return sphere;
  direction = glm::normalize(direction);
  double t_min = std::numeric_limits<double>::max(), t_max = 0.0, k = 0.0;
  for (const glm::dvec3& p : positions) {
    const double t = glm::dot(p - eye, direction);
    if (!(t > 0.0)) return sphere;
    t_min = std::min(t_min, t);
    t_max = std::max(t_max, t);
    k = std::max(k, glm::length(p - eye - t * direction) / t);
  }
  TileBound capsule;
  capsule.capsule = true;
  capsule.a = eye + t_min * direction;
  capsule.b = eye + t_max * direction;
  capsule.radius_a = k * t_min * (1.0 + 1e-9) + margin;
  capsule.radius_b = k * t_max * (1.0 + 1e-9) + margin;
  return t_max - t_min > 2.0 * capsule.radius_b ? capsule : sphere;
}

}  // namespace

float disk_inverse_scale(const Gathered& gathered, const Variant& variant) {
  return float(1.0 / (variant.sine_normalization ? std::sin(gathered.sun.angular_radius)
                                                 : std::tan(gathered.sun.angular_radius)));
}

double rotation_angle(std::uint64_t seed, std::uint32_t x, std::uint32_t y) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ull ^ (std::uint64_t(x) << 32 | y);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return 2.0 * std::numbers::pi * double(z >> 11) * 0x1p-53;
}

bool prepare_tile(const Case& c, const ViewSamples& samples, const Gathered& gathered,
                  const Variant& variant, float inverse_scale, std::size_t index, Tile& tile) {
  if (!prepare_tile_pixels(c, samples, gathered, variant, inverse_scale, index, tile)) return false;
  cull_candidates(gathered, tile);
  return true;
}

bool prepare_tile_pixels(const Case& c, const ViewSamples& samples, const Gathered& gathered,
                         const Variant& variant, float inverse_scale, std::size_t index,
                         Tile& tile) {
  const std::uint32_t tiles_x = tiles_across(samples.width);
  const std::uint32_t x0 = std::uint32_t(index % tiles_x) * tile_size;
  const std::uint32_t y0 = std::uint32_t(index / tiles_x) * tile_size;
  tile.pixels.clear();
  tile.candidates.clear();
  tile.fragments.clear();
  // Relevant pixels: regular samples (facing the light, not sky).
  std::vector<glm::dvec3> positions;
  for (std::uint32_t y = y0; y < std::min(y0 + tile_size, samples.height); ++y)
    for (std::uint32_t x = x0; x < std::min(x0 + tile_size, samples.width); ++x) {
      const std::size_t i = std::size_t(y) * samples.width + x;
      if (samples.samples[i].sample_class != SampleClass::regular) continue;
      tile.pixels.push_back(i);
      positions.emplace_back(samples.samples[i].position);
    }
  if (tile.pixels.empty()) return false;  // early exit
  tile.bound = tile_bound(glm::dvec3(c.camera.position), positions);
  tile.fragments.resize(tile.pixels.size());
  for (std::size_t j = 0; j < tile.pixels.size(); ++j) {
    const ViewSample& s = samples.samples[tile.pixels[j]];
    tile.fragments[j].position = gathered.light_space.to_light(s.position);
    tile.fragments[j].inverse_scale = inverse_scale;
    tile.fragments[j].reach_per_height = disk_reach_per_height(inverse_scale);
    if (variant.rotate) {
      const double angle = rotation_angle(c.parameters.seed, s.pixel_x, s.pixel_y);
      tile.fragments[j].cos_rotation = float(std::cos(angle));
      tile.fragments[j].sin_rotation = float(std::sin(angle));
    }
  }
  return true;
}

void cull_candidates(const Gathered& gathered, Tile& tile) {
  tile.candidates.clear();
  // Cull cluster cones, then the cones of the surviving clusters' triangles.
  for (const GatheredCluster& cluster : gathered.clusters) {
    if (!may_shadow(gathered.sun, cluster.cone, tile.bound)) continue;
    for (std::uint32_t k = cluster.first; k < cluster.first + cluster.count; ++k)
      if (may_shadow(gathered.sun, gathered.triangles[k].cone, tile.bound))
        tile.candidates.push_back(k);
  }
}

}  // namespace shadowcts::softtile
