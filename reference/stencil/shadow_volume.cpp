#include "reference/stencil/shadow_volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace shadowcts::stencil {
namespace {

// Distance from p to triangle abc (closest-point regions, Ericson, Real-Time Collision Detection
// 5.1.5), in double: it only has to be a good estimate, the extrusion keeps a factor 2 margin.
double point_triangle_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                               const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return glm::length(p - a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return glm::length(p - b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return glm::length(p - (a + (d1 / (d1 - d3)) * ab));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return glm::length(p - c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return glm::length(p - (a + (d2 / (d2 - d6)) * ac));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return glm::length(p - (b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b)));
  const double denominator = 1.0 / (va + vb + vc);
  return glm::length(p - (a + ab * (vb * denominator) + ac * (vc * denominator)));
}

}  // namespace

std::array<glm::dvec3, 3> dark_cap_base(const LightCap& cap) {
  return {cap.v[0], cap.v[2], cap.v[1]};
}

double light_to_caps_distance(const Occluders& occluders, const glm::dvec3& light) {
  double d = std::numeric_limits<double>::infinity();
  for (const LightCap& cap : occluders.caps)
    d = std::min(d, point_triangle_distance(light, cap.v[0], cap.v[1], cap.v[2]));
  return d;
}

ShadowVolumes build_shadow_volumes(const Occluders& occluders, const HardShadowLight& light,
                                   const glm::dvec3& eye, const ViewSamples& samples) {
  glm::dvec3 lo = eye, hi = eye;
  double reach = light.directional ? 0.0 : glm::length(eye - light.position);
  for (const ViewSample& s : samples.samples) {
    if (s.sample_class != SampleClass::regular) continue;
    const glm::dvec3 p(s.position);
    lo = glm::min(lo, p), hi = glm::max(hi, p);
    if (!light.directional) reach = std::max(reach, glm::length(p - light.position));
  }
  double scale = 1.0, shift = 0.0;
  glm::dvec3 away(0.0);
  if (light.directional) {
    // A point q is in the shadow of cap point x when q = x + t * away, t >= 0; for the eye and
    // the samples t is at most their deepest position along `away` minus the shallowest cap.
    away = -glm::normalize(light.direction);
    double deepest = glm::dot(eye, away), shallowest = std::numeric_limits<double>::infinity();
    for (const ViewSample& s : samples.samples)
      if (s.sample_class == SampleClass::regular)
        deepest = std::max(deepest, glm::dot(glm::dvec3(s.position), away));
    for (const LightCap& cap : occluders.caps)
      for (const glm::dvec3& v : cap.v) {
        shallowest = std::min(shallowest, glm::dot(v, away));
        lo = glm::min(lo, v), hi = glm::max(hi, v);
      }
    // Factor 2 and a floor of 1e-3 of the scene's diagonal: far beyond any rounding of the dots.
    shift = std::max(2.0 * (deepest - shallowest), 1e-3 * glm::length(hi - lo) + 1e-30);
  } else {
    scale = std::max(2.0, 2.0 * reach / light_to_caps_distance(occluders, light.position));
  }
  ShadowVolumes volumes;
  volumes.extrusion.directional = light.directional;
  volumes.extrusion.light = light.position;
  volumes.extrusion.scale = scale;
  volumes.extrusion.shift = shift;
  volumes.extrusion.away = away;
  const Extrusion& extrude = volumes.extrusion;

  volumes.silhouette_edges = occluders.silhouette.size();
  volumes.faces.reserve(2 * occluders.caps.size() + occluders.silhouette.size());
  for (const LightCap& cap : occluders.caps) {
    VolumeFace front;
    front.kind = FaceKind::light_cap;
    front.triangle = cap.triangle;
    front.v[0] = cap.v[0], front.v[1] = cap.v[1], front.v[2] = cap.v[2];
    volumes.faces.push_back(front);
  }
  for (const SilhouetteEdge& e : occluders.silhouette) {
    // The cap runs from -> to; the quad runs to -> from, down to the extruded copies.
    VolumeFace side;
    side.kind = FaceKind::side_quad;
    side.v[0] = e.to, side.v[1] = e.from, side.v[2] = extrude(e.from), side.v[3] = extrude(e.to);
    volumes.faces.push_back(side);
  }
  for (const LightCap& cap : occluders.caps) {
    VolumeFace dark;
    dark.kind = FaceKind::dark_cap;
    dark.triangle = cap.triangle;
    const std::array<glm::dvec3, 3> base = dark_cap_base(cap);
    for (int k = 0; k < 3; ++k) dark.v[k] = extrude(base[std::size_t(k)]);
    volumes.faces.push_back(dark);
  }
  return volumes;
}

std::array<VolumeFace, 5> own_volume_faces(const LightCap& cap, const Extrusion& extrude) {
  std::array<VolumeFace, 5> faces;
  faces[0].kind = FaceKind::light_cap;
  faces[0].triangle = cap.triangle;
  faces[0].v[0] = cap.v[0], faces[0].v[1] = cap.v[1], faces[0].v[2] = cap.v[2];
  for (int k = 0; k < 3; ++k) {
    // As build_shadow_volumes does for a silhouette edge from -> to of a cap.
    const glm::dvec3& from = cap.v[k];
    const glm::dvec3& to = cap.v[(k + 1) % 3];
    VolumeFace& side = faces[std::size_t(1 + k)];
    side.kind = FaceKind::side_quad;
    side.v[0] = to, side.v[1] = from, side.v[2] = extrude(from), side.v[3] = extrude(to);
  }
  faces[4].kind = FaceKind::dark_cap;
  faces[4].triangle = cap.triangle;
  const std::array<glm::dvec3, 3> base = dark_cap_base(cap);
  for (int k = 0; k < 3; ++k) faces[4].v[k] = extrude(base[std::size_t(k)]);
  return faces;
}

}  // namespace shadowcts::stencil
